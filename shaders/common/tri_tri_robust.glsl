// Robust triangle-triangle intersection: the answer of the exact rational oracle
// (src/cpu/oracle/exact_tri_tri.cpp) for every finite float input, on any conforming device that
// meets the two assumptions stated in common/orient.glsl (no expansion of the filter's products
// into raw coordinates; denormal inputs read unflushed), which the on-device self-check verifies.
// Compiled as GLSL and as C++ (src/cpu/shader_library.hpp), so the CPU tests run the very same
// code. Design and proofs: docs/narrow-phase.md.
//
// Two entry points, run by two passes:
//   int  glcTriTriFiltered(a0, a1, a2, b0, b1, b2)  -> 0, 1 or GLC_UNDECIDED
//        Float filters only (common/orient.glsl), straight-line: decides pairs whose every sign it
//        needs is certified (one triangle strictly on one side of the other's plane, or two
//        triangles crossing properly). Touching, coplanar and degenerate pairs, and near misses,
//        come back GLC_UNDECIDED; the collision and query passes compact those into a list.
//   bool glcTriTriExact(a0, a1, a2, b0, b1, b2)
//        The oracle's decision procedure, sign for sign, every sign exact (filter, else integer
//        arithmetic). Run by the exact pass over the undecided list only. After the call,
//        glcExactEvaluations holds the number of predicates it evaluated in integers, and
//        glcExactFailed is true when it could not finish (never, by the argument below; the
//        passes then report an error and use no answer).
//
// Semantics: closed triangles (touching counts); coplanar pairs decided in their plane; a zero-area
// triangle is the segment between its extreme corners, or the point it covers.

#ifndef GLC_TRI_TRI_ROBUST_GLSL
#define GLC_TRI_TRI_ROBUST_GLSL

#include "common/orient.glsl"

// ---------------------------------------------------------------------------------------------
// The filtered decision (Guigue and Devillers 2003, "Fast and robust triangle-triangle overlap
// test using orientation predicates", JGT 8(1), for the crossing case), with only certified signs.

// True when all three signs are certified and equal: the triangle is strictly on one side.
bool glcStrictlyOneSide(int s0, int s1, int s2) {
    return s0 != GLC_UNDECIDED && s0 == s1 && s1 == s2;
}

int glcTriTriFiltered(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    // A certified nonzero orient3d against a triangle's plane proves that triangle is proper.
    int d0 = glcOrient3dFilter(b0, b1, b2, a0), d1 = glcOrient3dFilter(b0, b1, b2, a1),
        d2 = glcOrient3dFilter(b0, b1, b2, a2);
    if (glcStrictlyOneSide(d0, d1, d2)) return 0;
    int e0 = glcOrient3dFilter(a0, a1, a2, b0), e1 = glcOrient3dFilter(a0, a1, a2, b1),
        e2 = glcOrient3dFilter(a0, a1, a2, b2);
    if (glcStrictlyOneSide(e0, e1, e2)) return 0;
    if (d0 == GLC_UNDECIDED || d1 == GLC_UNDECIDED || d2 == GLC_UNDECIDED || e0 == GLC_UNDECIDED ||
        e1 == GLC_UNDECIDED || e2 == GLC_UNDECIDED)
        return GLC_UNDECIDED;
    // Each triangle crosses the other's plane with no corner on it. Rotate each so its first
    // corner p is the one alone on its side (rotations keep the orientation).
    vec3 p1 = a0, q1 = a1, r1 = a2;
    if (d1 != d0 && d1 != d2) { p1 = a1; q1 = a2; r1 = a0; }
    if (d2 != d0 && d2 != d1) { p1 = a2; q1 = a0; r1 = a1; }
    int dp1 = d0 != d1 && d0 != d2 ? d0 : (d1 != d0 ? d1 : d2);
    vec3 p2 = b0, q2 = b1, r2 = b2;
    if (e1 != e0 && e1 != e2) { p2 = b1; q2 = b2; r2 = b0; }
    if (e2 != e0 && e2 != e1) { p2 = b2; q2 = b0; r2 = b1; }
    int ep2 = e0 != e1 && e0 != e2 ? e0 : (e1 != e0 ? e1 : e2);
    // Orient so that p1 is below plane 2 and p2 below plane 1 (swapping two corners flips a plane).
    if (dp1 > 0) { vec3 swap = q2; q2 = r2; r2 = swap; }
    if (ep2 > 0) { vec3 swap = q1; q1 = r1; r1 = swap; }
    // The segments in which each triangle meets the other's plane lie on the planes' common line;
    // they overlap iff these two orientations are >= 0 (0: they touch, which only exact decides).
    int s = glcOrient3dFilter(p1, q1, p2, q2);
    if (s == GLC_UNDECIDED) return GLC_UNDECIDED;
    if (s < 0) return 0;
    int t = glcOrient3dFilter(p1, r1, r2, p2);
    if (t == GLC_UNDECIDED) return GLC_UNDECIDED;
    return t > 0 ? 1 : 0;
}

