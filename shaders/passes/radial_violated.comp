#version 430 core
// RadialViolated — violated triangles of radial view-based culling (decision 0025, "The premise
// without a winding-number pass"; docs/culling.md, "Violated triangles"): one invocation per ghost
// face. The theorem needs the observer's closed surface — real and ghost faces — embedded at the
// start of the substep; the engine's TriTri keeps the real faces apart, this pass checks the rest:
// a ghost face against every real face of its surface and every ghost face before it, at x0, by
// the exact test (glcTriTriFiltered, else glcTriTriExact; pairs sharing a node are left out, as
// TriTri leaves out neighbours). One crossing, or a pair the exact test could not decide, marks the
// surface violated for this substep: RadialFree then frees none of its faces. Brute force behind a
// box test: (ghost faces) × (faces of the surface). The flag is an OR: the result does not depend on
// the order. CPU twin: cpu::radialViolatedPairs (non-empty exactly when a surface is marked).
#include "common/layout.glsl"
#include "common/lists.glsl" // g_counters: the statistics
#include "common/face_nodes.glsl"
#include "common/tri_tri_robust.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; }; // unused here
layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_OBSERVER_FACES) readonly buffer RadialObserverFacesBuf { uvec4 g_observerFaces[]; };
layout(std430, binding = GLC_BIND_RADIAL_VIOLATED) buffer RadialViolatedBuf { uint g_violated[]; };
#include "common/radial_ghost.glsl"

uniform uint u_ghostFaceCount;

bool sharesNode(uvec3 a, uvec3 b) {
    return any(equal(a, b.xxx)) || any(equal(a, b.yyy)) || any(equal(a, b.zzz));
}

// Whether the two triangles intersect, by the exact answer; undecidable counts as crossing (the
// surface is then not culled, which only costs time).
bool crosses(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    int filtered = glcTriTriFiltered(a0, a1, a2, b0, b1, b2);
    if (filtered != GLC_UNDECIDED) return filtered == 1;
    bool hit = glcTriTriExact(a0, a1, a2, b0, b1, b2);
    return hit || glcExactFailed;
}

void main() {
    uint ghostFace = globalIndex();
    if (ghostFace >= u_ghostFaceCount) return;
    uint face = u_realFaceCount + ghostFace;
    uint observer = g_faceObserver[face];
    if (observer == GLC_RADIAL_NO_OBSERVER) return;
    uvec3 g = glcRadialFaceNodes(face);
    vec3 g0 = glcRadialStart(g.x), g1 = glcRadialStart(g.y), g2 = glcRadialStart(g.z);
    vec3 lo = min(g0, min(g1, g2)), hi = max(g0, max(g1, g2));
    uvec4 range = g_observerFaces[observer];
    // The surface's real faces, then its ghost faces before this one (each ghost pair once).
    uint total = range.y + (face - range.z);
    for (uint k = 0u; k < total; ++k) {
        if (g_violated[observer] != 0u) return; // already marked: nothing left to learn
        uint other = k < range.y ? range.x + k : range.z + (k - range.y);
        uvec3 o = glcRadialFaceNodes(other);
        if (sharesNode(g, o)) continue;
        vec3 o0 = glcRadialStart(o.x), o1 = glcRadialStart(o.y), o2 = glcRadialStart(o.z);
        // Closed boxes: boxes that do not touch hold triangles that do not (touching counts).
        if (any(lessThan(max(o0, max(o1, o2)), lo)) || any(lessThan(hi, min(o0, min(o1, o2))))) continue;
        if (crosses(g0, g1, g2, o0, o1, o2)) {
            if (atomicOr(g_violated[observer], 1u) == 0u) atomicAdd(g_counters.stats[GLC_STAT_RADIAL_VIOLATED], 1u);
            return;
        }
    }
}
