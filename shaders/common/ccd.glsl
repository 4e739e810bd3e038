// Conservative continuous collision detection in float: vertex-face and edge-edge, linear motion
// over t in [0, 1]. Compiled as GLSL and as C++ (src/cpu/ccd_library.hpp), so the CPU tests run
// the very code a GPU pass will run; judged against the exact oracle (src/cpu/oracle/exact_ccd.cpp).
// Method, tolerances and the soundness argument: docs/ccd.md and
// docs/design/decisions/0021-conservative-float-ccd.md.
//
//   bool glcVertexFaceCcd(p0, a0, b0, c0, p1, a1, b1, c1, minSeparation, budget)
//   bool glcEdgeEdgeCcd(a0, a1, b0, b1, a0End, a1End, b0End, b1End, minSeparation, budget)
//        Points at t = 0, then the same points at t = 1. True when the primitives may come within
//        minSeparation (>= 0) of each other at some t in [0, 1]. Never false when they do (zero
//        false negatives), whatever the compiler does with contraction, reassociation or
//        flush-to-zero; the answer is the same when every coordinate and minSeparation are
//        scaled by 2^k (no input or normalized value overflowing or becoming subnormal).
//        After the call: glcCcdToi, a time of impact never later than the true earliest one
//        (1.0 when false); glcCcdCapped, true when the budget of boxes ran out (the answer is then
//        "may collide" with the lower bound reached); glcCcdBoxes, boxes evaluated.
//
// First, a separating-plane certificate decided in integers (glcCcdPlaneSeparated; docs/ccd.md,
// "Separating plane"): a plane that keeps the primitives' nodes more than minSeparation apart at
// t = 0 and at t = 1 answers "no collision" without a box.
// Method: inclusion-based bisection over (t, u, v) in the style of Tight-Inclusion (Wang et al.
// 2021). F(t, u, v) = (point on one primitive) - (point on the other) is multilinear in t, u and
// v, so over a box it is a convex combination of its 8 corner values: a box whose corner values
// of one coordinate all exceed minSeparation + (their error bound) holds no contact and is
// dropped. The error bound is proportional to the coordinates' magnitudes and holds for any
// evaluation order (docs/ccd.md, "Error bound"). A second test projects F on the geometric normal
// (a sliding contact shows no gap in any single axis).
// When that float search says "may collide", a refutation pass repeats the search on the query
// quantized to a 2^-29 grid with exact integer corner values (docs/ccd.md, "Exact refutation"):
// if it drops every box, no contact exists and the answer becomes false. It removes the false
// positives that the float error bound (about 2^-15 of the coordinates) cannot separate.
//
// GLSL subset shared with C++: no swizzles, no out/inout parameters, no array constructors,
// float literals with `f`; results in GLC_PRIVATE globals (thread_local in C++).

#ifndef GLC_CCD_GLSL
#define GLC_CCD_GLSL

#ifndef GLC_PRIVATE
#define GLC_PRIVATE // GLSL globals are per invocation; C++ makes them thread_local
#endif

// ---------------------------------------------------------------------------------------------
// Tolerances (docs/ccd.md, "Tolerances").

// GLC_CCD_MAX_LEVEL: the most halvings of each of t, u and v. Range 1..24: at most 24, so every
// box corner k * 2^-level is exact in float (24-bit significand) and u0 + v0 > 1 is decided
// exactly. Suggested 24 (the finest float allows); smaller levels give coarser times of impact.
#define GLC_CCD_MAX_LEVEL 24
// The worklist: depth-first, so it holds at most one box per halving on the current path.
#define GLC_CCD_STACK_BOXES (3 * GLC_CCD_MAX_LEVEL + 1)

// GLC_CCD_ROUNDINGS (N): the most roundings on any path of a corner value's evaluation, in any
// order the compiler may choose. The source needs 9; the fully expanded sum of its 18 monomials
// of at most three factors, summed in the worst order, needs 19. Suggested 32 (margin for a
// compiler that rewrites more); range >= 19.
#define GLC_CCD_ROUNDINGS 32.0f
// 2^-24: the unit roundoff of IEEE binary32 (GLSL: +, -, * correctly rounded).
const float GLC_CCD_UNIT_ROUNDOFF = 5.9604644775390625e-8f;
// The monomial bound (docs/ccd.md, "Error bound"): fully expanded, an interpolated point
// x0 + t (x1 - x0) is x0 + t x1 - t x0, whose monomials' magnitudes sum to at most (1 + 2 t) M_x
// with M_x = max(|x0|, |x1|) per axis; F weights two such points by 1 and two differences by
// u and v. Computed per box from the box's largest t, u and v (glcCcdMonomialSum).
// GLC_CCD_FLUSH_BOUND: absolute error allowed for flush-to-zero, in normalized units (largest
// coordinate in [0.5, 1)): each of at most N roundings loses at most 2^-126 when it flushes a
// result or input below the smallest normal, and is weighted by at most 3 on the way to F, so
// 3 * 32 * 2^-126 < 2^-118. Suggested 2^-100 (ample); any value >= 2^-118 is sound.
const float GLC_CCD_FLUSH_BOUND = 7.8886090522101181e-31f; // 2^-100
// GLC_CCD_ACCEPT_WIDTH: a box that cannot be dropped is accepted as "may collide" once the
// image of every coordinate is no wider than this many error bounds (halving further could not
// separate it from the error). Range > 0; smaller gives fewer false positives and more boxes.
// Suggested 1.
const float GLC_CCD_ACCEPT_WIDTH = 1.0f;

// GLC_CCD_DIRECTION_ROUNDINGS (N_D): as N, for the projection n . F of the corner values on a
// direction n: fully expanded, 54 monomials of at most four factors, 56 roundings in the worst
// order. Suggested 96 (the margin of N over 19); range >= 56.
#define GLC_CCD_DIRECTION_ROUNDINGS 96.0f