// ---------------------------------------------------------------------------------------------
// Exact comparisons of input floats: integer keys ordered like the values (+0 and -0 equal), so no
// float arithmetic (which may flush a denormal) is involved.

int glcKey(float f) {
    int k = floatBitsToInt(f);
    return k < 0 ? -(k & 0x7fffffff) : k;
}

ivec3 glcKey(vec3 v) { return ivec3(glcKey(v.x), glcKey(v.y), glcKey(v.z)); }

bool glcSamePoint(vec3 a, vec3 b) {
    ivec3 ka = glcKey(a), kb = glcKey(b);
    return ka.x == kb.x && ka.y == kb.y && ka.z == kb.z;
}

// ---------------------------------------------------------------------------------------------
// Deferred exact decisions. GLSL inlines every call, and an exact evaluation is large: with one
// behind every predicate call the shader would hold dozens of copies of it. So the procedure runs
// with the filters only; the first predicate they cannot decide, and whose exact sign is not yet
// known, voids the run (every later predicate answers 0 at once); glcTriTriExact then decides that
// predicate exactly (its ONE call site), records the sign and reruns.
//
// A recorded sign is found again by the predicate's KEY, never by its position in the run: the
// kind (orient3d, or orient2d dropping a coordinate) and each point as the index (0..5) of the
// first input corner with its bits. Every point a predicate is asked about is an input corner
// (shapes, edges and rotations only copy corners), so the key fixes the predicate's value. A rerun
// therefore need not repeat the last run's filter results bit for bit (a compiler may evaluate
// the inlined copies of a filter differently, or a value differently from one run to the next):
// a sign certified by a filter and one read from the cache are both exact, so every run takes the
// same path, and each rerun adds the exact sign of one more of its predicates. A run asks at most
// 6 + 6 + 6 * 18 = 120 predicates (shapes: 2 x 3 orient2d; triangle-triangle: 6 orient3d + 6
// edges x at most 18 orient2d), so at most 120 signs are recorded, within GLC_MAX_EXACT. Reaching
// the cap anyway, or a point that is not an input corner, would mean the argument above is broken:
// glcTriTriExact then sets glcExactFailed, and the passes report it as an error instead of
// answering from a voided run.

#ifndef GLC_MAX_EXACT
#define GLC_MAX_EXACT 128 // tests lower it (the C++ view; a GL test's own copy of a kernel's source)
#endif
GLC_PRIVATE uvec3 glcInputBits[6];              // the bits of the corners a0 a1 a2 b0 b1 b2 being decided
GLC_PRIVATE int glcExactEntries[GLC_MAX_EXACT]; // recorded signs: key << 2 | (sign + 1)
GLC_PRIVATE int glcExactKnown;                  // entries recorded so far
GLC_PRIVATE bool glcExactPending;               // this run met a predicate with no recorded sign
GLC_PRIVATE vec3 glcPending[4];                 // its points
GLC_PRIVATE int glcPendingDrop;                 // -1: orient3d; else orient2d dropping this coordinate
GLC_PRIVATE bool glcExactFailed;                // the last glcTriTriExact could not finish: no answer
GLC_PRIVATE uint glcExactEvaluations;           // predicates decided in integers by the last glcTriTriExact

