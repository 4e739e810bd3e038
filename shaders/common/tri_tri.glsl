// Triangle-triangle intersection, the narrow phase of the collision pipeline (TriTri in the
// AABB-octree paper, seeds/002 Alg. 3). Full design, error bounds and measured disagreements:
// docs/narrow-phase.md.
//
// Semantics: closed triangles, so touching at a vertex or along an edge counts; coplanar pairs
// are decided in their plane; a zero-area triangle is the segment between its extreme corners or
// the point it covers. Two precisions, chosen at compile time:
//   GLC_PRECISION_ROBUST  every sign is an orientation predicate on the raw float coordinates,
//                         decided by a float filter with a certified error bound and, when the
//                         filter cannot decide, exactly in double expansion arithmetic (Shewchuk
//                         1997). Agrees with the rational oracle src/cpu/exact_tri_tri on every
//                         finite float input.
//   (default)             fast: Moeller 1997, "A Fast Triangle-Triangle Intersection Test"
//                         (NoDivTriTriIsect), float arithmetic, |plane distance| < 1e-6 counts as
//                         coplanar. CPU twin: src/cpu/fast_tri_tri.cpp.
//
// Contract used by the collision passes:
//   bool triTriIntersect(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2);
// Optional hook: define GLC_COUNT_EXACT_FALLBACK() before including this file; robust calls it
// once each time a predicate falls back to the exact path.

#ifndef GLC_TRI_TRI_GLSL
#define GLC_TRI_TRI_GLSL

#ifndef GLC_COUNT_EXACT_FALLBACK
#define GLC_COUNT_EXACT_FALLBACK()
#endif

#ifdef GLC_PRECISION_ROBUST

// ---------------------------------------------------------------------------------------------
// Exact values and comparisons of float inputs, immune to denormal flushing (GLSL allows a
// float denormal to read as 0; llvmpipe sets DAZ/FTZ, which also applies to double conversion).

// The float's value as a double, built from its bits: exact for every finite float, denormals
// included (mantissa * 2^-149 is a normal double).
double glcExactValue(float f) {
    uint bits = floatBitsToUint(f);
    uint e = (bits >> 23) & 0xffu;
    uint m = bits & 0x7fffffu;
    double mag;
    if (e == 0u) {
        mag = double(m) * packDouble2x32(uvec2(0u, uint(1023 - 149) << 20)); // m * 2^-149
    } else {
        mag = packDouble2x32(uvec2(m << 29, ((e + 896u) << 20) | (m >> 3))); // 896 = 1023 - 127
    }
    return (bits >> 31) != 0u ? -mag : mag;
}

dvec3 glcExactValue(vec3 v) { return dvec3(glcExactValue(v.x), glcExactValue(v.y), glcExactValue(v.z)); }

// An integer key ordered like the float values (+0 and -0 share key 0): exact comparisons of
// inputs by integer compares, with no float arithmetic that could flush a denormal.
int glcKey(float f) {
    int k = floatBitsToInt(f);
    return k < 0 ? -(k & 0x7fffffff) : k;
}

ivec3 glcKey(vec3 v) { return ivec3(glcKey(v.x), glcKey(v.y), glcKey(v.z)); }

// ---------------------------------------------------------------------------------------------
// The exact path: sign of det[b-a, c-a, d-a] as a sum of 24 degree-3 monomials of the raw
// coordinates, [b,c,d] - [a,c,d] - [b,a,d] - [b,c,a] with [p,q,r] = p.(q x r) (differences of
// floats are not exact in double; products of two floats are). Each monomial x*y*z is split
// exactly into two doubles (Dekker: x*y has at most 48 significant bits, its halves at most 26,
// each half times the float z at most 50), and all are summed exactly into a nonoverlapping
// expansion (Shewchuk 1997, GROW-EXPANSION with Knuth's TWO-SUM and zero elimination); the sign
// is that of the largest component. Every component is a multiple of 2^-447 and below 2^385: no
// double overflows, underflows or denormals. orient2d is evaluated here too, lifted to 3D:
// orient3d((u_a,w_a,0), (u_b,w_b,0), (u_c,w_c,0), (0,0,1)) = orient2d(a, b, c).
// This function has ONE call site (triTriIntersect), so the shader holds one copy of it.