// GLC_CCD_REFUTE_WIDTH: the exact refutation gives up (the answer stays "may collide") at the
// first box it cannot drop whose exact corner values span no more than this in every coordinate
// (normalized units: the largest coordinate is in [0.5, 1)). It changes no guarantee, only how
// close a miss it can still refute and how much work a true contact costs it. Range > 0;
// suggested 2^-12 (2^-12 ... 2^-20 give the same Sample-Query answers; 2^-8 leaves 9 more
// edge-edge false positives).
const float GLC_CCD_REFUTE_WIDTH = 2.44140625e-4f; // 2^-12
// GLC_CCD_REFUTE_SHARE: the float search may use all but budget / GLC_CCD_REFUTE_SHARE boxes, so
// that a capped search still leaves the refutation some. Range >= 1; suggested 8.
#define GLC_CCD_REFUTE_SHARE 8

// GLC_CCD_TOI_TOLERANCE: once a box is accepted at time t_a, boxes starting later than
// t_a - tolerance are not searched (their start times still bound the answer): the time of impact
// reported is at most this much earlier than the earliest accepted box. It changes no decision,
// only work: without it, contacts along a line (parallel edges) are resolved cell by cell.
// Range [0, 1]; suggested 2^-12.
const float GLC_CCD_TOI_TOLERANCE = 2.44140625e-4f; // 2^-12

GLC_PRIVATE float glcCcdToi;
GLC_PRIVATE bool glcCcdCapped;
GLC_PRIVATE int glcCcdBoxes;

// ---------------------------------------------------------------------------------------------
// Normalization: a power of two, so scaling is exact and the decision scale-invariant.

// 2^-e with the largest magnitude times it in [0.5, 1) (1 when all coordinates are 0).
float glcCcdNormalizingScale(float largest) {
    if (largest == 0.0f) return 1.0f;
    int biasedExponent = int((floatBitsToUint(largest) >> 23) & 255u); // 0 for subnormals
    // largest < 2^(biasedExponent - 126); the scale 2^(126 - biasedExponent) has biased exponent
    // 253 - biasedExponent, kept in [1, 254] (a normal float).
    int scaleExponent = clamp(253 - biasedExponent, 1, 254);
    return uintBitsToFloat(uint(scaleExponent) << 23);
}

vec3 glcCcdAbsMax4(vec3 a, vec3 b, vec3 c, vec3 d) {
    return max(max(abs(a), abs(b)), max(abs(c), abs(d)));
}

// ---------------------------------------------------------------------------------------------
// F at one corner, from the four points already interpolated at the corner's t.

vec3 glcCcdAt(vec3 x0, vec3 x1, float t) {
    return x0 + t * (x1 - x0);
}

// Vertex-face: p - (a + u (b - a) + v (c - a)); edge-edge: (p + u (a - p)) - (b + v (c - b)),
// with p, a the first edge and b, c the second.
vec3 glcCcdF(bool edgeEdge, vec3 p, vec3 a, vec3 b, vec3 c, float u, float v) {
    if (edgeEdge) return (p + u * (a - p)) - (b + v * (c - b));
    return p - a - u * (b - a) - v * (c - a);
}

// Sum of the magnitudes of F's monomials, fully expanded, over a box whose largest t, u and v are
// t1, u1 and v1 (m: per-point magnitudes in the order of glcCcdF's p, a, b, c).
vec3 glcCcdMonomialSum(bool edgeEdge, vec3 mp, vec3 ma, vec3 mb, vec3 mc, float t1, float u1, float v1) {
    vec3 sum = edgeEdge ? mp + u1 * (ma + mp) + mb + v1 * (mc + mb) : mp + ma + u1 * (mb + ma) + v1 * (mc + ma);
    return (1.0f + 2.0f * t1) * sum;
}

// gamma_N = N u / (1 - N u) for N roundings, enlarged by 2^-20 of itself: its own evaluation and
// the bound's (at most 16 roundings of positive terms: relative error < 2^-20 in any order).
float glcCcdGamma(float roundings) {
    float gamma = roundings * GLC_CCD_UNIT_ROUNDOFF / (1.0f - roundings * GLC_CCD_UNIT_ROUNDOFF);
    return gamma * (1.0f + 9.5367431640625e-7f);
}

// ---------------------------------------------------------------------------------------------
// Projection on a direction (both passes). |F|_inf >= n . F / |n|_1 for any n (Hoelder), and
// n . F is multilinear in (t, u, v) like F, so n . F > minSeparation |n|_1 at every corner of a box
// drops it with the same guarantee as the axis test: |F|_inf > minSeparation on the whole box
// (a rounding cover that widens minSeparation per coordinate stays valid, see query ccd).

// A vector rounded to integers of magnitude < 2^bits (bits in 1 ... 24) in the same direction
// (zero when it is below 2^-100, and for NaN). Integers make |n|_1 exact, and the rounding through
// trunc() keeps a compiler from expanding n's formula into a projection (the error bounds below
// hold for the values of n, not of its formula).
vec3 glcCcdIntegerDirectionBits(vec3 raw, int bits) {
    vec3 m = abs(raw);
    float largest = max(m.x, max(m.y, m.z));
    if (!(largest >= 7.8886090522101181e-31f)) return vec3(0.0f); // 2^-100; also NaN
    // largest in [2^(E-127), 2^(E-126)) with E its biased exponent (27 ... 254): times
    // 2^(126 + bits - E) it lies in [2^(bits-1), 2^bits). The scale's biased exponent
    // 253 + bits - E is in [bits - 1, 226 + bits]: a normal float.
    int biasedExponent = int((floatBitsToUint(largest) >> 23) & 255u);
    float scale = uintBitsToFloat(uint(253 + bits - biasedExponent) << 23);
    return trunc(raw * scale);
}

// The float search's directions: integers below 2^11, so that its projections' error bounds stay
// small (GLC_CCD_DIRECTION_ROUNDINGS).
vec3 glcCcdIntegerDirection(vec3 raw) {
    return glcCcdIntegerDirectionBits(raw, 11);
}

// A direction for the box: the normal of the triangle (vertex-face) or the cross product of the two
// edges (edge-edge) at time t, as an integer direction (zero for a degenerate triangle or parallel
// edges). Any direction is sound.
vec3 glcCcdDirection(bool edgeEdge, vec3 p, vec3 a, vec3 b, vec3 c) {
    return glcCcdIntegerDirection(edgeEdge ? cross(a - p, c - b) : cross(b - a, c - a));
}