// The predicate's key: drop + 1 in bits 0-1, then for each point (orient2d passes d = a) in 3
// bits the index of the first input corner with its bits (points are copies of corners, so bits
// suffice; +0 and -0 just give two keys for one value); -1 when a point is not an input corner.
// One loop over the corners for all four points keeps the code small: every predicate call site
// holds a copy.
int glcPredicateKey(vec3 a, vec3 b, vec3 c, vec3 d, int drop) {
    uvec3 ba = floatBitsToUint(a), bb = floatBitsToUint(b), bc = floatBitsToUint(c), bd = floatBitsToUint(d);
    int ia = 7, ib = 7, ic = 7, id = 7;
    for (int k = 5; k >= 0; --k) { // downwards, so the first matching corner is the one that stays
        uvec3 corner = glcInputBits[k];
        ia = corner == ba ? k : ia;
        ib = corner == bb ? k : ib;
        ic = corner == bc ? k : ic;
        id = corner == bd ? k : id;
    }
    if (ia == 7 || ib == 7 || ic == 7 || id == 7) return -1;
    return (drop + 1) | (ia << 2) | (ib << 5) | (ic << 8) | (id << 11);
}

int glcUndecided(vec3 a, vec3 b, vec3 c, vec3 d, int drop) {
    if (glcExactKnown > 0) {
        int key = glcPredicateKey(a, b, c, d, drop);
        for (int i = 0; i < glcExactKnown; ++i)
            if ((glcExactEntries[i] >> 2) == key) return (glcExactEntries[i] & 3) - 1;
    }
    glcExactPending = true;
    glcPending[0] = a;
    glcPending[1] = b;
    glcPending[2] = c;
    glcPending[3] = d;
    glcPendingDrop = drop;
    return 0;
}

// Zeros that comparisons of the inputs prove, with no arithmetic: a coordinate all points share
// (a zero column of the determinant) or two equal points (a zero row, or two equal rows). Flat
// cloth in an axis plane, shared corners and degenerate triangles meet them all the time; each
// one found saves an exact evaluation (not the rerun: checked where the exact evaluation is, so
// the shader holds one copy; at every predicate call it doubled the exact kernel's compile time).
bool glcSameCoordinate(vec3 a, vec3 b, vec3 c, int k) {
    int ka = glcKey(a[k]);
    return glcKey(b[k]) == ka && glcKey(c[k]) == ka;
}

bool glcOrient3dZeroByComparison(vec3 a, vec3 b, vec3 c, vec3 d) {
    for (int k = 0; k < 3; ++k)
        if (glcSameCoordinate(a, b, c, k) && glcKey(d[k]) == glcKey(a[k])) return true;
    return glcSamePoint(a, b) || glcSamePoint(a, c) || glcSamePoint(a, d) || glcSamePoint(b, c) ||
           glcSamePoint(b, d) || glcSamePoint(c, d);
}

bool glcOrient2dZeroByComparison(vec3 a, vec3 b, vec3 c, int drop) {
    int u = glcKeptU(drop), w = glcKeptW(drop);
    if (glcSameCoordinate(a, b, c, u) || glcSameCoordinate(a, b, c, w)) return true;
    return (glcKey(a[u]) == glcKey(b[u]) && glcKey(a[w]) == glcKey(b[w])) ||
           (glcKey(a[u]) == glcKey(c[u]) && glcKey(a[w]) == glcKey(c[w])) ||
           (glcKey(b[u]) == glcKey(c[u]) && glcKey(b[w]) == glcKey(c[w]));
}

int glcOrient3d(vec3 a, vec3 b, vec3 c, vec3 d) {
    if (glcExactPending) return 0;
    int s = glcOrient3dFilter(a, b, c, d);
    return s != GLC_UNDECIDED ? s : glcUndecided(a, b, c, d, -1);
}

int glcOrient2d(vec3 a, vec3 b, vec3 c, int drop) {
    if (glcExactPending) return 0;
    int s = glcOrient2dFilter(a, b, c, drop);
    return s != GLC_UNDECIDED ? s : glcUndecided(a, b, c, a, drop);
}