double glcExpansion[48]; // per invocation
int glcExpansionLength;

const ivec4 GLC_TRIPLES[4] = ivec4[4](ivec4(1, 2, 3, 1), ivec4(0, 2, 3, -1), ivec4(1, 0, 3, -1), ivec4(1, 2, 0, -1));
const ivec4 GLC_PERMUTATIONS[6] = ivec4[6](ivec4(0, 1, 2, 1), ivec4(0, 2, 1, -1), ivec4(1, 2, 0, 1), ivec4(1, 0, 2, -1),
                                           ivec4(2, 0, 1, 1), ivec4(2, 1, 0, -1));

int glcOrient3dExact(vec3 fa, vec3 fb, vec3 fc, vec3 fd) {
    dvec3 pts[4] = dvec3[4](glcExactValue(fa), glcExactValue(fb), glcExactValue(fc), glcExactValue(fd));
    glcExpansionLength = 0;
    for (int t = 0; t < 24; ++t) {
        ivec4 tr = GLC_TRIPLES[t / 6], pm = GLC_PERMUTATIONS[t % 6];
        double x = pts[tr.x][pm.x], y = pts[tr.y][pm.y], z = pts[tr.z][pm.z];
        if (tr.w * pm.w < 0) x = -x;
        precise double p = x * y;
        precise double c = 134217729.0LF * p; // 2^27 + 1
        precise double hi = c - (c - p);
        precise double lo = p - hi;
        precise double halves[2] = double[2](hi * z, lo * z);
        for (int h = 0; h < 2; ++h) {
            precise double q = halves[h];
            if (q == 0.0LF) continue;
            int m = 0;
            for (int i = 0; i < glcExpansionLength; ++i) {
                double ei = glcExpansion[i];
                precise double s = q + ei;
                precise double bv = s - q;
                precise double av = s - bv;
                precise double err = (q - av) + (ei - bv);
                q = s;
                if (err != 0.0LF) {
                    glcExpansion[m] = err;
                    ++m;
                }
            }
            if (q != 0.0LF) {
                glcExpansion[m] = q;
                ++m;
            }
            glcExpansionLength = m;
        }
    }
    return glcExpansionLength == 0 ? 0 : (glcExpansion[glcExpansionLength - 1] > 0.0LF ? 1 : -1);
}

// ---------------------------------------------------------------------------------------------
// Deferred exact decisions. The decision procedure below is deterministic, so it asks the same
// questions in the same order as long as the answers are the same. It runs with the float
// filters only; the first predicate they cannot decide beyond the answers already known stops
// the run (every later predicate returns 0 at once and the run's answer is void). The driver
// then decides that predicate exactly, appends its sign and reruns. A run asks at most 6 + 114
// predicates (shapes: 2 x 3 orient2d; triangle-triangle: 6 orient3d + 6 edges x at most 18
// orient2d), within GLC_MAX_EXACT.

const int GLC_MAX_EXACT = 128;
int glcExactSigns[GLC_MAX_EXACT];
int glcExactKnown;    // exact answers found so far
int glcExactAsked;    // undecided predicates met in this run
bool glcExactPending; // this run met one beyond the known answers
vec3 glcPending[4];   // its points (orient2d lifted)

int glcUndecided(vec3 a, vec3 b, vec3 c, vec3 d) {
    if (glcExactAsked < glcExactKnown) {
        int s = glcExactSigns[glcExactAsked];
        ++glcExactAsked;
        return s;
    }
    glcExactPending = true;
    glcPending[0] = a;
    glcPending[1] = b;
    glcPending[2] = c;
    glcPending[3] = d;
    return 0;
}

// ---------------------------------------------------------------------------------------------
// Float filters (Shewchuk 1997, sec. 4.2, bound A), plus an absolute term for denormal flushing
// and a range guard against overflow. `precise` forbids FMA contraction and reassociation, so
// every operation is one correctly rounded IEEE float operation (GLSL 4.30, sec. 4.7.1).
// Derivation: docs/narrow-phase.md.

