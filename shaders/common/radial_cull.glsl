// Radial view-based culling's consumer side (decision 0025, docs/culling.md "Culling"): whether a
// pair of faces can be left out of an exact test (TriTri, the CCD at zero separation) because one
// of them is *free* — positive for its observer over the substep, its footprint meeting no
// non-positive face's — so by the decision's theorem it intersects nothing of its observer's
// surface during the substep. Only pairs of faces of the same observer are ever culled (the
// theorem says nothing about other surfaces). Word 0 of the free mask is 1 only in a substep whose
// mask RadialCulling computed (the engine clears it otherwise), so a stale mask is never read.
// Include after common/layout.glsl; the includer counts what it culls.
#ifndef GLC_RADIAL_CULL_GLSL
#define GLC_RADIAL_CULL_GLSL

layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_radialFaceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_FREE) readonly buffer RadialFreeBuf { uint g_radialFree[]; };
layout(std430, binding = GLC_BIND_RADIAL_NODE_OBSERVER) readonly buffer RadialNodeObserverBuf { uint g_radialNodeObserver[]; };

bool glcRadialFree(uint face) {
    return (g_radialFree[1u + face / 32u] & (1u << (face % 32u))) != 0u;
}

bool glcRadialCulled(uint faceA, uint faceB) {
    if (g_radialFree[0] == 0u) return false;
    uint observer = g_radialFaceObserver[faceA];
    if (observer == GLC_RADIAL_NO_OBSERVER || observer != g_radialFaceObserver[faceB]) return false;
    return glcRadialFree(faceA) || glcRadialFree(faceB);
}

// Vertex `node` against `face`: touching would make the faces around the node intersect the face,
// so a free face suffices — when the node lies on the face's observer's surface (every face
// around it is that surface's: GLC_BIND_RADIAL_NODE_OBSERVER).
bool glcRadialCulledVertexFace(uint node, uint face) {
    if (g_radialFree[0] == 0u) return false;
    uint observer = g_radialFaceObserver[face];
    if (observer == GLC_RADIAL_NO_OBSERVER || !glcRadialFree(face)) return false;
    return g_radialNodeObserver[node] == observer;
}

#endif
