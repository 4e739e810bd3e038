// Radial view-based culling's classification (Wong & Cheng 2016, Appendix B; docs/culling.md): is
// a triangle *positive* with respect to a point observer over the whole substep? Compiled as GLSL
// and as C++ (src/cpu/radial_library.hpp), so the CPU tests run the very code a GPU pass will run;
// judged against exact rational coefficients (tests/unit/radial_sign_test.cpp).
//
//   bool glcRadialPositive(p0, p1, p2, q, p0End, p1End, p2End, qEnd)
//        The triangle's vertices and the observer at t = 0, then the same points at t = 1, each
//        moving linearly. True only when phi(t) = n(t) . (p0(t) - q(t)) > 0 for every t in
//        [0, 1], with n = (p1 - p0) x (p2 - p0): q stays strictly on the side its normal points
//        away from. False means "not proven" (a degenerate, coplanar, crossing or overflowing case
//        included), never "negative".
//
// Method. With a = p1 - p0, b = p2 - p0, c = p0 - q, each linear in t, phi is the triple product
// D(a, b, c) = (a x b) . c: a cubic whose Bernstein coefficients over [0, 1] are (subscripts: the
// end each factor is taken at)
//   B0 = D(a0, b0, c0),                          B3 = D(a1, b1, c1),
//   3 B1 = D(a1, b0, c0) + D(a0, b1, c0) + D(a0, b0, c1),
//   3 B2 = D(a1, b1, c0) + D(a1, b0, c1) + D(a0, b1, c1)
// (D is linear in each factor). phi(t) = sum B_i C(3, i) t^i (1 - t)^(3 - i) is a convex
// combination of them, so B_i > 0 for all four proves phi > 0 on [0, 1].
//
// Certified in float, whatever the compiler does with contraction, reassociation and flushing:
// - the six differences are `precise` in GLSL (computed as written, one rounding each: relative
//   error <= u per coordinate, whatever is done with their uses); C++ computes them as written;
// - each coefficient (times 3 for B1, B2) is a signed sum of at most 18 products of three
//   differences; in any order of the sum, with or without fused multiply-adds, each product
//   passes through at most 3 (its inputs) + 2 (its own) + 17 (the sum) = 22 roundings, so the
//   float value is within gamma_22 * M of the exact one, M the sum of the products' magnitudes;
// - M is computed in float from the same differences (a sum of non-negative products: relative
//   error below gamma_22 too);
// - flushing: a result flushed to zero loses at most 2^-126; inside a product's path that is an
//   absolute error of at most 22 * 2^-126 per product (2^-100 covers all of them), but a flushed
//   difference coordinate (|a_i| < 2^-126, read as 0) weighs on the products it is a factor of:
//   at most 2^-126 (|b|_1 |c|_1 + |a|_1 |c|_1 + |a|_1 |b|_1) per triple product, with |.|_1 the
//   coordinates' magnitude sums (2^-123 covers that with rounding to spare).
// So value > gamma_N (1 + gamma_N) M + 2^-123 F + 2^-100, F the sum of those |.|_1 products and
// N = GLC_RADIAL_ROUNDINGS >= 22, proves the exact coefficient positive. The test computes it as
// value - 2 (that bound) > 0 (glcRadialCoefficientBounds below, shared with segment observers):
// the second bound covers the subtraction's own rounding. NaN and infinity fail every comparison:
// never positive.
//
// GLSL subset shared with C++: no swizzles, no out/inout parameters, float literals with `f`.

#ifndef GLC_RADIAL_SIGN_GLSL
#define GLC_RADIAL_SIGN_GLSL

#ifndef GLC_PRECISE
#define GLC_PRECISE precise // C++ defines it empty (its compilers evaluate as written)
#endif

// 2^-24: the unit roundoff of IEEE binary32 (GLSL: +, -, * correctly rounded).
const float GLC_RADIAL_UNIT_ROUNDOFF = 5.9604644775390625e-8f;
// GLC_RADIAL_ROUNDINGS (N): the most roundings on a product's path through a coefficient, in any
// order (22, above). Range >= 22; suggested 32 (margin for a compiler that rewrites more). Larger
// only proves fewer triangles positive: the bound is N * 2^-24 ~ 1.9e-6 of M at 32.
const float GLC_RADIAL_ROUNDINGS = 32.0f;
// Absolute allowance for flush-to-zero inside the products' paths (above): 2^-100 is ample. A
// coefficient of subnormal size is never proven positive.
const float GLC_RADIAL_FLUSH_BOUND = 7.8886090522101181e-31f; // 2^-100
// Weight of a flushed difference coordinate (2^-126, above) with margin for rounding: 2^-123.
const float GLC_RADIAL_FLUSHED_INPUT = 9.4039548065783000e-38f; // 2^-123

// D(a, b, c) = (a x b) . c, written out.
float glcRadialTriple(vec3 a, vec3 b, vec3 c) {
    return (a.y * b.z - a.z * b.y) * c.x + (a.z * b.x - a.x * b.z) * c.y + (a.x * b.y - a.y * b.x) * c.z;
}

