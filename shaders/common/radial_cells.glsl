// Footprint cells of radial view-based culling (decision 0025, "Footprint cells"): a grid that lets
// RadialFree skip its brute-force scan for most faces without changing a single answer.
//
// Direction space is the cube [-1, 1]^3 cut into GLC_RADIAL_CELL_GRID^3 cells; a segment
// observer's feet [0, 1] are cut into GLC_RADIAL_FOOT_BINS bins. A footprint (cone, feet) covers
// a *box* of cells — the cells of the axis-aligned box around the cone's axis, GlcRadialCellReach
// wide on each side — and a range of bins. RadialClassify marks, per observer, the (cell, bin)s of
// every face not proven positive; RadialFree scans a positive face's non-positive list only when
// one of its own (cell, bin)s is marked.
//
// Why no answer changes: the scan calls a face free when glcRadialFeetMeet and
// glcRadialFootprintsMeet are false for every listed face. The cells only ever skip the scan of a
// face for which that is so, because whenever both tests return true (as computed, in float, with
// their slack) the two boxes and bin ranges share a (cell, bin):
//  - Cones: glcRadialFootprintsMeet(a, b) true means a . b >= ca cb - sa sb - GLC_FOOTPRINT_SLACK up
//    to its rounding (a few ulps), i.e. a . b >= cos(ta + tb) - s with s < 2^-14 + 2^-20 (ta, tb the
//    half-angles, < 90 degrees). The axes are unit within 2^-21, so |a - b|^2 = |a|^2 + |b|^2 -
//    2 a . b <= 4 sin^2((ta + tb) / 2) + 2 (s + 2^-20), and with 2 sin((ta + tb) / 2) <= 2 sin(ta / 2)
//    + 2 sin(tb / 2) (sine is concave there): |a - b| <= rA + rB + sqrt(2 (s + 2^-20)), where
//    r = 2 sin(t / 2) = sqrt(2 (1 - c)) is the cone's chord. Each box reaches r + 2^-6 from its
//    axis; 2 * 2^-6 > sqrt(2 (s + 2^-20)) ~ 0.0115 with room for the rounding of r and of the box's
//    ends (below 2^-20). So every coordinate of a - b is within the two reaches: the boxes overlap,
//    and the cell of any point of their overlap is in both (cell indices are monotone in x).
//    A cone of every direction (c <= -1) reaches 2 + 2^-6: the whole grid.
//  - Feet: glcRadialFeetMeet(a, b) true means u = max(a.x, b.x) lies in both closed intervals; bins
//    are floor(u * GLC_RADIAL_FOOT_BINS) (exact: a power of two) clamped, monotone in u, so u's bin
//    is in both ranges. NaN ends give the whole range.
//
// Two grids: a footprint whose box holds more than 64 of the fine grid's cells (a cone wider than
// about 20 degrees) marks the coarse grid's cells instead, and a positive face looks at both.
// The proof holds for any grid. Layout (GLC_BIND_RADIAL_CELLS): per observer GLC_RADIAL_CELL_WORDS
// words, one byte per cell (bit b set when bin b of that cell is marked): the coarse grid's
// GLC_RADIAL_COARSE_WORDS words, then the fine grid's.
//
// GLSL subset shared with C++ (cpu/radial_library.hpp): no swizzles, no out/inout parameters,
// float literals with `f`. Include after common/layout.glsl.

#ifndef GLC_RADIAL_CELLS_GLSL
#define GLC_RADIAL_CELLS_GLSL

// Added to a cone's chord. Range > 0.0058 (half of sqrt(2 (2^-14 + 2^-19)), the meeting test's
// slack and rounding, see above); suggested 2^-6 (a box widens by an eighth of a cell).
const float GLC_CELL_REACH_SLACK = 0.015625f; // 2^-6
// A footprint whose box holds more fine cells than this is marked in the coarse grid instead (at
// most 4^3 = 64 cells there); a positive face with such a box is scanned without looking at cells.
const int GLC_RADIAL_MOST_MARKED_CELLS = 64;

// How far (per coordinate) every direction of the cone lies from its axis, with the slack above.
float glcRadialCellReach(vec4 cone) {
    return sqrt(max(2.0f * (1.0f - cone.w), 0.0f)) + GLC_CELL_REACH_SLACK;
}

// The lowest cell of a grid (cells per axis) that a coordinate at or above x can lie in, and the
// highest one at or below x (NaN: the whole range).
int glcRadialCellLow(float x, int grid) {
    if (!(x > -1.0f)) return 0;
    return min(int((x + 1.0f) * (0.5f * float(grid))), grid - 1);
}
int glcRadialCellHigh(float x, int grid) {
    if (!(x < 1.0f)) return grid - 1;
    return max(int((x + 1.0f) * (0.5f * float(grid))), 0);
}

// The corners of the cone's box of cells in a grid.
ivec3 glcRadialCellsLow(vec4 cone, int grid) {
    float r = glcRadialCellReach(cone);
    return ivec3(glcRadialCellLow(cone.x - r, grid), glcRadialCellLow(cone.y - r, grid),
                 glcRadialCellLow(cone.z - r, grid));
}
ivec3 glcRadialCellsHigh(vec4 cone, int grid) {
    float r = glcRadialCellReach(cone);
    return ivec3(glcRadialCellHigh(cone.x + r, grid), glcRadialCellHigh(cone.y + r, grid),
                 glcRadialCellHigh(cone.z + r, grid));
}

// Bits lo .. hi of a byte: the bins of the feet interval (an inverted or NaN interval: every bin,
// as glcRadialFeetMeet may call it meeting anything; a compiler that assumes no NaN may drop that
// check; feet are NaN only from non-finite positions, which EngineOptions::checkFinite reports).
uint glcRadialFootBins(vec2 feet) {
    if (!(feet.x <= feet.y)) return (1u << uint(GLC_RADIAL_FOOT_BINS)) - 1u;
    float scale = float(GLC_RADIAL_FOOT_BINS);
    int lo = feet.x > 0.0f ? min(int(feet.x * scale), GLC_RADIAL_FOOT_BINS - 1) : 0;
    int hi = feet.y < 1.0f ? max(int(feet.y * scale), 0) : GLC_RADIAL_FOOT_BINS - 1;
    uint upToHi = (2u << uint(hi)) - 1u, belowLo = (1u << uint(lo)) - 1u;
    return upToHi & ~belowLo;
}

// Cells in the box from lo to hi (0 when empty).
int glcRadialCellCount(ivec3 lo, ivec3 hi) {
    return max(hi.x - lo.x + 1, 0) * max(hi.y - lo.y + 1, 0) * max(hi.z - lo.z + 1, 0);
}

// Where cell (x, y, z) of a grid (GLC_RADIAL_COARSE_GRID or GLC_RADIAL_CELL_GRID) of `observer`
// lies: its word, and the shift of its byte in that word.
uint glcRadialCellWord(uint observer, int grid, int x, int y, int z) {
    uint cell = uint((z * grid + y) * grid + x);
    uint level = grid == GLC_RADIAL_CELL_GRID ? uint(GLC_RADIAL_COARSE_WORDS) : 0u;
    return observer * uint(GLC_RADIAL_CELL_WORDS) + level + cell / 4u;
}
uint glcRadialCellShift(int x) {
    return uint(x % 4) * 8u; // cells in a word are consecutive in x; both grids are multiples of 4
}

#endif
