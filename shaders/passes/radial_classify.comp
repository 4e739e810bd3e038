#version 430 core
// RadialClassify — radial view-based culling's triangle classification (issue 24, docs/culling.md,
// "Classification"): one invocation per face. A face is *positive* when glcRadialPositive proves
// phi(t) = n(t) . (p0(t) - q(t)) > 0 over the whole substep for its observer q, every point moving
// linearly from x0 (the positions) to x1 (the predicted positions). The proof is a certified float
// bound that holds whatever the compiler does (shaders/common/radial_sign.glsl); not proven means
// "may collide", never "negative". Output: bit f % 32 of word f / 32 of GLC_BIND_RADIAL_POSITIVE,
// set by atomicOr (the host clears the mask first): the result does not depend on the order.
// A face without an observer (GLC_RADIAL_NO_OBSERVER) is never positive. The classified faces are
// the real faces, then the ghost faces that close observed surfaces' holes (common/radial_ghost.glsl):
// one invocation each, ghost nodes read from RadialGhostNodes' positions.
// Also, for RadialFree, every observed face's footprint cone (common/radial_footprint.glsl) and
// the lists of observed faces not proven positive, one per observer (appended in any order:
// RadialFree only asks whether some listed cone meets a face's, which does not depend on the order),
// and the footprint cells those faces cover (common/radial_cells.glsl: set by atomicOr into a mask
// the host clears, so the order does not matter either).
// A segment observer (GLC_BIND_RADIAL_SEGMENTS, w = 1; decision 0025 "Segment observers") judges each
// point from its foot on the segment: the face's feet interval (GLC_BIND_RADIAL_FEET), positivity for
// every foot in it, and the cone of its fibers' directions; a face whose cone is every direction may
// touch the segment, and gets every foot, so that it meets every face's footprint. A point
// observer's faces get every foot too (their footprints are their cones).
#include "common/layout.glsl"
#include "common/face_nodes.glsl"

layout(local_size_x = GLC_WORKGROUP_SIZE) in;
#include "common/index.glsl" // after local_size: it reads gl_WorkGroupSize
#include "common/radial_sign.glsl"
#include "common/radial_footprint.glsl"
#include "common/radial_cells.glsl"

layout(std430, binding = GLC_BIND_NODE_POSITIONS) readonly buffer NodePositionsBuf { vec4 g_start[]; };
layout(std430, binding = GLC_BIND_PREDICTED_POSITIONS) readonly buffer PredictedPositionsBuf { vec4 g_end[]; };
layout(std430, binding = GLC_BIND_RADIAL_OBSERVERS) readonly buffer RadialObserversBuf { vec4 g_observers[]; };
layout(std430, binding = GLC_BIND_RADIAL_FACE_OBSERVER) readonly buffer RadialFaceObserverBuf { uint g_faceObserver[]; };
layout(std430, binding = GLC_BIND_RADIAL_POSITIVE) buffer RadialPositiveBuf { uint g_positive[]; };
layout(std430, binding = GLC_BIND_RADIAL_CONES) buffer RadialConesBuf { vec4 g_cones[]; };
layout(std430, binding = GLC_BIND_RADIAL_NONPOSITIVE) buffer RadialNonPositiveBuf { uint g_nonPositive[]; };
layout(std430, binding = GLC_BIND_RADIAL_SEGMENTS) readonly buffer RadialSegmentsBuf { vec4 g_segments[]; };
layout(std430, binding = GLC_BIND_RADIAL_FEET) buffer RadialFeetBuf { vec2 g_feet[]; };
layout(std430, binding = GLC_BIND_RADIAL_CELLS) buffer RadialCellsBuf { uint g_cells[]; };

#include "common/radial_ghost.glsl"

uniform uint u_faceCount; // classified faces: real, then ghost

// Marks the footprint's cells for RadialFree: in the fine grid, or in the coarse one when its box
// holds more than GLC_RADIAL_MOST_MARKED_CELLS fine cells (at most 64 coarse ones).
void markCells(uint observer, vec4 cone, vec2 feet) {
    int grid = GLC_RADIAL_CELL_GRID;
    ivec3 lo = glcRadialCellsLow(cone, grid), hi = glcRadialCellsHigh(cone, grid);
    if (glcRadialCellCount(lo, hi) > GLC_RADIAL_MOST_MARKED_CELLS) {
        grid = GLC_RADIAL_COARSE_GRID;
        lo = glcRadialCellsLow(cone, grid);
        hi = glcRadialCellsHigh(cone, grid);
    }
    uint bins = glcRadialFootBins(feet);
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x)
                atomicOr(g_cells[glcRadialCellWord(observer, grid, x, y, z)], bins << glcRadialCellShift(x));
}

void main() {
    uint face = globalIndex();
    if (face >= u_faceCount) return;
    uint observer = g_faceObserver[face];
    if (observer == GLC_RADIAL_NO_OBSERVER) return;
    uvec3 n = glcRadialFaceNodes(face);
    vec3 p0 = glcRadialStart(n.x), p1 = glcRadialStart(n.y), p2 = glcRadialStart(n.z);
    vec3 p0End = glcRadialEnd(n.x), p1End = glcRadialEnd(n.y), p2End = glcRadialEnd(n.z);
    vec3 q = g_observers[2u * observer].xyz, qEnd = g_observers[2u * observer + 1u].xyz;
    // A surface whose faces wind inward (w < 0, decision 0025 "Orientation") is classified with
    // every face turned round: its winding number around an inside observer is then +1.
    if (g_observers[2u * observer].w < 0.0) {
        vec3 t = p1;
        p1 = p2;
        p2 = t;
        t = p1End;
        p1End = p2End;
        p2End = t;
    }
    bool positive;
    vec4 segmentStart = g_segments[2u * observer];
    if (segmentStart.w != 0.0) {
        vec3 r = segmentStart.xyz, rEnd = g_segments[2u * observer + 1u].xyz;
        vec2 feet = glcRadialFeet(p0, p1, p2, q, r, p0End, p1End, p2End, qEnd, rEnd);
        vec4 cone = glcRadialSegmentFootprint(p0, p1, p2, q, r, p0End, p1End, p2End, qEnd, rEnd, feet);
        positive = glcRadialSegmentPositive(p0, p1, p2, q, r, p0End, p1End, p2End, qEnd, rEnd, feet.x, feet.y);
        g_cones[face] = cone;
        g_feet[face] = cone.w <= -1.0 ? glcRadialWholeSegment() : feet;
    } else {
        g_cones[face] = glcRadialFootprint(p0, p1, p2, q, p0End, p1End, p2End, qEnd);
        positive = glcRadialPositive(p0, p1, p2, q, p0End, p1End, p2End, qEnd);
        g_feet[face] = glcRadialWholeSegment();
    }
    if (positive) {
        atomicOr(g_positive[face / 32u], 1u << (face % 32u));
    } else { // into its observer's bucket (RadialFree scans only that one), and counted in all
        uint slot = atomicAdd(g_nonPositive[1u + 2u * observer], 1u);
        g_nonPositive[g_nonPositive[2u + 2u * observer] + slot] = face;
        atomicAdd(g_nonPositive[0], 1u);
        markCells(observer, g_cones[face], g_feet[face]); // as written above (this invocation's own writes)
    }
}