// The exact sign of the pending predicate: 0 when comparisons prove it, else integer arithmetic.
// Called at one place only (glcTriTriExact), so the shader holds one copy of both.
int glcPendingSign() {
    bool zero = glcPendingDrop < 0 ? glcOrient3dZeroByComparison(glcPending[0], glcPending[1], glcPending[2], glcPending[3])
                                   : glcOrient2dZeroByComparison(glcPending[0], glcPending[1], glcPending[2], glcPendingDrop);
    if (zero) return 0;
    ++glcExactEvaluations;
    return glcOrientExact(glcPending[0], glcPending[1], glcPending[2], glcPending[3], glcPendingDrop);
}

// ---------------------------------------------------------------------------------------------
// The oracle's decision procedure, sign for sign. Where the oracle picks "the" projection axis by
// magnitude, any axis whose normal component is exactly nonzero gives the same answers (the
// projection is then injective on the plane); we try axes by float magnitude and verify the exact
// sign. Loops over edges keep one copy of each test in the shader.

// p between a and b in every coordinate (exact; with collinearity: p on the closed segment ab).
bool glcBetween(vec3 a, vec3 b, vec3 p) {
    ivec3 ka = glcKey(a), kb = glcKey(b), kp = glcKey(p);
    bool ok = true;
    for (int k = 0; k < 3; ++k) ok = ok && kp[k] >= min(ka[k], kb[k]) && kp[k] <= max(ka[k], kb[k]);
    return ok;
}

// p between a and b in the two coordinates the projection keeps.
bool glcBetween2d(vec3 a, vec3 b, vec3 p, int drop) {
    ivec3 ka = glcKey(a), kb = glcKey(b), kp = glcKey(p);
    bool ok = true;
    for (int k = 0; k < 3; ++k)
        if (k != drop) ok = ok && kp[k] >= min(ka[k], kb[k]) && kp[k] <= max(ka[k], kb[k]);
    return ok;
}

// Axes ordered by decreasing float magnitude of n (a guess; callers verify exact signs).
ivec3 glcAxesByMagnitude(vec3 n) {
    float x = abs(n.x), y = abs(n.y), z = abs(n.z);
    if (x >= y && x >= z) return y >= z ? ivec3(0, 1, 2) : ivec3(0, 2, 1);
    if (y >= z) return x >= z ? ivec3(1, 0, 2) : ivec3(1, 2, 0);
    return x >= y ? ivec3(2, 0, 1) : ivec3(2, 1, 0);
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

// A triangle's point set: count 3 (proper triangle; drop = an injective projection), 2 (the
// segment v[0] v[1]) or 1 (the point v[0]).
struct GlcShape {
    vec3 v[3];
    int count;
    int drop;
};

// p in the closed proper triangle t, all coplanar, in an injective projection.
bool glcPointInTriangle2d(GlcShape t, vec3 p) {
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; ++k) {
        int s = glcOrient2d(t.v[k], t.v[(k + 1) % 3], p, t.drop);
        pos += s > 0 ? 1 : 0;
        neg += s < 0 ? 1 : 0;
    }
    return pos == 0 || neg == 0;
}

GlcShape glcShapeOf(vec3 a, vec3 b, vec3 c) {
    GlcShape s;
    s.v[0] = a;
    s.v[1] = b;
    s.v[2] = c;
    s.drop = glcPlaneAxis(a, b, c);
    s.count = 3;
    if (s.drop >= 0) return s;
    s.drop = 0;
    ivec3 ka = glcKey(a), kb = glcKey(b), kc = glcKey(c);
    if (glcSamePoint(a, b) && glcSamePoint(b, c)) {
        s.count = 1;
        return s;
    }
    // Collinear: the extreme corners along any axis where they differ are the farthest pair.
    int j = ka.x != kb.x || ka.x != kc.x ? 0 : (ka.y != kb.y || ka.y != kc.y ? 1 : 2);
    int k0 = ka[j], k1 = kb[j], k2 = kc[j];
    s.v[0] = k0 <= k1 && k0 <= k2 ? a : (k1 <= k2 ? b : c);
    s.v[1] = k0 >= k1 && k0 >= k2 ? a : (k1 >= k2 ? b : c);
    s.v[2] = s.v[1];
    s.count = 2;
    return s;
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
        if (glcPointInTriangle2d(t, p) || glcPointInTriangle2d(t, q)) return true;
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
    }
    return pos == 0 || neg == 0;
}