// |n|_1 of an integer direction (exact: three integers below 2^11).
float glcCcdDirectionNorm(vec3 n) {
    vec3 a = abs(n);
    return a.x + a.y + a.z;
}

// ---------------------------------------------------------------------------------------------
// Exact corner values (the refutation pass). Every coordinate, normalized to |x| < 1, is truncated
// to the grid 2^-29: X = int(x * 2^29), |X| < 2^29, |x - X 2^-29| < 2^-29. F of the quantized query
// is then exact integer arithmetic: with t = T 2^-24, u = U 2^-24, v = V 2^-24 (box corners are
// dyadic of level <= 24) and F = G(t) + u H(t) + v K(t), each of G, H, K linear in t,
// F * 2^(29 + 48) = (G0 2^24 + T G1) 2^24 + U (H0 2^24 + T H1) + V (K0 2^24 + T K1),
// |G0| < 2^30, |G1| < 2^31 (differences of differences: 32-bit ints), so |F 2^77| < 2^83: 96-bit
// two's complement integers in a uvec3 (least significant limb in x), arithmetic modulo 2^96 that
// is exact because every value fits. No floating-point operation decides anything here: the
// compiler cannot change these values.

// Quantization error: per coordinate < 2^-29; F combines the points with weights summing to at
// most 4 at box corners (vertex-face: p - (1 - u - v) a - u b - v c with u, v in [0, 1]; edge-edge:
// 2), so the quantized F is within 4 * 2^-29 = 2^-27 of the float query's F. A coordinate flushed
// to zero (|x| < 2^-126) quantizes to 0 either way: inside the same bound.
const float GLC_CCD_QUANTUM_ERROR = 7.450580596923828e-09f; // 2^-27
// Relative error of a projection n . f computed from converted exact values f: |f - exact| <=
// 5.0001 * 2^-24 |f| from the conversion, then three products and two sums; even with a compiler
// distributing n over the six pieces of each conversion (18 monomials, 19 roundings in any order),
// |computed - n . exact| <= gamma_19 |n| . |f| < 2^-19.7 |n| . |f|. 2^-18 covers it.
const float GLC_CCD_EXACT_PROJECTION_ERROR = 3.814697265625e-6f; // 2^-18

struct GlcCcdExactQuery {
    ivec3 g0, g1, h0, h1, k0, k1; // F = (g0 + t g1) + u (h0 + t h1) + v (k0 + t k1), units 2^-29
};

ivec3 glcCcdQuantize(vec3 x) {
    return ivec3(x * 536870912.0f); // times 2^29 (exact), then truncated toward zero
}

// s: the four points at t = 0 in glcCcdF's order (p, a, b, c), e: at t = 1; normalized.
GlcCcdExactQuery glcCcdExact(bool edgeEdge, vec3 s0, vec3 s1, vec3 s2, vec3 s3, vec3 e0, vec3 e1, vec3 e2, vec3 e3) {
    ivec3 p0 = glcCcdQuantize(s0), a0 = glcCcdQuantize(s1), b0 = glcCcdQuantize(s2), c0 = glcCcdQuantize(s3);
    ivec3 p1 = glcCcdQuantize(e0), a1 = glcCcdQuantize(e1), b1 = glcCcdQuantize(e2), c1 = glcCcdQuantize(e3);
    GlcCcdExactQuery q;
    if (edgeEdge) { // (p - b) + u (a - p) + v (b - c)
        q.g0 = p0 - b0; q.g1 = (p1 - p0) - (b1 - b0);
        q.h0 = a0 - p0; q.h1 = (a1 - a0) - (p1 - p0);
        q.k0 = b0 - c0; q.k1 = (b1 - b0) - (c1 - c0);
    } else { // (p - a) + u (a - b) + v (a - c)
        q.g0 = p0 - a0; q.g1 = (p1 - p0) - (a1 - a0);
        q.h0 = a0 - b0; q.h1 = (a1 - a0) - (b1 - b0);
        q.k0 = a0 - c0; q.k1 = (a1 - a0) - (c1 - c0);
    }
    return q;
}

uvec3 glcCcdWide(int v) {
    uint sign = v < 0 ? 0xffffffffu : 0u;
    return uvec3(uint(v), sign, sign);
}

uvec3 glcCcdAdd(uvec3 a, uvec3 b) {
    uint c0, c1, c2;
    uint x = uaddCarry(a.x, b.x, c0);
    uint y = uaddCarry(a.y, b.y, c1);
    y = uaddCarry(y, c0, c2);
    return uvec3(x, y, a.z + b.z + c1 + c2);
}

uvec3 glcCcdShift24(uvec3 a) { // a * 2^24
    return uvec3(a.x << 24, (a.y << 24) | (a.x >> 8), (a.z << 24) | (a.y >> 8));
}

uvec3 glcCcdTimes(uvec3 a, uint s) { // a * s modulo 2^96: two's complement a, unsigned s
    uint h0, l0, h1, l1, c;
    umulExtended(a.x, s, h0, l0);
    umulExtended(a.y, s, h1, l1);
    uint y = uaddCarry(l1, h0, c);
    return uvec3(l0, y, a.z * s + h1 + c);
}

// c0 2^24 + T c1: a coefficient linear in t, at t = T 2^-24, in units of 2^-(29 + 24).
uvec3 glcCcdLinearAt(int c0, int c1, uint T) {
    return glcCcdAdd(glcCcdShift24(glcCcdWide(c0)), glcCcdTimes(glcCcdWide(c1), T));
}

