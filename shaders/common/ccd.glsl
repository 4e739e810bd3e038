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
// Method: inclusion-based bisection over (t, u, v) in the style of Tight-Inclusion (Wang et al.
// 2021). F(t, u, v) = (point on one primitive) - (point on the other) is multilinear in t, u and
// v, so over a box it is a convex combination of its 8 corner values: a box whose corner values
// of one coordinate all exceed minSeparation + (their error bound) holds no contact and is
// dropped. The error bound is proportional to the coordinates' magnitudes and holds for any
// evaluation order (docs/ccd.md, "Error bound").
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

// ---------------------------------------------------------------------------------------------
// The inclusion search, shared by both kinds.

bool glcCcdInclusion(bool edgeEdge, vec3 s0, vec3 s1, vec3 s2, vec3 s3, vec3 e0, vec3 e1, vec3 e2,
                     vec3 e3, float minSeparation, int budget) {
    glcCcdBoxes = 0;
    glcCcdCapped = false;
    // Normalize by a power of two (exact): the rest sees the same numbers at every scale 2^k.
    vec3 largest = max(glcCcdAbsMax4(s0, s1, s2, s3), glcCcdAbsMax4(e0, e1, e2, e3));
    float scale = glcCcdNormalizingScale(max(largest.x, max(largest.y, largest.z)));
    s0 = s0 * scale; s1 = s1 * scale; s2 = s2 * scale; s3 = s3 * scale;
    e0 = e0 * scale; e1 = e1 * scale; e2 = e2 * scale; e3 = e3 * scale;
    largest = largest * scale;
    float delta = max(minSeparation, 0.0f) * scale;

    // Per point and axis, the larger magnitude of its two positions (exact).
    vec3 m0 = max(abs(s0), abs(e0)), m1 = max(abs(s1), abs(e1)), m2 = max(abs(s2), abs(e2)), m3 = max(abs(s3), abs(e3));
    // gamma_N = N u / (1 - N u): |computed F - exact F| <= gamma_N * (monomial sum) + flush term.
    float gamma = GLC_CCD_ROUNDINGS * GLC_CCD_UNIT_ROUNDOFF / (1.0f - GLC_CCD_ROUNDINGS * GLC_CCD_UNIT_ROUNDOFF);
    // Enlarged by 2^-20 of itself: the bound's own evaluation has at most 16 roundings of
    // positive terms (relative error < 2^-20 in any order).
    gamma = gamma * (1.0f + 9.5367431640625e-7f);

    // Worklist of boxes (t0, t1, u0, u1, v0, v1), depth-first, earlier t popped first.
    float stack[GLC_CCD_STACK_BOXES * 6];
    int top = 0;
    stack[0] = 0.0f; stack[1] = 1.0f; stack[2] = 0.0f; stack[3] = 1.0f; stack[4] = 0.0f; stack[5] = 1.0f;
    top = 1;
    float best = 2.0f;   // earliest accepted box's t0 (2: none)
    float lowest = 2.0f; // the least t0 of the boxes accepted or left unsearched
    float finest = 1.0f / float(1 << GLC_CCD_MAX_LEVEL);

    while (top > 0) {
        if (glcCcdBoxes >= budget) { glcCcdCapped = true; break; }
        top = top - 1;
        int base = top * 6;
        float t0 = stack[base], t1 = stack[base + 1], u0 = stack[base + 2], u1 = stack[base + 3];
        float v0 = stack[base + 4], v1 = stack[base + 5];
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
        vec3 errorBound = gamma * glcCcdMonomialSum(edgeEdge, m0, m1, m2, m3, t1, u1, v1) + vec3(GLC_CCD_FLUSH_BOUND);
        vec3 threshold = vec3(delta) + errorBound;
        threshold = threshold + threshold * 9.5367431640625e-7f; // its own two roundings: 2^-20 of it
        vec3 acceptWidth = GLC_CCD_ACCEPT_WIDTH * errorBound;
        // Drop the box when one coordinate is beyond the threshold at every corner.
        if (lo.x > threshold.x || lo.y > threshold.y || lo.z > threshold.z) continue;
        if (hi.x < -threshold.x || hi.y < -threshold.y || hi.z < -threshold.z) continue;

        // How much each variable moves the corner values, in units of the error bound.
        float spreadT = 0.0f, spreadU = 0.0f, spreadV = 0.0f;
        for (int i = 0; i < 8; ++i) {
            if ((i & 1) == 0) { vec3 d = abs(f[i + 1] - f[i]) / acceptWidth; spreadT = max(spreadT, max(d.x, max(d.y, d.z))); }
            if ((i & 2) == 0) { vec3 d = abs(f[i + 2] - f[i]) / acceptWidth; spreadU = max(spreadU, max(d.x, max(d.y, d.z))); }
            if ((i & 4) == 0) { vec3 d = abs(f[i + 4] - f[i]) / acceptWidth; spreadV = max(spreadV, max(d.x, max(d.y, d.z))); }
        }
        bool canT = t1 - t0 > finest, canU = u1 - u0 > finest, canV = v1 - v0 > finest;
        if (!canT) spreadT = -1.0f;
        if (!canU) spreadU = -1.0f;
        if (!canV) spreadV = -1.0f;
        vec3 width = hi - lo;
        bool narrow = width.x <= acceptWidth.x && width.y <= acceptWidth.y && width.z <= acceptWidth.z;
        if (narrow || (!canT && !canU && !canV)) {
            best = min(best, t0); // may collide in this box; no contact in it before t0
            lowest = min(lowest, t0);
            continue;
        }
        if (top + 2 > GLC_CCD_STACK_BOXES) { glcCcdCapped = true; lowest = min(lowest, t0); break; } // unreachable: depth-first
        // Halve the variable that moves the values most; push the later half of t first.
        for (int k = 0; k < 6; ++k) { stack[base + 6 + k] = stack[base + k]; }
        if (spreadT >= spreadU && spreadT >= spreadV) {
            float mid = 0.5f * (t0 + t1);
            stack[base] = mid;          // later half, popped second
            stack[base + 6 + 1] = mid;  // earlier half, popped first
        } else if (spreadU >= spreadV) {
            float mid = 0.5f * (u0 + u1);
            stack[base + 3] = mid;
            stack[base + 6 + 2] = mid;
        } else {
            float mid = 0.5f * (v0 + v1);
            stack[base + 5] = mid;
            stack[base + 6 + 4] = mid;
        }
        top = top + 2;
    }
    if (glcCcdCapped) {
        // Out of budget: every box still listed may hold a contact.
        for (int i = 0; i < top; ++i) { lowest = min(lowest, stack[i * 6]); }
        lowest = min(lowest, 1.0f);
    }
    glcCcdToi = min(lowest, 1.0f);
    return lowest <= 1.0f;
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