// All six corners share one coordinate exactly: both triangles lie in one axis plane, every
// orient3d between them is 0 (a flat cloth in its rest pose: six exact decisions saved per pair).
bool glcInOneAxisPlane(GlcShape s, GlcShape t) {
    bool found = false;
    for (int k = 0; k < 3; ++k)
        found = found || (glcSameCoordinate(s.v[0], s.v[1], s.v[2], k) && glcSameCoordinate(t.v[0], t.v[1], t.v[2], k) &&
                          glcKey(s.v[0][k]) == glcKey(t.v[0][k]));
    return found;
}

bool glcTriangleTriangle(GlcShape s, GlcShape t) {
    int d[3];
    int e[3];
    bool axisPlane = glcInOneAxisPlane(s, t);
    for (int k = 0; k < 3; ++k) d[k] = axisPlane ? 0 : glcOrient3d(s.v[0], s.v[1], s.v[2], t.v[k]);
    if ((d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0)) return false;
    for (int k = 0; k < 3; ++k) e[k] = axisPlane ? 0 : glcOrient3d(t.v[0], t.v[1], t.v[2], s.v[k]);
    if ((e[0] > 0 && e[1] > 0 && e[2] > 0) || (e[0] < 0 && e[1] < 0 && e[2] < 0)) return false;
    // Closed triangles meet iff an edge of one meets the other (see the oracle).
    for (int k = 0; k < 6; ++k) {
        int i = k % 3, j = (k + 1) % 3;
        bool first = k < 3;
        vec3 p = first ? s.v[i] : t.v[i];
        vec3 q = first ? s.v[j] : t.v[j];
        int sp = first ? e[i] : d[i];
        int sq = first ? e[j] : d[j];
        if (glcSegmentTriangle(p, q, first ? t : s, sp, sq)) return true;
    }
    return false;
}

// s has at least as many corners as t.
bool glcShapesIntersectOrdered(GlcShape s, GlcShape t) {
    if (s.count == 3) {
        if (t.count == 1)
            return glcOrient3d(s.v[0], s.v[1], s.v[2], t.v[0]) == 0 && glcPointInTriangle2d(s, t.v[0]);
        if (t.count == 2)
            return glcSegmentTriangle(t.v[0], t.v[1], s, glcOrient3d(s.v[0], s.v[1], s.v[2], t.v[0]),
                                      glcOrient3d(s.v[0], s.v[1], s.v[2], t.v[1]));
        return glcTriangleTriangle(s, t);
    }
    if (s.count == 2)
        return t.count == 2 ? glcSegmentSegment(s.v[0], s.v[1], t.v[0], t.v[1]) : glcPointSegment(t.v[0], s.v[0], s.v[1]);
    return glcSamePoint(s.v[0], t.v[0]);
}

bool glcRobustProcedure(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    GlcShape s = glcShapeOf(a0, a1, a2);
    GlcShape t = glcShapeOf(b0, b1, b2);
    return s.count >= t.count ? glcShapesIntersectOrdered(s, t) : glcShapesIntersectOrdered(t, s);
}

bool glcTriTriExact(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    glcInputBits[0] = floatBitsToUint(a0);
    glcInputBits[1] = floatBitsToUint(a1);
    glcInputBits[2] = floatBitsToUint(a2);
    glcInputBits[3] = floatBitsToUint(b0);
    glcInputBits[4] = floatBitsToUint(b1);
    glcInputBits[5] = floatBitsToUint(b2);
    glcExactKnown = 0;
    glcExactEvaluations = 0u;
    glcExactFailed = false;
    for (int run = 0; run <= GLC_MAX_EXACT; ++run) {
        glcExactPending = false;
        bool hit = glcRobustProcedure(a0, a1, a2, b0, b1, b2);
        if (!glcExactPending) return hit;
        // A voided run's answer is never returned: record the pending sign, or fail.
        int key = glcPredicateKey(glcPending[0], glcPending[1], glcPending[2], glcPending[3], glcPendingDrop);
        if (glcExactKnown == GLC_MAX_EXACT || key < 0) break;
        glcExactEntries[glcExactKnown] = (key << 2) | (glcPendingSign() + 1);
        ++glcExactKnown;
    }
    glcExactFailed = true;
    return false;
}

#endif // GLC_TRI_TRI_ROBUST_GLSL