const float GLC_ORIENT2D_BOUND = 1.7881400e-7;   // >= (3 + 16u)u, u = 2^-24
const float GLC_ORIENT3D_BOUND = 4.1723290e-7;   // >= (7 + 56u)u
const float GLC_FLUSH_TERM = 3.0092655e-36;      // 2^-118 = 256 * 2^-126 (smallest normal float)
const float GLC_FILTER_RANGE = 1099511627776.0;  // 2^40: larger coordinates go straight to exact

bool glcInRange(vec3 v) { return all(lessThanEqual(abs(v), vec3(GLC_FILTER_RANGE))); }

// Sign of det[b-a, c-a, d-a] = (b-a) x (c-a) . (d-a) (d above (+) or below (-) the plane abc)
// when the filter certifies it, else GLC_UNDECIDED.
const int GLC_UNDECIDED = 2;

int glcOrient3dFilter(vec3 a, vec3 b, vec3 c, vec3 d) {
    if (glcInRange(a) && glcInRange(b) && glcInRange(c) && glcInRange(d)) {
        precise vec3 ba = b - a;
        precise vec3 ca = c - a;
        precise vec3 da = d - a;
        precise float p0 = ca.y * da.z, p1 = ca.z * da.y;
        precise float p2 = ca.z * da.x, p3 = ca.x * da.z;
        precise float p4 = ca.x * da.y, p5 = ca.y * da.x;
        precise float det = ba.x * (p0 - p1) + ba.y * (p2 - p3) + ba.z * (p4 - p5);
        precise float perm = abs(ba.x) * (abs(p0) + abs(p1)) + abs(ba.y) * (abs(p2) + abs(p3)) +
                             abs(ba.z) * (abs(p4) + abs(p5));
        vec3 m3 = max(max(abs(ba), abs(ca)), abs(da));
        float m = max(max(max(m3.x, m3.y), m3.z), 1.0);
        precise float bound = GLC_ORIENT3D_BOUND * perm + GLC_FLUSH_TERM * (m * m);
        if (det > bound) return 1;
        if (-det > bound) return -1;
    }
    return GLC_UNDECIDED;
}

// The exact sign of det[b-a, c-a, d-a]: the filter's, else the exact path's.
int glcOrient3d(vec3 a, vec3 b, vec3 c, vec3 d) {
    if (glcExactPending) return 0;
    int s = glcOrient3dFilter(a, b, c, d);
    return s != GLC_UNDECIDED ? s : glcUndecided(a, b, c, d);
}

// The 2D view of a point that drops coordinate `drop` (0: (y,z), 1: (x,z), 2: (x,y)), as in the
// oracle's Projection.
vec2 glcProject(vec3 v, int drop) { return drop == 0 ? v.yz : (drop == 1 ? v.xz : v.xy); }

// Sign of (b.u-a.u)(c.w-a.w) - (b.w-a.w)(c.u-a.u) in the projection dropping `drop` when the
// filter certifies it, else GLC_UNDECIDED.
int glcOrient2dFilter(vec3 fa, vec3 fb, vec3 fc, int drop) {
    vec2 a = glcProject(fa, drop), b = glcProject(fb, drop), c = glcProject(fc, drop);
    if (all(lessThanEqual(max(max(abs(a), abs(b)), abs(c)), vec2(GLC_FILTER_RANGE)))) {
        precise vec2 ba = b - a;
        precise vec2 ca = c - a;
        precise float l = ba.x * ca.y;
        precise float r = ba.y * ca.x;
        precise float det = l - r;
        precise float perm = abs(l) + abs(r);
        vec2 m2 = max(abs(ba), abs(ca));
        float m = max(max(m2.x, m2.y), 1.0);
        precise float bound = GLC_ORIENT2D_BOUND * perm + GLC_FLUSH_TERM * m;
        if (det > bound) return 1;
        if (-det > bound) return -1;
    }
    return GLC_UNDECIDED;
}

// The exact sign of the orient2d: the filter's, else the exact path's (lifted to orient3d).
int glcOrient2d(vec3 a, vec3 b, vec3 c, int drop) {
    if (glcExactPending) return 0;
    int s = glcOrient2dFilter(a, b, c, drop);
    if (s != GLC_UNDECIDED) return s;
    vec2 pa = glcProject(a, drop), pb = glcProject(b, drop), pc = glcProject(c, drop);
    return glcUndecided(vec3(pa, 0.0), vec3(pb, 0.0), vec3(pc, 0.0), vec3(0.0, 0.0, 1.0));
}

