// Orientation predicates on float points, exact by construction:
//   orient3d(a, b, c, d) = sign of det[b-a, c-a, d-a] (d above (+), on (0), below (-) the plane abc
//                          seen with abc counter-clockwise),
//   orient2d(a, b, c)    = the same for the 2D points that drop coordinate `drop` (0: keep y,z;
//                          1: keep x,z; 2: keep x,y).
// Each has a float FILTER, which returns the sign only when a bound that survives any relaxed
// compilation certifies it (else GLC_UNDECIDED; it never returns 0), and an EXACT evaluation in
// integer arithmetic (common/exact_int.glsl) that is always right. Compiled as GLSL and as C++
// (src/cpu/shader_library.hpp). The soundness argument of the filter is in docs/narrow-phase.md,
// "Why the filter is sound on any conforming device"; in short:
//   - every + - * is assumed only faithfully rounded (relative error <= u = 2^-23, any rounding
//     mode), may be contracted into an FMA (one rounding fewer) or carried in higher precision;
//   - the compiler may reassociate and factor the polynomial in the coordinate differences in any
//     way: each of its monomials then passes through at most all 26 (orient3d) operations of the
//     expression, so |computed - exact| <= gamma_26 * permanent, gamma_26 = 26u / (1 - 26u);
//   - inputs and results below 2^-126 may be flushed to zero: at most 2^-126 per input and per
//     operation, amplified by at most max(M,1)^2 (M the largest |difference|);
//   - so the sign is certified when |det| > 2^-18 * permanent + 2^-118 * max(M,1)^2 (2^-18 >
//     gamma_26 / (1 - gamma_26) * (1 + u) = 3.11e-6; 2^-118 = 256 * 2^-126 > 71 * 2^-126 with
//     room to spare), both sides computed in float by the same relaxed rules;
//   - coordinates above 2^40 go straight to the exact path: nothing can overflow, so there is no
//     infinity or NaN for a fast-math compiler to assume away.
// Two ASSUMPTIONS the argument does not prove, both allowed by GLSL and done by no compiler we
// know; the on-device self-check refuses a device that breaks either (docs/narrow-phase.md):
//   - no compiler EXPANDS a product of differences into raw coordinates ((b-a)*y into b*y - a*y).
//     That cancels products of coordinates: for a small triangle far from the origin the float
//     determinant is then mostly rounding error while the permanent stays small, and the filter
//     certifies signs at random (the self-check's far-from-origin cases fail);
//   - a denormal INPUT reaches floatBitsToUint unflushed. If a device flushes it first, the exact
//     path decides the pair with that coordinate as +-0, another pair (the denormal cases fail).

#ifndef GLC_ORIENT_GLSL
#define GLC_ORIENT_GLSL

#include "common/exact_int.glsl"

const int GLC_UNDECIDED = 2;

const float GLC_FILTER_RELATIVE = 3.814697265625e-6f; // 2^-18
const float GLC_FILTER_FLUSH = 3.0092655e-36f;        // 2^-118 (rounded up: 3.00926553e-36 > 2^-118)
const float GLC_FILTER_RANGE = 1099511627776.0f;      // 2^40

bool glcInFilterRange(vec3 v) {
    return abs(v.x) <= GLC_FILTER_RANGE && abs(v.y) <= GLC_FILTER_RANGE && abs(v.z) <= GLC_FILTER_RANGE;
}

float glcMaxComponent(vec3 v) { return max(max(v.x, v.y), v.z); }

// The filter's float evaluation: (det, permanent, max(M, 1)) of det[b-a, c-a, d-a], M the largest
// |difference|. Separate so the tests can measure its error against the exact determinant.
vec3 glcOrient3dEstimate(vec3 a, vec3 b, vec3 c, vec3 d) {
    vec3 ba = b - a;
    vec3 ca = c - a;
    vec3 da = d - a;
    float det = ba.x * (ca.y * da.z - ca.z * da.y) + ba.y * (ca.z * da.x - ca.x * da.z) +
                ba.z * (ca.x * da.y - ca.y * da.x);
    float permanent = abs(ba.x) * (abs(ca.y * da.z) + abs(ca.z * da.y)) +
                      abs(ba.y) * (abs(ca.z * da.x) + abs(ca.x * da.z)) +
                      abs(ba.z) * (abs(ca.x * da.y) + abs(ca.y * da.x));
    float m = max(glcMaxComponent(max(max(abs(ba), abs(ca)), abs(da))), 1.0f);
    return vec3(det, permanent, m);
}

