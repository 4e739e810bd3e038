// Radial view-based culling over real and ghost triangles (docs/culling.md, "Ghost triangles"):
// the classified faces are the real faces [0, u_realFaceCount), then the ghost faces that close
// the observed surfaces' holes; the nodes are the real nodes [0, u_nodeCount), then the ghost nodes
// (each the mean of its loop's nodes, written by RadialGhostNodes at both ends of the substep).
// Ghosts are only ever classified and counted by the observer check (RadialWinding); they never collide.
// Include after common/layout.glsl and common/face_nodes.glsl, with the real start and end
// positions declared as g_start[] and g_end[].
#ifndef GLC_RADIAL_GHOST_GLSL
#define GLC_RADIAL_GHOST_GLSL

layout(std430, binding = GLC_BIND_RADIAL_GHOST_FACES) readonly buffer RadialGhostFacesBuf { uint g_ghostFaces[]; };
layout(std430, binding = GLC_BIND_RADIAL_GHOST_POSITIONS) readonly buffer RadialGhostPositionsBuf { vec4 g_ghostPositions[]; };

uniform uint u_realFaceCount; // faces of the model; classified faces past them are ghost faces
uniform uint u_nodeCount;     // nodes of the model; node indices past them are ghost nodes

uvec3 glcRadialFaceNodes(uint face) {
    if (face < u_realFaceCount) return faceNodes(face);
    uint g = 3u * (face - u_realFaceCount);
    return uvec3(g_ghostFaces[g], g_ghostFaces[g + 1u], g_ghostFaces[g + 2u]);
}

vec3 glcRadialStart(uint node) {
    return node < u_nodeCount ? g_start[node].xyz : g_ghostPositions[2u * (node - u_nodeCount)].xyz;
}

vec3 glcRadialEnd(uint node) {
    return node < u_nodeCount ? g_end[node].xyz : g_ghostPositions[2u * (node - u_nodeCount) + 1u].xyz;
}

#endif