// ---------------------------------------------------------------------------------------------
// The oracle's decision procedure (src/cpu/exact_tri_tri.cpp), sign for sign. Where the oracle
// picks "the" projection axis by magnitude, any axis whose normal component is exactly nonzero
// gives the same answers (the projection is then injective on the plane); we pick by float
// magnitude and verify the exact sign. Loops over edges keep one copy of each test in the shader.

// p between a and b in every coordinate (exact; with collinearity: p on the closed segment ab).
bool glcBetween(vec3 a, vec3 b, vec3 p) {
    ivec3 ka = glcKey(a), kb = glcKey(b), kp = glcKey(p);
    return all(greaterThanEqual(kp, min(ka, kb))) && all(lessThanEqual(kp, max(ka, kb)));
}

// p between a and b in the two coordinates the projection keeps.
bool glcBetween2d(vec3 a, vec3 b, vec3 p, int drop) {
    ivec3 ka = glcKey(a), kb = glcKey(b), kp = glcKey(p);
    bvec3 in3 = greaterThanEqual(kp, min(ka, kb));
    bvec3 in3hi = lessThanEqual(kp, max(ka, kb));
    bool inX = in3.x && in3hi.x, inY = in3.y && in3hi.y, inZ = in3.z && in3hi.z;
    return drop == 0 ? (inY && inZ) : (drop == 1 ? (inX && inZ) : (inX && inY));
}

// Axes ordered by decreasing float magnitude of n (a guess; callers verify exact signs).
ivec3 glcAxesByMagnitude(vec3 n) {
    vec3 a = abs(n);
    if (a.x >= a.y && a.x >= a.z) return a.y >= a.z ? ivec3(0, 1, 2) : ivec3(0, 2, 1);
    if (a.y >= a.z) return a.x >= a.z ? ivec3(1, 0, 2) : ivec3(1, 2, 0);
    return a.x >= a.y ? ivec3(2, 0, 1) : ivec3(2, 1, 0);
}

// An axis whose component of (b-a) x (c-a) is exactly nonzero, or -1 when a, b, c are collinear.
int glcPlaneAxis(vec3 a, vec3 b, vec3 c) {
    ivec3 order = glcAxesByMagnitude(cross(b - a, c - a));
    for (int i = 0; i < 3; ++i) {
        if (glcOrient2d(a, b, c, order[i]) != 0) return order[i];
    }
    return -1;
}

// Closed segments ab and cd, all four coplanar, in an injective projection.
bool glcSegmentsIntersect2d(vec3 a, vec3 b, vec3 c, vec3 d, int drop) {
    int o1 = glcOrient2d(a, b, c, drop), o2 = glcOrient2d(a, b, d, drop);
    int o3 = glcOrient2d(c, d, a, drop), o4 = glcOrient2d(c, d, b, drop);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && glcBetween2d(a, b, c, drop)) || (o2 == 0 && glcBetween2d(a, b, d, drop)) ||
           (o3 == 0 && glcBetween2d(c, d, a, drop)) || (o4 == 0 && glcBetween2d(c, d, b, drop));
}

// p in the closed non-degenerate triangle t, all coplanar, in an injective projection.
bool glcPointInTriangle2d(vec3 t[3], vec3 p, int drop) {
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; ++k) {
        int s = glcOrient2d(t[k], t[(k + 1) % 3], p, drop);
        pos += s > 0 ? 1 : 0;
        neg += s < 0 ? 1 : 0;
        if (pos > 0 && neg > 0) return false;
    }
    return true;
}

// A triangle's point set: count 3 (proper triangle; drop = an injective projection), 2 (the
// segment v[0] v[1]) or 1 (the point v[0]).
struct GlcShape {
    vec3 v[3];
    int count;
    int drop;
};

