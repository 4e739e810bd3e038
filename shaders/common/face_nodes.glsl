// The node indices of a face: FacesBuf (GLC_BIND_FACES) declared once for every collision kernel
// that reads faces, with its one accessor.
layout(std430, binding = GLC_BIND_FACES) readonly buffer FacesBuf { uint g_faceIndices[]; };

uvec3 faceNodes(uint face) {
    return uvec3(g_faceIndices[3u * face], g_faceIndices[3u * face + 1u], g_faceIndices[3u * face + 2u]);
}
