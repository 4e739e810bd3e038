#version 430 core
// RadialFree — radial view-based culling's free faces (decision 0025): one invocation per face. A
// face is *free* when it is proven positive for its observer (RadialClassify) and its footprint
// (its cone, and for a segment observer its feet) meets that of no face of the same observer that is
// not proven positive (the list
// RadialClassify appended). By the decision's theorem a free face intersects nothing of its
// observer's surface during the substep; common/radial_cull.glsl leaves its pairs out of the exact
// tests. A face none of whose footprint cells a listed face marked (common/radial_cells.glsl) meets
// none of their footprints and is free at once; any other face is tested against its observer's
// whole non-positive list (RadialClassify's bucket of that observer). Either way the answer is
// the brute-force scan's (the cells only skip scans that find nothing). Sets bit f of
// words 1.. of the free mask (atomicOr into a cleared mask) and word 0 = 1: the mask holds for this substep. Ghost faces are in the list (they bound where the
// surface may fold) but are never free themselves; a surface that does not wind exactly once
// around its observer (RadialWinding) frees nothing. CPU twin: cpu::radialFreeFaces.
#include "common/layout.glsl"
#include "common/lists.glsl" // g_counters: the statistics

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/radial_footprint.glsl"
#include "common/radial_cells.glsl"

layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_POSITIVE) readonly buffer RadialPositiveBuf { uint g_positive[]; };
layout(std430, binding = GLC_BIND_RADIAL_CONES) readonly buffer RadialConesBuf { vec4 g_cones[]; };
layout(std430, binding = GLC_BIND_RADIAL_FEET) readonly buffer RadialFeetBuf { vec2 g_feet[]; };
layout(std430, binding = GLC_BIND_RADIAL_NONPOSITIVE) readonly buffer RadialNonPositiveBuf { uint g_nonPositive[]; };
layout(std430, binding = GLC_BIND_RADIAL_FREE) buffer RadialFreeBuf { uint g_free[]; };
layout(std430, binding = GLC_BIND_RADIAL_WINDING) readonly buffer RadialWindingBuf { uint g_winding[]; };
layout(std430, binding = GLC_BIND_RADIAL_CELLS) readonly buffer RadialCellsBuf { uint g_cells[]; };

uniform uint u_faceCount;     // real faces (the non-positive list may hold ghost faces past them)
uniform uint u_observerCount;

// The theorem's premise for `observer` (RadialWinding): its surface winds exactly once around it.
bool windsOnce(uint observer) {
    return g_winding[2u * observer] == 1u && g_winding[2u * observer + 1u] == 0u;
}

// Whether some (cell, bin) of the footprint's box is marked in a grid.
bool boxMarked(uint observer, int grid, ivec3 lo, ivec3 hi, uint bins) {
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x)
                if ((g_cells[glcRadialCellWord(observer, grid, x, y, z)] & (bins << glcRadialCellShift(x))) != 0u)
                    return true;
    return false;
}

// Whether a face not proven positive marked one of this footprint's cells, in either grid (or the
// footprint is too wide to look at the fine one): only then can a listed footprint meet it.
bool cellsMarked(uint observer, vec4 cone, vec2 feet) {
    uint bins = glcRadialFootBins(feet);
    int coarse = GLC_RADIAL_COARSE_GRID, fine = GLC_RADIAL_CELL_GRID;
    if (boxMarked(observer, coarse, glcRadialCellsLow(cone, coarse), glcRadialCellsHigh(cone, coarse), bins))
        return true;
    ivec3 lo = glcRadialCellsLow(cone, fine), hi = glcRadialCellsHigh(cone, fine);
    return glcRadialCellCount(lo, hi) > GLC_RADIAL_MOST_MARKED_CELLS || boxMarked(observer, fine, lo, hi, bins);
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
    if (count > 0u && cellsMarked(observer, cone, feet)) { // an empty list needs no look at the cells
        for (uint k = 0u; k < count; ++k) {
            uint other = g_nonPositive[first + k];
            if (glcRadialFeetMeet(feet, g_feet[other]) && glcRadialFootprintsMeet(cone, g_cones[other])) return;
        }
    }
    atomicOr(g_free[1u + face / 32u], 1u << (face % 32u));
    atomicAdd(g_counters.stats[GLC_STAT_RADIAL_FREE], 1u);
}