// The value a * 2^-77 as a float, within a relative 5.0001 * 2^-24: six 16-bit pieces, each
// converted exactly (below 2^24) and scaled by an exact power of two (>= 2^-77: never subnormal),
// summed in whatever order: five roundings of non-negative terms.
float glcCcdToFloat(uvec3 a) {
    bool negative = (a.z >> 31) != 0u;
    if (negative) a = glcCcdAdd(~a, uvec3(1u, 0u, 0u));
    float m = float(a.z >> 16) * 8.0f + float(a.z & 0xffffu) * 1.220703125e-4f // 2^3, 2^-13
              + float(a.y >> 16) * 1.862645149230957e-09f + float(a.y & 0xffffu) * 2.842170943040401e-14f // 2^-29, 2^-45
              + float(a.x >> 16) * 4.336808689942018e-19f + float(a.x & 0xffffu) * 6.617444900424222e-24f; // 2^-61, 2^-77
    return negative ? -m : m;
}

// One coordinate of the quantized F at time T and the four (u, v) corners (u0, v0), (u1, v0),
// (u0, v1), (u1, v1), each exact before its conversion to float.
vec4 glcCcdExactCorners(int g0, int g1, int h0, int h1, int k0, int k1, uint T, uint U0, uint U1, uint V0, uint V1) {
    uvec3 G = glcCcdShift24(glcCcdLinearAt(g0, g1, T));
    uvec3 H = glcCcdLinearAt(h0, h1, T), K = glcCcdLinearAt(k0, k1, T);
    uvec3 hu0 = glcCcdTimes(H, U0), hu1 = glcCcdTimes(H, U1);
    uvec3 kv0 = glcCcdAdd(G, glcCcdTimes(K, V0)), kv1 = glcCcdAdd(G, glcCcdTimes(K, V1));
    return vec4(glcCcdToFloat(glcCcdAdd(kv0, hu0)), glcCcdToFloat(glcCcdAdd(kv0, hu1)),
                glcCcdToFloat(glcCcdAdd(kv1, hu0)), glcCcdToFloat(glcCcdAdd(kv1, hu1)));
}

// A box corner as the integer numerator over 2^24 (exact: dyadic of level <= 24, in [0, 1]).
uint glcCcdGrid(float x) {
    return uint(x * 16777216.0f);
}

// ---------------------------------------------------------------------------------------------
// Which variable to halve: the one whose halving moves the corner values most, in units of
// `unit` per coordinate; -1 when none can be halved. 0: t, 1: u, 2: v.
int glcCcdSplitVariable(vec3 f0, vec3 f1, vec3 f2, vec3 f3, vec3 f4, vec3 f5, vec3 f6, vec3 f7, vec3 unit,
                        bool canT, bool canU, bool canV) {
    vec3 dt = max(max(abs(f1 - f0), abs(f3 - f2)), max(abs(f5 - f4), abs(f7 - f6))) / unit;
    vec3 du = max(max(abs(f2 - f0), abs(f3 - f1)), max(abs(f6 - f4), abs(f7 - f5))) / unit;
    vec3 dv = max(max(abs(f4 - f0), abs(f5 - f1)), max(abs(f6 - f2), abs(f7 - f3))) / unit;
    float spreadT = canT ? max(dt.x, max(dt.y, dt.z)) : -1.0f;
    float spreadU = canU ? max(du.x, max(du.y, du.z)) : -1.0f;
    float spreadV = canV ? max(dv.x, max(dv.y, dv.z)) : -1.0f;
    if (!canT && !canU && !canV) return -1;
    if (spreadT >= spreadU && spreadT >= spreadV) return 0;
    return spreadU >= spreadV ? 1 : 2;
}

// ---------------------------------------------------------------------------------------------
// The inclusion search, shared by both kinds.

// The worklist of both passes: boxes (t0, t1, u0, u1, v0, v1), depth-first, so it holds at most
// one box per halving on the current path.
GLC_PRIVATE float glcCcdStack[GLC_CCD_STACK_BOXES * 6];

// Replaces the box at `base` (on top of the worklist) by its two halves in `variable` (0: t, 1: u,
// 2: v), the earlier or lower half on top.
void glcCcdPushHalves(int base, int variable) {
    for (int k = 0; k < 6; ++k) { glcCcdStack[base + 6 + k] = glcCcdStack[base + k]; }
    int low = base + 2 * variable; // this variable's lower end
    float mid = 0.5f * (glcCcdStack[low] + glcCcdStack[low + 1]);
    glcCcdStack[low] = mid;          // the upper half stays below, popped second
    glcCcdStack[low + 6 + 1] = mid;  // the lower half on top, popped first
}

// +1 when n . f certainly exceeds reach, -1 when it is certainly below -reach, else 0, for a
// computed n . f within reach_error + relative * |n| . |f| of the exact one (reach includes
// reach_error). The factor 1 + 2^-20 covers the rounding of the margin's own positive terms.
int glcCcdSide(vec3 n, vec3 f, float reach, float relative) {
    float projection = dot(n, f);
    float margin = (reach + relative * dot(abs(n), abs(f))) * (1.0f + 9.5367431640625e-7f);
    return projection > margin ? 1 : (projection < -margin ? -1 : 0);
}

// True when the projection on n clears minSeparation on the same side at all 8 corners.
bool glcCcdProjectionClear(vec3 n, vec3 f0, vec3 f1, vec3 f2, vec3 f3, vec3 f4, vec3 f5, vec3 f6, vec3 f7,
                           float reach, float relative) {
    int sides = glcCcdSide(n, f0, reach, relative) + glcCcdSide(n, f1, reach, relative) +
                glcCcdSide(n, f2, reach, relative) + glcCcdSide(n, f3, reach, relative) +
                glcCcdSide(n, f4, reach, relative) + glcCcdSide(n, f5, reach, relative) +
                glcCcdSide(n, f6, reach, relative) + glcCcdSide(n, f7, reach, relative);
    return sides == 8 || sides == -8;
}