// What D's float value may be off by (above): gamma_N (1 + gamma_N) M + 2^-123 F.
float glcRadialTripleError(vec3 a, vec3 b, vec3 c) {
    vec3 x = abs(a), y = abs(b), z = abs(c);
    float magnitude =
        (x.y * y.z + x.z * y.y) * z.x + (x.z * y.x + x.x * y.z) * z.y + (x.x * y.y + x.y * y.x) * z.z;
    float sa = x.x + x.y + x.z, sb = y.x + y.y + y.z, sc = z.x + z.y + z.z;
    float gamma =
        GLC_RADIAL_ROUNDINGS * GLC_RADIAL_UNIT_ROUNDOFF / (1.0f - GLC_RADIAL_ROUNDINGS * GLC_RADIAL_UNIT_ROUNDOFF);
    return gamma * (1.0f + gamma) * magnitude + GLC_RADIAL_FLUSHED_INPUT * (sb * sc + sa * sc + sa * sb);
}

// Segment observers (decision 0025, "Segment observers"): the observer is a segment
// s(u) = (1 - u) A + u B, u in [0, 1], A and B moving linearly, and a point x of the triangle is
// judged from its foot s(u(x)), the segment's point nearest to it. The triangle is positive when
// n(t) . (x - foot(x)) > 0 for every x in it and every t; with the feet of all its points within
// s([uLo, uHi]) (glcRadialFeet, common/radial_footprint.glsl) it suffices that
// phi_u(t) = n(t) . (p0(t) - s(u)(t)) > 0 for every u in [uLo, uHi] (n . (x - s(u)) is the same for
// every x of the triangle's plane). phi is affine in the observer, so phi_u = (1 - u) phi_A + u phi_B
// and so are its Bernstein coefficients: their lower bounds (1 - u) L_A + u L_B are linear in u,
// positive on [uLo, uHi] when positive at both ends. No point inside the segment is ever computed.
//
//   vec4 glcRadialCoefficientBounds(p0, p1, p2, q, p0End, p1End, p2End, qEnd)
//        Lower bounds of phi's four Bernstein coefficients (B0, 3 B1, 3 B2, B3) for observer q:
//        each coefficient's float value minus twice its error bound and the flush allowance. Why
//        the float subtraction cannot lift it above the exact coefficient: the bound was computed
//        with N = GLC_RADIAL_ROUNDINGS >= 32 roundings where 22 suffice, and the margin of one
//        error bound (>= 32 * 2^-24 M) dwarfs the subtraction's own two roundings (<= 3 * 2^-24 M).
//   bool glcRadialSegmentPositive(p0, p1, p2, a, b, p0End, p1End, p2End, aEnd, bEnd, uLo, uHi)
//        True only when phi_u > 0 over the substep for every u in [uLo, uHi].
vec4 glcRadialCoefficientBounds(vec3 p0, vec3 p1, vec3 p2, vec3 q, vec3 p0End, vec3 p1End, vec3 p2End,
                                vec3 qEnd) {
    GLC_PRECISE vec3 a0 = p1 - p0;
    GLC_PRECISE vec3 b0 = p2 - p0;
    GLC_PRECISE vec3 c0 = p0 - q;
    GLC_PRECISE vec3 a1 = p1End - p0End;
    GLC_PRECISE vec3 b1 = p2End - p0End;
    GLC_PRECISE vec3 c1 = p0End - qEnd;
    float coefficient0 = glcRadialTriple(a0, b0, c0);
    float error0 = glcRadialTripleError(a0, b0, c0);
    float coefficient3 = glcRadialTriple(a1, b1, c1);
    float error3 = glcRadialTripleError(a1, b1, c1);
    // 3 B1 and 3 B2 (the factor does not change the sign).
    float coefficient1 = glcRadialTriple(a1, b0, c0) + glcRadialTriple(a0, b1, c0) + glcRadialTriple(a0, b0, c1);
    float error1 =
        glcRadialTripleError(a1, b0, c0) + glcRadialTripleError(a0, b1, c0) + glcRadialTripleError(a0, b0, c1);
    float coefficient2 = glcRadialTriple(a1, b1, c0) + glcRadialTriple(a1, b0, c1) + glcRadialTriple(a0, b1, c1);
    float error2 =
        glcRadialTripleError(a1, b1, c0) + glcRadialTripleError(a1, b0, c1) + glcRadialTripleError(a0, b1, c1);
    return vec4(coefficient0 - 2.0f * error0 - GLC_RADIAL_FLUSH_BOUND,
                coefficient1 - 2.0f * error1 - GLC_RADIAL_FLUSH_BOUND,
                coefficient2 - 2.0f * error2 - GLC_RADIAL_FLUSH_BOUND,
                coefficient3 - 2.0f * error3 - GLC_RADIAL_FLUSH_BOUND);
}