GlcShape glcShapeOf(vec3 a, vec3 b, vec3 c) {
    int axis = glcPlaneAxis(a, b, c);
    if (axis >= 0) return GlcShape(vec3[3](a, b, c), 3, axis);
    ivec3 ka = glcKey(a), kb = glcKey(b), kc = glcKey(c);
    if (ka == kb && kb == kc) return GlcShape(vec3[3](a, a, a), 1, 0);
    // Collinear: the extreme corners along any axis where they differ are the farthest pair.
    int j = ka.x != kb.x || ka.x != kc.x ? 0 : (ka.y != kb.y || ka.y != kc.y ? 1 : 2);
    int k0 = ka[j], k1 = kb[j], k2 = kc[j];
    vec3 lo = k0 <= k1 && k0 <= k2 ? a : (k1 <= k2 ? b : c);
    vec3 hi = k0 >= k1 && k0 >= k2 ? a : (k1 >= k2 ? b : c);
    return GlcShape(vec3[3](lo, hi, hi), 2, 0);
}

bool glcPointSegment(vec3 p, vec3 a, vec3 b) {
    if (!glcBetween(a, b, p)) return false;
    for (int k = 0; k < 3; ++k) {
        if (glcOrient2d(a, b, p, k) != 0) return false;
    }
    return true;
}

bool glcSegmentSegment(vec3 a, vec3 b, vec3 c, vec3 d) {
    if (glcOrient3d(a, b, c, d) != 0) return false; // skew lines never meet
    int drop = glcPlaneAxis(a, b, c);
    if (drop < 0) drop = glcPlaneAxis(a, b, d);
    if (drop < 0) {
        // All four collinear: every orient2d is 0, so only the betweenness tests remain.
        return glcBetween(a, b, c) || glcBetween(a, b, d) || glcBetween(c, d, a) || glcBetween(c, d, b);
    }
    return glcSegmentsIntersect2d(a, b, c, d, drop);
}

// Segment pq against the proper triangle t, given sp, sq = orient3d(t, p), orient3d(t, q).
bool glcSegmentTriangle(vec3 p, vec3 q, GlcShape t, int sp, int sq) {
    if (sp * sq > 0) return false;
    if (sp == 0 && sq == 0) { // coplanar: an endpoint inside, or the segment crosses an edge
        if (glcPointInTriangle2d(t.v, p, t.drop) || glcPointInTriangle2d(t.v, q, t.drop)) return true;
        for (int k = 0; k < 3; ++k) {
            if (glcSegmentsIntersect2d(p, q, t.v[k], t.v[(k + 1) % 3], t.drop)) return true;
        }
        return false;
    }
    // One point on the plane: in the closed triangle iff the line pq passes on the same side
    // (or on) each directed edge.
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; ++k) {
        int s = glcOrient3d(p, q, t.v[k], t.v[(k + 1) % 3]);
        pos += s > 0 ? 1 : 0;
        neg += s < 0 ? 1 : 0;
        if (pos > 0 && neg > 0) return false;
    }
    return true;
}

// Signs of orient3d(t, corner of s) for each corner; true when all are strictly on one side.
bool glcOneSide(GlcShape t, GlcShape s, out int signs[3]) {
    for (int k = 0; k < 3; ++k) signs[k] = glcOrient3d(t.v[0], t.v[1], t.v[2], s.v[k]);
    return (signs[0] > 0 && signs[1] > 0 && signs[2] > 0) || (signs[0] < 0 && signs[1] < 0 && signs[2] < 0);
}

bool glcTriangleTriangle(GlcShape s, GlcShape t) {
    int d[3], e[3];
    if (glcOneSide(s, t, d)) return false; // t strictly on one side of s's plane
    if (glcOneSide(t, s, e)) return false;
    // Closed triangles meet iff an edge of one meets the other (see the oracle).
    for (int k = 0; k < 6; ++k) {
        int i = k % 3, j = (k + 1) % 3;
        bool first = k < 3;
        vec3 p = first ? s.v[i] : t.v[i], q = first ? s.v[j] : t.v[j];
        int sp = first ? e[i] : d[i], sq = first ? e[j] : d[j];
        if (glcSegmentTriangle(p, q, first ? t : s, sp, sq)) return true;
    }
    return false;
}