// ---------------------------------------------------------------------------------------------
// The separating-plane certificate (normalized inputs; docs/ccd.md, "Separating plane"), decided
// before the search, in integers. Every point of a primitive is a convex combination of its nodes,
// and every node moves linearly, so when n . (x_a - x_b) > delta |n|_1 holds for every node a of
// the first primitive and b of the second at t = 0 and at t = 1, it holds at every t between (each
// is linear in t) and for every pair of points of the two primitives (convex combinations):
// |F|_inf >= n . F / |n|_1 > delta throughout the substep, and no box needs searching. Decided
// exactly on the refutation's grid: X = int(x 2^29) is within one unit of x 2^29, so
// n . (x_a - x_b) 2^29 > N - 2 |n|_1 with N = n . (X_a - X_b), an integer below 2^52 (96-bit
// limbs, glcCcdTimes); with D >= delta 2^29 an integer, N > (D + 2) |n|_1 proves the inequality.
// n is an integer direction below 2^20 (exact |n|_1); which one does not matter for soundness:
// the offset between the primitives' closest points at t = 0, then at t = 1, then at t = 1/2,
// computed in float without a division. It separates pairs that stay apart while they move —
// resting contacts sliding, bodies falling together — at gaps down to a few units of 2^-29 of the
// coordinates, where the float search is below its error bound (about 2^-15) and the refutation
// gives up at GLC_CCD_REFUTE_WIDTH (2^-12) in the configurations its projection on the normal
// cannot decide (a vertex beside a face's edge or corner, edges meeting near their ends). No
// floating-point operation decides.

// The offset from the closest point of triangle abc to p (Ericson, Real-Time Collision Detection,
// 5.1.5), times a positive factor: written without a division, so that every device that
// evaluates the GLSL as written (llvmpipe divides by a reciprocal) computes the same bits as the
// C++ twin. A degenerate triangle gives some offset, or zero; any direction will do.
vec3 glcCcdTriangleOffset(vec3 p, vec3 a, vec3 b, vec3 c) {
    vec3 ab = b - a, ac = c - a, ap = p - a;
    float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return ap;
    vec3 bp = p - b;
    float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return bp;
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return (d1 - d3) * ap - d1 * ab; // edge ab
    vec3 cp = p - c;
    float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return cp;
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return (d2 - d6) * ap - d2 * ac; // edge ac
    float va = d3 * d6 - d5 * d4;
    float e4 = d4 - d3, e5 = d5 - d6;
    if (va <= 0.0f && e4 >= 0.0f && e5 >= 0.0f) return (e4 + e5) * bp - e4 * (c - b); // edge bc
    return (va + vb + vc) * ap - vb * ab - vc * ac; // the interior
}

// The offset from the closest point of segment bc to the closest point of segment pa (Sunday's
// clamped form of Ericson 5.1.9: s = sN / sD, t = tN / tD), times sD tD > 0, without a division.
vec3 glcCcdSegmentOffset(vec3 p, vec3 a, vec3 b, vec3 c) {
    vec3 u = a - p, v = c - b, w = p - b;
    float A = dot(u, u), B = dot(u, v), C = dot(v, v), D = dot(u, w), E = dot(v, w);
    float det = A * C - B * B;
    float sN = 0.0f, sD = 1.0f, tN = E, tD = C;
    if (det > 0.0f) {
        sN = B * E - C * D; sD = det; tN = A * E - B * D; tD = det;
        if (sN < 0.0f) { sN = 0.0f; tN = E; tD = C; }
        else if (sN > sD) { sN = sD; tN = E + B; tD = C; }
    }
    if (!(tD > 0.0f)) { tN = 0.0f; tD = 1.0f; } // a point for an edge
    if (tN < 0.0f) {
        tN = 0.0f;
        if (-D < 0.0f) sN = 0.0f;
        else if (-D > A) sN = sD;
        else { sN = -D; sD = A; }
    } else if (tN > tD) {
        tN = tD;
        if (B - D < 0.0f) sN = 0.0f;
        else if (B - D > A) sN = sD;
        else { sN = B - D; sD = A; }
    }
    return (sD * tD) * w + (sN * tD) * u - (tN * sD) * v;
}

// The offset from the second primitive's closest point to the first's, in glcCcdF's order, times a
// positive factor.
vec3 glcCcdClosestOffset(bool edgeEdge, vec3 p, vec3 a, vec3 b, vec3 c) {
    if (edgeEdge) return glcCcdSegmentOffset(p, a, b, c);
    return glcCcdTriangleOffset(p, a, b, c);
}

// n . (X - Y) - threshold as a 96-bit integer (X, Y quantized points, n an integer direction;
// |n_i (X_i - Y_i)| < 2^50).
uvec3 glcCcdPlaneExcess(ivec3 n, ivec3 x, ivec3 y, uvec3 threshold) {
    ivec3 d = x - y; // |d| < 2^30
    uvec3 sum = glcCcdAdd(~threshold, uvec3(1u, 0u, 0u)); // -threshold
    for (int i = 0; i < 3; ++i) {
        int signedD = n[i] < 0 ? -d[i] : d[i];
        sum = glcCcdAdd(sum, glcCcdTimes(glcCcdWide(signedD), uint(abs(n[i]))));
    }
    return sum;
}

// Whether a 96-bit two's complement integer is > 0.
bool glcCcdPositive(uvec3 a) {
    return (a.z >> 31) == 0u && (a.x | a.y | a.z) != 0u;
}

// Whether n separates the first primitive (vertex p, or edge pa) from the second (face abc, or
// edge bc) by more than the threshold at one time (quantized points).
bool glcCcdPlaneSeparates(bool edgeEdge, ivec3 n, ivec3 p, ivec3 a, ivec3 b, ivec3 c, uvec3 threshold) {
    if (edgeEdge)
        return glcCcdPositive(glcCcdPlaneExcess(n, p, b, threshold)) &&
               glcCcdPositive(glcCcdPlaneExcess(n, p, c, threshold)) &&
               glcCcdPositive(glcCcdPlaneExcess(n, a, b, threshold)) &&
               glcCcdPositive(glcCcdPlaneExcess(n, a, c, threshold));
    return glcCcdPositive(glcCcdPlaneExcess(n, p, a, threshold)) &&
           glcCcdPositive(glcCcdPlaneExcess(n, p, b, threshold)) &&
           glcCcdPositive(glcCcdPlaneExcess(n, p, c, threshold));
}

