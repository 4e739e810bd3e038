#version 430 core
// RadialViolated — violated triangles of radial view-based culling (decision 0025, "The premise
// without a winding-number pass"; docs/culling.md, "Violated pairs"): one invocation per ghost
// face, looping over the faces of its surface (its real faces, then its ghost faces before this
// one, so each ghost pair once). The theorem needs the observer's closed
// surface — real and ghost faces — embedded at the start of the substep; the engine's TriTri keeps
// the real faces apart, this pass checks the rest, at x0: pairs sharing a node are left out (as
// TriTri leaves out neighbours), then a closed-box test, then the certified filter
// (glcTriTriFiltered). A crossing marks the surface violated for this substep (RadialFree then
// frees none of its faces); a pair the filter cannot decide goes to a short list that
// RadialViolatedExact decides exactly — or, when the list is full, marks the surface too (culling
// less only costs time). Brute force behind the box test; the exact code lives in its own kernel,
// whose private arrays would slow every invocation of this one on llvmpipe. The flag is an OR:
// the result does not depend on the order. CPU twin: cpu::radialViolatedPairs (non-empty exactly
// when a surface is marked).
#include "common/layout.glsl"
#include "common/lists.glsl" // g_counters: the statistics
#include "common/face_nodes.glsl"
#include "common/tri_tri_robust.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; }; // unused here
layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
// Per observer: where its real faces are listed, how many, its first ghost face, how many; then the lists.
layout(std430, binding = GLC_BIND_RADIAL_OBSERVER_FACES) readonly buffer RadialObserverFacesBuf { uint g_observerFaces[]; };
layout(std430, binding = GLC_BIND_RADIAL_VIOLATED) buffer RadialViolatedBuf { uint g_violated[]; };
// uint[2 + 2 * u_undecidedCapacity]: the count, unused, then (ghost face, other face) pairs
layout(std430, binding = GLC_BIND_RADIAL_UNDECIDED) buffer RadialUndecidedBuf { uint g_undecided[]; };
#include "common/radial_ghost.glsl"

uniform uint u_undecidedCapacity; // pairs the undecided list holds

uniform uint u_ghostFaceCount;  // ghost faces in all

bool sharesNode(uvec3 a, uvec3 b) {
    return any(equal(a, b.xxx)) || any(equal(a, b.yyy)) || any(equal(a, b.zzz));
}

// Whether ghost face `face` and face `other` (sharing no node) cross at x0: the closed-box test,
// then the certified filter; an undecided pair goes to RadialViolatedExact's list (returns false),
// or, with the list full, counts as crossing.
bool crosses(uint face, uint other, vec3 g0, vec3 g1, vec3 g2, vec3 gMin, vec3 gMax) {
    uvec3 o = glcRadialFaceNodes(other);
    vec3 o0 = glcRadialStart(o.x), o1 = glcRadialStart(o.y), o2 = glcRadialStart(o.z);
    // Closed boxes: boxes that do not touch hold triangles that do not (touching counts).
    if (any(lessThan(max(o0, max(o1, o2)), gMin)) || any(lessThan(gMax, min(o0, min(o1, o2))))) return false;
    if (sharesNode(glcRadialFaceNodes(face), o)) return false;
    int filtered = glcTriTriFiltered(g0, g1, g2, o0, o1, o2);
    if (filtered == GLC_UNDECIDED) {
        uint slot = atomicAdd(g_undecided[0], 1u);
        if (slot >= u_undecidedCapacity) return true;
        g_undecided[2u + 2u * slot] = face;
        g_undecided[3u + 2u * slot] = other;
        return false;
    }
    return filtered != 0;
}

void main() {
    uint ghostFace = globalIndex();
    if (ghostFace >= u_ghostFaceCount) return;
    uint face = u_realFaceCount + ghostFace;
    uint observer = g_faceObserver[face];
    if (observer == GLC_RADIAL_NO_OBSERVER) return;
    uvec4 range = uvec4(g_observerFaces[4u * observer], g_observerFaces[4u * observer + 1u],
                        g_observerFaces[4u * observer + 2u], g_observerFaces[4u * observer + 3u]);
    uvec3 g = glcRadialFaceNodes(face);
    vec3 g0 = glcRadialStart(g.x), g1 = glcRadialStart(g.y), g2 = glcRadialStart(g.z);
    vec3 gMin = min(g0, min(g1, g2)), gMax = max(g0, max(g1, g2));
    // The surface's real faces, then its ghost faces before this one (each ghost pair once).
    uint count = range.y + (face - range.z);
    for (uint k = 0u; k < count; ++k) {
        if (g_violated[observer] != 0u) return; // already marked
        uint other = k < range.y ? g_observerFaces[range.x + k] : range.z + (k - range.y);
        if (crosses(face, other, g0, g1, g2, gMin, gMax)) {
            if (atomicOr(g_violated[observer], 1u) == 0u)
                atomicAdd(g_counters.stats[GLC_STAT_RADIAL_VIOLATED], 1u);
            return;
        }
    }
}