// s has at least as many corners as t.
bool glcShapesIntersectOrdered(GlcShape s, GlcShape t) {
    if (s.count == 3) {
        if (t.count == 1) {
            return glcOrient3d(s.v[0], s.v[1], s.v[2], t.v[0]) == 0 && glcPointInTriangle2d(s.v, t.v[0], s.drop);
        }
        if (t.count == 2) {
            return glcSegmentTriangle(t.v[0], t.v[1], s, glcOrient3d(s.v[0], s.v[1], s.v[2], t.v[0]),
                                      glcOrient3d(s.v[0], s.v[1], s.v[2], t.v[1]));
        }
        return glcTriangleTriangle(s, t);
    }
    if (s.count == 2) return t.count == 2 ? glcSegmentSegment(s.v[0], s.v[1], t.v[0], t.v[1]) : glcPointSegment(t.v[0], s.v[0], s.v[1]);
    return glcKey(s.v[0]) == glcKey(t.v[0]);
}

bool glcRobustTriTri(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    GlcShape s = glcShapeOf(a0, a1, a2), t = glcShapeOf(b0, b1, b2);
    return s.count >= t.count ? glcShapesIntersectOrdered(s, t) : glcShapesIntersectOrdered(t, s);
}

// The common case in straight-line code: both triangles certified proper (a nonzero normal
// component) and one certified strictly on one side of the other's plane. These are the oracle's
// first decisions, so "separated" here is its answer; anything else goes to the full procedure.
bool glcCertifiedSeparated(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    int sa = glcOrient2dFilter(a0, a1, a2, glcAxesByMagnitude(cross(a1 - a0, a2 - a0)).x);
    int sb = glcOrient2dFilter(b0, b1, b2, glcAxesByMagnitude(cross(b1 - b0, b2 - b0)).x);
    if (sa == 0 || sa == GLC_UNDECIDED || sb == 0 || sb == GLC_UNDECIDED) return false;
    int d0 = glcOrient3dFilter(a0, a1, a2, b0), d1 = glcOrient3dFilter(a0, a1, a2, b1), d2 = glcOrient3dFilter(a0, a1, a2, b2);
    if ((d0 == 1 && d1 == 1 && d2 == 1) || (d0 == -1 && d1 == -1 && d2 == -1)) return true;
    int e0 = glcOrient3dFilter(b0, b1, b2, a0), e1 = glcOrient3dFilter(b0, b1, b2, a1), e2 = glcOrient3dFilter(b0, b1, b2, a2);
    return (e0 == 1 && e1 == 1 && e2 == 1) || (e0 == -1 && e1 == -1 && e2 == -1);
}

bool triTriIntersect(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    if (glcCertifiedSeparated(a0, a1, a2, b0, b1, b2)) return false;
    glcExactKnown = 0;
    bool hit = false;
    for (int run = 0; run <= GLC_MAX_EXACT; ++run) {
        glcExactAsked = 0;
        glcExactPending = false;
        hit = glcRobustTriTri(a0, a1, a2, b0, b1, b2);
        if (!glcExactPending || glcExactKnown == GLC_MAX_EXACT) break; // the bound is never reached (see above)
        GLC_COUNT_EXACT_FALLBACK();
        glcExactSigns[glcExactKnown] = glcOrient3dExact(glcPending[0], glcPending[1], glcPending[2], glcPending[3]);
        ++glcExactKnown;
    }
    return hit;
}

#else // fast

// ---------------------------------------------------------------------------------------------
// Moeller 1997, NoDivTriTriIsect, transcribed operation for operation (the CPU twin in
// src/cpu/fast_tri_tri.cpp follows the same order). GLC_FAST_EPSILON is the paper's EPSILON:
// an absolute threshold on the unnormalised plane distances N.x + d (units: length^3).
// `precise` (no FMA contraction) and the written-out dot product make the answers reproducible:
// every conforming device computes the same floats as the twin (denormal flushing aside), so
// fast's disagreements with the oracle measured once hold everywhere. On llvmpipe, without them,
// the GPU differed from the twin on 0.8-1.9 % of the one-ulp and scaled sets (docs/narrow-phase.md).

const float GLC_FAST_EPSILON = 0.000001;