// Whether the integer direction of `offset` separates the primitives by more than delta at t = 0
// and at t = 1 (S: the quantized points at t = 0, E: at t = 1; D >= delta 2^29).
bool glcCcdPlaneSeparatesBoth(bool edgeEdge, vec3 offset, ivec3 S0, ivec3 S1, ivec3 S2, ivec3 S3, ivec3 E0,
                              ivec3 E1, ivec3 E2, ivec3 E3, uint D) {
    // 20 bits: the direction of a close pair's offset, kept to 2^-20, must not tilt the plane into
    // the nodes of a pair that slides far compared with its gap.
    vec3 direction = glcCcdIntegerDirectionBits(offset, 20);
    if (direction == vec3(0.0f)) return false;
    ivec3 n = ivec3(direction); // exact: integers below 2^20
    uint norm = uint(abs(n.x) + abs(n.y) + abs(n.z));
    uvec3 threshold = glcCcdTimes(uvec3(D + 2u, 0u, 0u), norm); // (D + 2) |n|_1 < 2^29 2^22
    return glcCcdPlaneSeparates(edgeEdge, n, S0, S1, S2, S3, threshold) &&
           glcCcdPlaneSeparates(edgeEdge, n, E0, E1, E2, E3, threshold);
}

// True when a plane keeps the primitives more than delta apart over the whole substep (exact).
bool glcCcdPlaneSeparated(bool edgeEdge, vec3 s0, vec3 s1, vec3 s2, vec3 s3, vec3 e0, vec3 e1, vec3 e2, vec3 e3,
                          float delta) {
    if (!(delta < 0.5f)) return false; // D + 2 must fit 32 bits (and NaN)
    uint D = uint(ceil(delta * 536870912.0f)); // times 2^29 (exact), rounded up: D >= delta 2^29
    ivec3 S0 = glcCcdQuantize(s0), S1 = glcCcdQuantize(s1), S2 = glcCcdQuantize(s2), S3 = glcCcdQuantize(s3);
    ivec3 E0 = glcCcdQuantize(e0), E1 = glcCcdQuantize(e1), E2 = glcCcdQuantize(e2), E3 = glcCcdQuantize(e3);
    if (glcCcdPlaneSeparatesBoth(edgeEdge, glcCcdClosestOffset(edgeEdge, s0, s1, s2, s3), S0, S1, S2, S3, E0, E1,
                                 E2, E3, D))
        return true;
    if (glcCcdPlaneSeparatesBoth(edgeEdge, glcCcdClosestOffset(edgeEdge, e0, e1, e2, e3), S0, S1, S2, S3, E0, E1,
                                 E2, E3, D))
        return true;
    vec3 middle = glcCcdClosestOffset(edgeEdge, glcCcdAt(s0, e0, 0.5f), glcCcdAt(s1, e1, 0.5f),
                                      glcCcdAt(s2, e2, 0.5f), glcCcdAt(s3, e3, 0.5f));
    return glcCcdPlaneSeparatesBoth(edgeEdge, middle, S0, S1, S2, S3, E0, E1, E2, E3, D);
}

