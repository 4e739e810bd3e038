#version 430 core
// RadialFree — radial view-based culling's free faces (decision 0025): one invocation per face. A
// face is *free* when it is proven positive for its observer (RadialClassify) and its footprint
// (its cone, and for a segment observer its feet) meets that of no face of the same observer that is
// not proven positive (the list
// RadialClassify appended). By the decision's theorem a free face intersects nothing of its
// observer's surface during the substep; common/radial_cull.glsl leaves its pairs out of the exact
// tests. Brute force over its observer's non-positive list (RadialClassify's bucket of that
// observer: its length is the culling's cost; a bin of cone axes would bound it). Sets bit f of
// words 1.. of the free mask (atomicOr into a cleared mask) and word 0 = 1: the mask holds for this substep. Ghost faces are in the list (they bound where the
// surface may fold) but are never free themselves; a surface that does not wind exactly once
// around its observer (RadialWinding) frees nothing. CPU twin: cpu::radialFreeFaces.
#include "common/layout.glsl"
#include "common/lists.glsl" // g_counters: the statistics

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/radial_footprint.glsl"

layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_POSITIVE) readonly buffer RadialPositiveBuf { uint g_positive[]; };
layout(std430, binding = GLC_BIND_RADIAL_CONES) readonly buffer RadialConesBuf { vec4 g_cones[]; };
layout(std430, binding = GLC_BIND_RADIAL_FEET) readonly buffer RadialFeetBuf { vec2 g_feet[]; };
layout(std430, binding = GLC_BIND_RADIAL_NONPOSITIVE) readonly buffer RadialNonPositiveBuf { uint g_nonPositive[]; };
layout(std430, binding = GLC_BIND_RADIAL_FREE) buffer RadialFreeBuf { uint g_free[]; };
layout(std430, binding = GLC_BIND_RADIAL_WINDING) readonly buffer RadialWindingBuf { uint g_winding[]; };

uniform uint u_faceCount;     // real faces (the non-positive list may hold ghost faces past them)
uniform uint u_observerCount;

// The theorem's premise for `observer` (RadialWinding): its surface winds exactly once around it.
bool windsOnce(uint observer) {
    return g_winding[2u * observer] == 1u && g_winding[2u * observer + 1u] == 0u;
}

void main() {
    uint face = globalIndex();
    if (face == 0u) {
        g_free[0] = 1u;
        g_counters.stats[GLC_STAT_RADIAL_NON_POSITIVE] = g_nonPositive[0];
    }
    if (face < u_observerCount && !windsOnce(face)) // one invocation per observer counts the failures
        atomicAdd(g_counters.stats[GLC_STAT_RADIAL_VIOLATED], 1u);
    if (face >= u_faceCount) return;
    if ((g_positive[face / 32u] & (1u << (face % 32u))) == 0u) return;
    uint observer = g_faceObserver[face];
    if (!windsOnce(observer)) return; // no premise: nothing of this surface is free
    vec4 cone = g_cones[face];
    vec2 feet = g_feet[face];
    uint first = g_nonPositive[2u + 2u * observer], count = g_nonPositive[1u + 2u * observer];
    for (uint k = 0u; k < count; ++k) {
        uint other = g_nonPositive[first + k];
        if (glcRadialFeetMeet(feet, g_feet[other]) && glcRadialFootprintsMeet(cone, g_cones[other])) return;
    }
    atomicOr(g_free[1u + face / 32u], 1u << (face % 32u));
    atomicAdd(g_counters.stats[GLC_STAT_RADIAL_FREE], 1u);
}