// The point observer's test: every coefficient's lower bound positive.
bool glcRadialPositive(vec3 p0, vec3 p1, vec3 p2, vec3 q, vec3 p0End, vec3 p1End, vec3 p2End, vec3 qEnd) {
    vec4 bounds = glcRadialCoefficientBounds(p0, p1, p2, q, p0End, p1End, p2End, qEnd);
    return bounds.x > 0.0f && bounds.y > 0.0f && bounds.z > 0.0f && bounds.w > 0.0f;
}

// Rounding of la + u (lb - la) for u in [0, 1]: at most 3 roundings (the difference, the product,
// the sum; fewer fused), each within 2^-24 (|la| + |lb|) of it; 2^-20 covers them with margin.
const float GLC_RADIAL_MIX_ROUNDOFF = 9.5367431640625e-7f; // 2^-20

// (1 - u) la + u lb > 0 for every u in [uLo, uHi] (a line: its ends decide), certified.
bool glcRadialAboveOn(float la, float lb, float uLo, float uHi) {
    if (la > 0.0f && lb > 0.0f) return true;
    float margin = GLC_RADIAL_MIX_ROUNDOFF * (abs(la) + abs(lb)) + GLC_RADIAL_FLUSH_BOUND;
    return la + uLo * (lb - la) > margin && la + uHi * (lb - la) > margin;
}

bool glcRadialSegmentPositive(vec3 p0, vec3 p1, vec3 p2, vec3 a, vec3 b, vec3 p0End, vec3 p1End, vec3 p2End,
                              vec3 aEnd, vec3 bEnd, float uLo, float uHi) {
    vec4 la = glcRadialCoefficientBounds(p0, p1, p2, a, p0End, p1End, p2End, aEnd);
    vec4 lb = glcRadialCoefficientBounds(p0, p1, p2, b, p0End, p1End, p2End, bEnd);
    return glcRadialAboveOn(la.x, lb.x, uLo, uHi) && glcRadialAboveOn(la.y, lb.y, uLo, uHi) &&
           glcRadialAboveOn(la.z, lb.z, uLo, uHi) && glcRadialAboveOn(la.w, lb.w, uLo, uHi);
}

// The observer check (decision 0025, "The winding number"): how a ray from q along d crosses
// the triangle (p0, p1, p2), all at one instant, decided by certified signs of triple products of
// the `precise` differences e_i = p_i - q (and the exact direction d), each with the bound of
// glcRadialTripleError:
//   s_i = D(e_i, e_{i+1}, d): the line q + t d passes through the triangle's interior exactly when
//         s_0, s_1, s_2 are all nonzero with one sign (the ray runs on the same side of each edge);
//   D(e_0, e_1, e_2) = n . (p0 - q): q's side of the plane (n = (p1 - p0) x (p2 - p0));
//   n . d = s_0 + s_1 + s_2: the side the ray leaves through (no cancellation when the s_i share
//         their sign).
// The ray (t > 0) crosses when the line does and n . (p0 - q) has the sign of n . d. Returns +1
// (it leaves through the side n points to), -1 (through the back), 0 (no crossing), or
// GLC_RADIAL_RAY_UNDECIDED when a sign the answer needs is not proven (the ray through an edge or
// vertex, q on the triangle's plane within rounding): the caller then proves nothing.
const int GLC_RADIAL_RAY_UNDECIDED = 2;
// The ray the observer check casts (any direction serves; one with no simple relation to the axes
// makes a ray through an edge of an axis-aligned mesh unlikely, and such a ray only proves nothing).
const vec3 GLC_RADIAL_RAY = vec3(0.31415927f, 0.57721566f, 0.75366311f);

int glcRadialSignOf(float value, float error) {
    if (value > error + GLC_RADIAL_FLUSH_BOUND) return 1;
    if (value < -(error + GLC_RADIAL_FLUSH_BOUND)) return -1;
    return 0; // NaN included
}

int glcRadialRayCrossing(vec3 p0, vec3 p1, vec3 p2, vec3 q, vec3 d) {
    GLC_PRECISE vec3 e0 = p0 - q;
    GLC_PRECISE vec3 e1 = p1 - q;
    GLC_PRECISE vec3 e2 = p2 - q;
    int s0 = glcRadialSignOf(glcRadialTriple(e0, e1, d), glcRadialTripleError(e0, e1, d));
    int s1 = glcRadialSignOf(glcRadialTriple(e1, e2, d), glcRadialTripleError(e1, e2, d));
    int s2 = glcRadialSignOf(glcRadialTriple(e2, e0, d), glcRadialTripleError(e2, e0, d));
    // A proven pair of opposite signs: the line misses, whatever the third.
    if ((s0 * s1 < 0) || (s1 * s2 < 0) || (s2 * s0 < 0)) return 0;
    if (s0 == 0 || s1 == 0 || s2 == 0) return GLC_RADIAL_RAY_UNDECIDED;
    int side = glcRadialSignOf(glcRadialTriple(e0, e1, e2), glcRadialTripleError(e0, e1, e2));
    if (side == 0) return GLC_RADIAL_RAY_UNDECIDED;
    return side == s0 ? s0 : 0;
}

#endif