// The float search (normalized inputs): true when some box may hold a contact; sets glcCcdToi,
// glcCcdCapped and counts glcCcdBoxes.
bool glcCcdFloatSearch(bool edgeEdge, vec3 s0, vec3 s1, vec3 s2, vec3 s3, vec3 e0, vec3 e1, vec3 e2, vec3 e3,
                       float delta, int budget) {
    // Per point and axis, the larger magnitude of its two positions (exact).
    vec3 m0 = max(abs(s0), abs(e0)), m1 = max(abs(s1), abs(e1)), m2 = max(abs(s2), abs(e2)), m3 = max(abs(s3), abs(e3));
    // |computed F - exact F| <= gamma_N * (monomial sum) + flush term; the projection's N_D alike.
    float gamma = glcCcdGamma(GLC_CCD_ROUNDINGS), gammaProjection = glcCcdGamma(GLC_CCD_DIRECTION_ROUNDINGS);

    glcCcdStack[0] = 0.0f; glcCcdStack[1] = 1.0f; glcCcdStack[2] = 0.0f; glcCcdStack[3] = 1.0f;
    glcCcdStack[4] = 0.0f; glcCcdStack[5] = 1.0f;
    int top = 1;
    float best = 2.0f;   // earliest accepted box's t0 (2: none)
    float lowest = 2.0f; // the least t0 of the boxes accepted or left unsearched
    float finest = 1.0f / float(1 << GLC_CCD_MAX_LEVEL);

    while (top > 0) {
        if (glcCcdBoxes >= budget) { glcCcdCapped = true; break; }
        top = top - 1;
        int base = top * 6;
        float t0 = glcCcdStack[base], t1 = glcCcdStack[base + 1], u0 = glcCcdStack[base + 2], u1 = glcCcdStack[base + 3];
        float v0 = glcCcdStack[base + 4], v1 = glcCcdStack[base + 5];
        if (t0 >= best - GLC_CCD_TOI_TOLERANCE) { // lowers the time of impact by less than the tolerance
            lowest = min(lowest, t0);
            continue;
        }
        if (!edgeEdge && u0 + v0 > 1.0f) continue; // outside the triangle (exact: dyadic, level <= 24)
        glcCcdBoxes = glcCcdBoxes + 1;

        vec3 pA = glcCcdAt(s0, e0, t0), aA = glcCcdAt(s1, e1, t0), bA = glcCcdAt(s2, e2, t0), cA = glcCcdAt(s3, e3, t0);
        vec3 pB = glcCcdAt(s0, e0, t1), aB = glcCcdAt(s1, e1, t1), bB = glcCcdAt(s2, e2, t1), cB = glcCcdAt(s3, e3, t1);
        // Corner i: t from bit 0, u from bit 1, v from bit 2.
        vec3 f[8];
        f[0] = glcCcdF(edgeEdge, pA, aA, bA, cA, u0, v0);
        f[1] = glcCcdF(edgeEdge, pB, aB, bB, cB, u0, v0);
        f[2] = glcCcdF(edgeEdge, pA, aA, bA, cA, u1, v0);
        f[3] = glcCcdF(edgeEdge, pB, aB, bB, cB, u1, v0);
        f[4] = glcCcdF(edgeEdge, pA, aA, bA, cA, u0, v1);
        f[5] = glcCcdF(edgeEdge, pB, aB, bB, cB, u0, v1);
        f[6] = glcCcdF(edgeEdge, pA, aA, bA, cA, u1, v1);
        f[7] = glcCcdF(edgeEdge, pB, aB, bB, cB, u1, v1);
        vec3 lo = f[0], hi = f[0];
        for (int i = 1; i < 8; ++i) { lo = min(lo, f[i]); hi = max(hi, f[i]); }
        // Error bound of this box's corner values, and the threshold delta + errorBound.
        vec3 monomials = glcCcdMonomialSum(edgeEdge, m0, m1, m2, m3, t1, u1, v1);
        vec3 errorBound = gamma * monomials + vec3(GLC_CCD_FLUSH_BOUND);
        vec3 threshold = vec3(delta) + errorBound;
        threshold = threshold + threshold * 9.5367431640625e-7f; // its own two roundings: 2^-20 of it
        vec3 acceptWidth = GLC_CCD_ACCEPT_WIDTH * errorBound;
        // Drop the box when one coordinate is beyond the threshold at every corner.
        if (lo.x > threshold.x || lo.y > threshold.y || lo.z > threshold.z) continue;
        if (hi.x < -threshold.x || hi.y < -threshold.y || hi.z < -threshold.z) continue;
        // Or when the projection on the normal at the box's middle time is: the computed n . F
        // is within gamma_ND * sum_i |n_i| (monomial sum)_i of the exact one (docs/ccd.md), and
        // each flushed operation loses < 2^-126, weighted by at most 3 * 2^11.
        vec3 n = glcCcdDirection(edgeEdge, 0.5f * (pA + pB), 0.5f * (aA + aB), 0.5f * (bA + bB), 0.5f * (cA + cB));
        if (n != vec3(0.0f)) {
            float norm = glcCcdDirectionNorm(n);
            float reach = (delta + GLC_CCD_FLUSH_BOUND) * norm + gammaProjection * dot(abs(n), monomials);
            if (glcCcdProjectionClear(n, f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], reach, 0.0f)) continue;
        }

        vec3 width = hi - lo;
        bool narrow = width.x <= acceptWidth.x && width.y <= acceptWidth.y && width.z <= acceptWidth.z;
        int split = glcCcdSplitVariable(f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], acceptWidth,
                                        t1 - t0 > finest, u1 - u0 > finest, v1 - v0 > finest);
        if (narrow || split < 0) {
            best = min(best, t0); // may collide in this box; no contact in it before t0
            lowest = min(lowest, t0);
            continue;
        }
        if (top + 2 > GLC_CCD_STACK_BOXES) { glcCcdCapped = true; lowest = min(lowest, t0); break; } // unreachable: depth-first
        glcCcdPushHalves(base, split); // halve the variable that moves the values most
        top = top + 2;
    }
    if (glcCcdCapped) {
        // Out of budget: every box still listed may hold a contact.
        for (int i = 0; i < top; ++i) { lowest = min(lowest, glcCcdStack[i * 6]); }
        lowest = min(lowest, 1.0f);
    }
    glcCcdToi = min(lowest, 1.0f);
    return lowest <= 1.0f;
}