// Coplanar triangles: edge-edge crossings and corner containment in the axis-aligned plane where
// the projected area of N is largest (Moeller 1997, coplanar_tri_tri).
bool glcFastEdgeEdge(vec2 v0, vec2 a, vec2 u0, vec2 u1) {
    precise float bx = u0.x - u1.x, by = u0.y - u1.y;
    precise float cx = v0.x - u0.x, cy = v0.y - u0.y;
    precise float f = a.y * bx - a.x * by;
    precise float d = by * cx - bx * cy;
    if ((f > 0.0 && d >= 0.0 && d <= f) || (f < 0.0 && d <= 0.0 && d >= f)) {
        precise float e = a.x * cy - a.y * cx;
        if (f > 0.0) {
            if (e >= 0.0 && e <= f) return true;
        } else {
            if (e <= 0.0 && e >= f) return true;
        }
    }
    return false;
}

bool glcFastEdgeAgainstTriEdges(vec2 v0, vec2 v1, vec2 u0, vec2 u1, vec2 u2) {
    precise vec2 a = v1 - v0;
    return glcFastEdgeEdge(v0, a, u0, u1) || glcFastEdgeEdge(v0, a, u1, u2) || glcFastEdgeEdge(v0, a, u2, u0);
}

bool glcFastPointInTri(vec2 v0, vec2 u0, vec2 u1, vec2 u2) {
    precise float a = u1.y - u0.y, b = -(u1.x - u0.x), c = -a * u0.x - b * u0.y;
    precise float d0 = a * v0.x + b * v0.y + c;
    a = u2.y - u1.y;
    b = -(u2.x - u1.x);
    c = -a * u1.x - b * u1.y;
    precise float d1 = a * v0.x + b * v0.y + c;
    a = u0.y - u2.y;
    b = -(u0.x - u2.x);
    c = -a * u2.x - b * u2.y;
    precise float d2 = a * v0.x + b * v0.y + c;
    return d0 * d1 > 0.0 && d0 * d2 > 0.0;
}

bool glcFastCoplanar(vec3 n, vec3 v0, vec3 v1, vec3 v2, vec3 u0, vec3 u1, vec3 u2) {
    vec3 a = abs(n);
    int i0, i1;
    if (a.x > a.y) {
        if (a.x > a.z) { i0 = 1; i1 = 2; } else { i0 = 0; i1 = 1; }
    } else {
        if (a.z > a.y) { i0 = 0; i1 = 1; } else { i0 = 0; i1 = 2; }
    }
    precise vec2 pv0 = vec2(v0[i0], v0[i1]), pv1 = vec2(v1[i0], v1[i1]), pv2 = vec2(v2[i0], v2[i1]);
    precise vec2 pu0 = vec2(u0[i0], u0[i1]), pu1 = vec2(u1[i0], u1[i1]), pu2 = vec2(u2[i0], u2[i1]);
    if (glcFastEdgeAgainstTriEdges(pv0, pv1, pu0, pu1, pu2)) return true;
    if (glcFastEdgeAgainstTriEdges(pv1, pv2, pu0, pu1, pu2)) return true;
    if (glcFastEdgeAgainstTriEdges(pv2, pv0, pu0, pu1, pu2)) return true;
    return glcFastPointInTri(pv0, pu0, pu1, pu2) || glcFastPointInTri(pu0, pv0, pv1, pv2);
}

// NEWCOMPUTE_INTERVALS: the projection interval of one triangle on the intersection line, as
// (a, b, c, x0, x1). Returns false when both triangles are coplanar.
bool glcFastInterval(float vv0, float vv1, float vv2, float d0, float d1, float d2, float d0d1, float d0d2,
                     out float a, out float b, out float c, out float x0, out float x1) {
    a = 0.0; b = 0.0; c = 0.0; x0 = 0.0; x1 = 0.0;
    if (d0d1 > 0.0) {
        a = vv2; b = (vv0 - vv2) * d2; c = (vv1 - vv2) * d2; x0 = d2 - d0; x1 = d2 - d1;
    } else if (d0d2 > 0.0) {
        a = vv1; b = (vv0 - vv1) * d1; c = (vv2 - vv1) * d1; x0 = d1 - d0; x1 = d1 - d2;
    } else if (d1 * d2 > 0.0 || d0 != 0.0) {
        a = vv0; b = (vv1 - vv0) * d0; c = (vv2 - vv0) * d0; x0 = d0 - d1; x1 = d0 - d2;
    } else if (d1 != 0.0) {
        a = vv1; b = (vv0 - vv1) * d1; c = (vv2 - vv1) * d1; x0 = d1 - d0; x1 = d1 - d2;
    } else if (d2 != 0.0) {
        a = vv2; b = (vv0 - vv2) * d2; c = (vv1 - vv2) * d2; x0 = d2 - d0; x1 = d2 - d1;
    } else {
        return false;
    }
    return true;
}