// The evaluation the filter decides from: glcOrient3dEstimate in every shader. A test seam: the
// C++ view (src/cpu/shader_library.hpp) defines it first, so that tests can feed the decision
// below the float evaluations other conforming compilers could produce (a worst-case rounding, a
// rewriting). No shader defines it: GLSL builds have no variant here.
#ifndef GLC_ORIENT3D_ESTIMATE
#define GLC_ORIENT3D_ESTIMATE glcOrient3dEstimate
#endif

int glcOrient3dFilter(vec3 a, vec3 b, vec3 c, vec3 d) {
    if (!(glcInFilterRange(a) && glcInFilterRange(b) && glcInFilterRange(c) && glcInFilterRange(d)))
        return GLC_UNDECIDED;
    vec3 e = GLC_ORIENT3D_ESTIMATE(a, b, c, d); // det, permanent, max(M, 1)
    float bound = GLC_FILTER_RELATIVE * e.y + GLC_FILTER_FLUSH * (e.z * e.z);
    if (e.x > bound) return 1;
    if (-e.x > bound) return -1;
    return GLC_UNDECIDED;
}

// The coordinates a 2D view keeps: (u, w) = (y, z), (x, z) or (x, y).
int glcKeptU(int drop) { return drop == 0 ? 1 : 0; }
int glcKeptW(int drop) { return drop == 2 ? 1 : 2; }

int glcOrient2dFilter(vec3 a, vec3 b, vec3 c, int drop) {
    int u = glcKeptU(drop), w = glcKeptW(drop);
    float bu = b[u] - a[u], bw = b[w] - a[w];
    float cu = c[u] - a[u], cw = c[w] - a[w];
    if (!(glcInFilterRange(a) && glcInFilterRange(b) && glcInFilterRange(c))) return GLC_UNDECIDED;
    float l = bu * cw;
    float r = bw * cu;
    float det = l - r;
    float permanent = abs(l) + abs(r);
    float m = max(max(max(abs(bu), abs(bw)), max(abs(cu), abs(cw))), 1.0f);
    float bound = GLC_FILTER_RELATIVE * permanent + GLC_FILTER_FLUSH * m;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    return GLC_UNDECIDED;
}

// Exact sign of orient3d(a, b, c, d) (drop < 0) or of orient2d(a, b, c) dropping coordinate
// `drop` (d unused), in integers: the rows of the determinant are the exact differences b-a, c-a,
// d-a (2D: (b-a, 0), (c-a, 0), (0, 0, 1)), expanded along the first row. Degree 3 (2D: 2) in
// differences of one bit more than the inputs; the expansion's values stay below
// 3 * 2 * (2 * 2^(high-low))^3 < 2^(3(high-low) + 6) (2D: 2 * (2 * 2^(high-low))^2 < 2^(2(high-low) + 3)).
int glcOrientExact(vec3 a, vec3 b, vec3 c, vec3 d, int drop) {
    bool planar = drop >= 0;
    int u = glcKeptU(drop), w = glcKeptW(drop);
    GlcFrame f = glcFrameEmpty();
    for (int k = 0; k < 3; ++k) {
        if (planar && k != u && k != w) continue;
        f = glcFrameInclude(f, a[k]);
        f = glcFrameInclude(f, b[k]);
        f = glcFrameInclude(f, c[k]);
        if (!planar) f = glcFrameInclude(f, d[k]);
    }
    int n = planar ? glcFrameLimbs(f, 2, 3) : glcFrameLimbs(f, 3, 6);
    // Registers 0-8: row r, column k at 3r + k; 9-13: scratch.
    const int P = 9, A = 10, T1 = 11, T2 = 12, DET = 13;
    for (int r = 0; r < 3; ++r) {
        vec3 p = r == 0 ? b : (r == 1 ? c : d);
        for (int k = 0; k < 3; ++k) {
            if (planar && (r == 2 || k == 2)) {
                glcBigSetUint(3 * r + k, r == k ? 1u : 0u, n);
            } else {
                int axis = planar ? (k == 0 ? u : w) : k;
                glcBigSetFloat(P, p[axis], f, n);
                glcBigSetFloat(A, a[axis], f, n);
                glcBigSub(3 * r + k, P, A, n);
            }
        }
    }
    glcBigSetUint(DET, 0u, n);
    for (int k = 0; k < 3; ++k) {
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        glcBigMul(T1, 3 + k1, 6 + k2, n);
        glcBigMul(T2, 3 + k2, 6 + k1, n);
        glcBigSub(T1, T1, T2, n); // the minor
        glcBigMul(T2, k, T1, n);
        glcBigAdd(DET, DET, T2, n);
    }
    return glcBigSign(DET, n);
}

#endif // GLC_ORIENT_GLSL