// The exact refutation (normalized inputs): true when every box of the quantized query is
// dropped, so that no point comes within delta of the other primitive; false when it meets a box
// it cannot drop that is narrower than GLC_CCD_REFUTE_WIDTH (or cannot be halved), or after
// `budget` boxes. Counts glcCcdBoxes. docs/ccd.md, "Exact refutation".
bool glcCcdRefute(bool edgeEdge, vec3 s0, vec3 s1, vec3 s2, vec3 s3, vec3 e0, vec3 e1, vec3 e2, vec3 e3,
                  float delta, int budget) {
    GlcCcdExactQuery q = glcCcdExact(edgeEdge, s0, s1, s2, s3, e0, e1, e2, e3);
    // A coordinate of the float query's F exceeds delta where the quantized one exceeds
    // delta + 2^-27 (+ the flush term); the computed value is within 5.0001 * 2^-24 of it relative.
    float reachAxis = (delta + GLC_CCD_QUANTUM_ERROR + GLC_CCD_FLUSH_BOUND) * (1.0f + 9.5367431640625e-7f);
    float finest = 1.0f / float(1 << GLC_CCD_MAX_LEVEL);
    glcCcdStack[0] = 0.0f; glcCcdStack[1] = 1.0f; glcCcdStack[2] = 0.0f; glcCcdStack[3] = 1.0f;
    glcCcdStack[4] = 0.0f; glcCcdStack[5] = 1.0f;
    int top = 1;
    int boxes = 0;
    while (top > 0) {
        if (boxes >= budget) return false;
        top = top - 1;
        int base = top * 6;
        float t0 = glcCcdStack[base], t1 = glcCcdStack[base + 1], u0 = glcCcdStack[base + 2], u1 = glcCcdStack[base + 3];
        float v0 = glcCcdStack[base + 4], v1 = glcCcdStack[base + 5];
        if (!edgeEdge && u0 + v0 > 1.0f) continue;
        boxes = boxes + 1;
        glcCcdBoxes = glcCcdBoxes + 1;

        uint T0 = glcCcdGrid(t0), T1 = glcCcdGrid(t1), U0 = glcCcdGrid(u0), U1 = glcCcdGrid(u1), V0 = glcCcdGrid(v0), V1 = glcCcdGrid(v1);
        vec4 xA = glcCcdExactCorners(q.g0.x, q.g1.x, q.h0.x, q.h1.x, q.k0.x, q.k1.x, T0, U0, U1, V0, V1);
        vec4 yA = glcCcdExactCorners(q.g0.y, q.g1.y, q.h0.y, q.h1.y, q.k0.y, q.k1.y, T0, U0, U1, V0, V1);
        vec4 zA = glcCcdExactCorners(q.g0.z, q.g1.z, q.h0.z, q.h1.z, q.k0.z, q.k1.z, T0, U0, U1, V0, V1);
        vec4 xB = glcCcdExactCorners(q.g0.x, q.g1.x, q.h0.x, q.h1.x, q.k0.x, q.k1.x, T1, U0, U1, V0, V1);
        vec4 yB = glcCcdExactCorners(q.g0.y, q.g1.y, q.h0.y, q.h1.y, q.k0.y, q.k1.y, T1, U0, U1, V0, V1);
        vec4 zB = glcCcdExactCorners(q.g0.z, q.g1.z, q.h0.z, q.h1.z, q.k0.z, q.k1.z, T1, U0, U1, V0, V1);
        // Corner i: t from bit 0, u from bit 1, v from bit 2 (as in the float search).
        vec3 f0 = vec3(xA.x, yA.x, zA.x), f1 = vec3(xB.x, yB.x, zB.x), f2 = vec3(xA.y, yA.y, zA.y), f3 = vec3(xB.y, yB.y, zB.y);
        vec3 f4 = vec3(xA.z, yA.z, zA.z), f5 = vec3(xB.z, yB.z, zB.z), f6 = vec3(xA.w, yA.w, zA.w), f7 = vec3(xB.w, yB.w, zB.w);
        vec3 lo = min(min(min(f0, f1), min(f2, f3)), min(min(f4, f5), min(f6, f7)));
        vec3 hi = max(max(max(f0, f1), max(f2, f3)), max(max(f4, f5), max(f6, f7)));
        if (lo.x > reachAxis || lo.y > reachAxis || lo.z > reachAxis) continue;
        if (hi.x < -reachAxis || hi.y < -reachAxis || hi.z < -reachAxis) continue;
        // A box whose every value is within delta in every coordinate holds a contact (within
        // delta): nothing here can be refuted, so stop at once instead of at the refutation width.
        float inner = delta - (reachAxis - delta);
        if (hi.x < inner && hi.y < inner && hi.z < inner && lo.x > -inner && lo.y > -inner && lo.z > -inner)
            return false;
        // The projection on the normal at the box's middle time: exact n . (quantized F) is within
        // sum_i |n_i| 2^-27 of n . F; computed from the converted values it is within 2^-18 of
        // |n| . |f| (any order, even distributed over the six pieces: 19 roundings).
        float tm = 0.5f * (t0 + t1);
        vec3 n = glcCcdDirection(edgeEdge, glcCcdAt(s0, e0, tm), glcCcdAt(s1, e1, tm), glcCcdAt(s2, e2, tm), glcCcdAt(s3, e3, tm));
        if (n != vec3(0.0f)) {
            float reach = (delta + GLC_CCD_QUANTUM_ERROR + GLC_CCD_FLUSH_BOUND) * glcCcdDirectionNorm(n);
            if (glcCcdProjectionClear(n, f0, f1, f2, f3, f4, f5, f6, f7, reach, GLC_CCD_EXACT_PROJECTION_ERROR)) continue;
        }

        vec3 width = hi - lo;
        int split = glcCcdSplitVariable(f0, f1, f2, f3, f4, f5, f6, f7, vec3(GLC_CCD_REFUTE_WIDTH), t1 - t0 > finest,
                                        u1 - u0 > finest, v1 - v0 > finest);
        if (split < 0 || (width.x <= GLC_CCD_REFUTE_WIDTH && width.y <= GLC_CCD_REFUTE_WIDTH && width.z <= GLC_CCD_REFUTE_WIDTH))
            return false; // a box that may hold a contact at this resolution: give up
        if (top + 2 > GLC_CCD_STACK_BOXES) return false; // unreachable: depth-first
        glcCcdPushHalves(base, split);
        top = top + 2;
    }
    return true;
}

bool glcCcdInclusion(bool edgeEdge, vec3 s0, vec3 s1, vec3 s2, vec3 s3, vec3 e0, vec3 e1, vec3 e2,
                     vec3 e3, float minSeparation, int budget) {
    glcCcdBoxes = 0;
    glcCcdCapped = false;
    // Normalize by a power of two (exact): the rest sees the same numbers at every scale 2^k.
    vec3 largest = max(glcCcdAbsMax4(s0, s1, s2, s3), glcCcdAbsMax4(e0, e1, e2, e3));
    float scale = glcCcdNormalizingScale(max(largest.x, max(largest.y, largest.z)));
    s0 = s0 * scale; s1 = s1 * scale; s2 = s2 * scale; s3 = s3 * scale;
    e0 = e0 * scale; e1 = e1 * scale; e2 = e2 * scale; e3 = e3 * scale;
    float delta = max(minSeparation, 0.0f) * scale;

    if (glcCcdPlaneSeparated(edgeEdge, s0, s1, s2, s3, e0, e1, e2, e3, delta)) {
        glcCcdToi = 1.0f;
        return false;
    }
    bool mayCollide = glcCcdFloatSearch(edgeEdge, s0, s1, s2, s3, e0, e1, e2, e3, delta,
                                        budget - budget / GLC_CCD_REFUTE_SHARE);
    if (mayCollide && glcCcdRefute(edgeEdge, s0, s1, s2, s3, e0, e1, e2, e3, delta, budget - glcCcdBoxes)) {
        glcCcdToi = 1.0f; // every box dropped: no contact, and the answer is complete
        glcCcdCapped = false;
        return false;
    }
    return mayCollide;
}

bool glcVertexFaceCcd(vec3 p0, vec3 a0, vec3 b0, vec3 c0, vec3 p1, vec3 a1, vec3 b1, vec3 c1,
                      float minSeparation, int budget) {
    return glcCcdInclusion(false, p0, a0, b0, c0, p1, a1, b1, c1, minSeparation, budget);
}

bool glcEdgeEdgeCcd(vec3 a0, vec3 a1, vec3 b0, vec3 b1, vec3 a0End, vec3 a1End, vec3 b0End, vec3 b1End,
                    float minSeparation, int budget) {
    return glcCcdInclusion(true, a0, a1, b0, b1, a0End, a1End, b0End, b1End, minSeparation, budget);
}

#endif // GLC_CCD_GLSL
