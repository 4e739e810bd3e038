#version 430 core
// RadialViolatedExact — the exact half of RadialViolated (docs/culling.md, "Violated pairs"): one
// invocation per pair of a ghost face and a face of its surface that the certified filter left
// undecided (touching, coplanar, degenerate or nearly so), decided by glcTriTriExact of
// common/tri_tri_robust.glsl at x0, one pair per invocation. A crossing, or a pair the exact test
// cannot finish, marks the surface violated for this substep (culling less only costs time).
// Dispatched over the list's whole capacity; invocations past its count return at once.
#include "common/layout.glsl"
#include "common/lists.glsl" // g_counters: the statistics
#include "common/face_nodes.glsl"
#include "common/tri_tri_robust.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; }; // unused here
layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_VIOLATED) buffer RadialViolatedBuf { uint g_violated[]; };
layout(std430, binding = GLC_BIND_RADIAL_UNDECIDED) readonly buffer RadialUndecidedBuf { uint g_undecided[]; };
#include "common/radial_ghost.glsl"

uniform uint u_undecidedCapacity; // pairs the undecided list holds

void main() {
    uint i = globalIndex();
    if (i >= min(g_undecided[0], u_undecidedCapacity)) return;
    uint face = g_undecided[2u + 2u * i], other = g_undecided[3u + 2u * i];
    uint observer = g_faceObserver[face];
    if (g_violated[observer] != 0u) return; // already marked
    uvec3 g = glcRadialFaceNodes(face), o = glcRadialFaceNodes(other);
    bool hit = glcTriTriExact(glcRadialStart(g.x), glcRadialStart(g.y), glcRadialStart(g.z), glcRadialStart(o.x),
                              glcRadialStart(o.y), glcRadialStart(o.z));
    if ((hit || glcExactFailed) && atomicOr(g_violated[observer], 1u) == 0u)
        atomicAdd(g_counters.stats[GLC_STAT_RADIAL_VIOLATED], 1u);
}