// dot() may sum in any order; Moeller's DOT is ((x + y) + z).
float glcFastDot(vec3 a, vec3 b) {
    precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
    return r;
}

bool triTriIntersect(vec3 v0, vec3 v1, vec3 v2, vec3 u0, vec3 u1, vec3 u2) {
    precise vec3 e1 = v1 - v0, e2 = v2 - v0;
    precise vec3 n1 = cross(e1, e2);
    precise float d1 = -glcFastDot(n1, v0);
    precise float du0 = glcFastDot(n1, u0) + d1, du1 = glcFastDot(n1, u1) + d1, du2 = glcFastDot(n1, u2) + d1;
    if (abs(du0) < GLC_FAST_EPSILON) du0 = 0.0;
    if (abs(du1) < GLC_FAST_EPSILON) du1 = 0.0;
    if (abs(du2) < GLC_FAST_EPSILON) du2 = 0.0;
    precise float du0du1 = du0 * du1, du0du2 = du0 * du2;
    if (du0du1 > 0.0 && du0du2 > 0.0) return false;

    e1 = u1 - u0;
    e2 = u2 - u0;
    precise vec3 n2 = cross(e1, e2);
    precise float d2 = -glcFastDot(n2, u0);
    precise float dv0 = glcFastDot(n2, v0) + d2, dv1 = glcFastDot(n2, v1) + d2, dv2 = glcFastDot(n2, v2) + d2;
    if (abs(dv0) < GLC_FAST_EPSILON) dv0 = 0.0;
    if (abs(dv1) < GLC_FAST_EPSILON) dv1 = 0.0;
    if (abs(dv2) < GLC_FAST_EPSILON) dv2 = 0.0;
    precise float dv0dv1 = dv0 * dv1, dv0dv2 = dv0 * dv2;
    if (dv0dv1 > 0.0 && dv0dv2 > 0.0) return false;

    precise vec3 dir = cross(n1, n2);
    precise float mx = abs(dir.x);
    int index = 0;
    precise float bb = abs(dir.y), cc = abs(dir.z);
    if (bb > mx) { mx = bb; index = 1; }
    if (cc > mx) { mx = cc; index = 2; }
    precise float vp0 = v0[index], vp1 = v1[index], vp2 = v2[index];
    precise float up0 = u0[index], up1 = u1[index], up2 = u2[index];

    precise float a, b, c, x0, x1;
    if (!glcFastInterval(vp0, vp1, vp2, dv0, dv1, dv2, dv0dv1, dv0dv2, a, b, c, x0, x1))
        return glcFastCoplanar(n1, v0, v1, v2, u0, u1, u2);
    precise float d, e, f, y0, y1;
    if (!glcFastInterval(up0, up1, up2, du0, du1, du2, du0du1, du0du2, d, e, f, y0, y1))
        return glcFastCoplanar(n1, v0, v1, v2, u0, u1, u2);

    precise float xx = x0 * x1, yy = y0 * y1, xxyy = xx * yy;
    precise float tmp = a * xxyy;
    precise vec2 isect1 = vec2(tmp + b * x1 * yy, tmp + c * x0 * yy);
    tmp = d * xxyy;
    precise vec2 isect2 = vec2(tmp + e * xx * y1, tmp + f * xx * y0);
    if (isect1.x > isect1.y) isect1 = isect1.yx;
    if (isect2.x > isect2.y) isect2 = isect2.yx;
    return !(isect1.y < isect2.x || isect2.y < isect1.x);
}

#endif // GLC_PRECISION_ROBUST

#endif // GLC_TRI_TRI_GLSL
