// Radial view-based culling's footprints (decision 0025, "Decision" 3): a cone of directions, seen
// from the observer, that holds every direction in which a triangle can lie during the substep.
// Compiled as GLSL and as C++ (src/cpu/radial_library.hpp); tested against sampled motions
// (tests/unit/radial_footprint_test.cpp).
//
//   vec4 glcRadialFootprint(p0, p1, p2, q, p0End, p1End, p2End, qEnd)
//        (unit axis, cosine of the half-angle). Every direction (x - q(t)) / |x - q(t)| with x in
//        the triangle at t and t in [0, 1] is within the half-angle of the axis. A cosine of -1
//        means "every direction" (the observer may be in the swept triangle's hull, or the
//        directions span a half-space or more).
//   bool glcRadialFootprintsMeet(vec4 a, vec4 b)
//        False only when no direction is in both cones (conservative: true when in doubt).
//
// Why the cone holds the footprint: a point of the triangle is a material point with fixed
// barycentric weights w, so x(t) - q(t) = (1 - t) (sum w_i p_i - q) + t (sum w_i p_iEnd - qEnd)
// lies in the convex hull H of the 6 differences p_i - q and p_iEnd - qEnd. When those 6 are all
// within an angle below 90 degrees of an axis, so is every point of H (a circular cone of
// half-angle < 90 degrees is convex), and so are their directions. Rounding: the differences are
// computed in float (relative error below 2^-23 per coordinate, a direction error below 2^-21
// rad), the cosines of their angles to the axis too (a few ulps); GLC_FOOTPRINT_SLACK, subtracted
// from the cosine, covers both with a wide margin (it widens the cone by about 10^-2 degrees at
// most).
//
// GLSL subset shared with C++: no swizzles, no out/inout parameters, float literals with `f`.

#ifndef GLC_RADIAL_FOOTPRINT_GLSL
#define GLC_RADIAL_FOOTPRINT_GLSL

// Cosine slack: a cone's cosine is lowered by this much, and cones meet when their axes' cosine is
// within this much of the limit. Range > 2^-18 (the rounding above); suggested 2^-14 (a cone of
// half-angle theta widens by at most 2^-14 / sin(theta) rad, and never for theta near 0 by more
// than sqrt(2 * 2^-14) ~ 0.011 rad).
const float GLC_FOOTPRINT_SLACK = 6.103515625e-5f; // 2^-14

vec4 glcRadialEverywhere() {
    return vec4(0.0f, 0.0f, 1.0f, -1.0f);
}

vec4 glcRadialFootprint(vec3 p0, vec3 p1, vec3 p2, vec3 q, vec3 p0End, vec3 p1End, vec3 p2End, vec3 qEnd) {
    // The 6 differences: each vertex minus the observer, at the start and at the end.
    vec3 d0 = p0 - q, d1 = p1 - q, d2 = p2 - q, e0 = p0End - qEnd, e1 = p1End - qEnd, e2 = p2End - qEnd;
    float l0 = length(d0), l1 = length(d1), l2 = length(d2), m0 = length(e0), m1 = length(e1), m2 = length(e2);
    if (!(min(min(min(l0, l1), l2), min(min(m0, m1), m2)) > 0.0f)) return glcRadialEverywhere(); // also NaN
    vec3 sum = d0 / l0 + d1 / l1 + d2 / l2 + e0 / m0 + e1 / m1 + e2 / m2;
    float size = length(sum);
    if (!(size > 1.0e-3f)) return glcRadialEverywhere();
    vec3 axis = sum / size;
    // The cosine of each difference's angle to the axis; the smallest bounds them all.
    float c = min(min(min(dot(axis, d0) / l0, dot(axis, d1) / l1), dot(axis, d2) / l2),
                  min(min(dot(axis, e0) / m0, dot(axis, e1) / m1), dot(axis, e2) / m2));
    c -= GLC_FOOTPRINT_SLACK;
    // Half-angles of 90 degrees or more: the hull may hold directions beyond the 6 (the cone is
    // then not convex), or the observer itself.
    if (!(c > GLC_FOOTPRINT_SLACK)) return glcRadialEverywhere();
    // The axis is not exactly unit after rounding: the cosines above were computed with it as it
    // is, and the meeting test below uses it as it is, with the same slack.
    return vec4(axis, c);
}

bool glcRadialFootprintsMeet(vec4 a, vec4 b) {
    float ca = a.w, cb = b.w;
    if (ca <= -1.0f || cb <= -1.0f) return true;
    // Half-angles theta_a, theta_b in (0, 90 degrees): the cones meet when the axes' angle is at
    // most theta_a + theta_b, i.e. cos(angle) >= cos(theta_a + theta_b) = ca cb - sa sb.
    float sa = sqrt(max(1.0f - ca * ca, 0.0f)), sb = sqrt(max(1.0f - cb * cb, 0.0f));
    float axes = dot(vec3(a.x, a.y, a.z), vec3(b.x, b.y, b.z));
    return axes >= ca * cb - sa * sb - GLC_FOOTPRINT_SLACK;
}


// Segment observers (decision 0025, "Segment observers"; the observer is the segment from a to b,
// each end moving linearly). A point x is seen along its *fiber*: the ray from its foot s(u(x)) —
// the segment's nearest point, u(x) = clamp((x - a) . (b - a) / |b - a|^2, 0, 1) — through x. The
// fibers of all points off the segment never cross, so two triangles can meet only where they
// share a fiber, and a fiber is named by its foot's u and its direction. A triangle's footprint is
// then bounded by an interval of u (its *feet*) and a cone of directions.
//
//   vec2 glcRadialFeet(p0, p1, p2, a, b, p0End, p1End, p2End, aEnd, bEnd)
//        [uLo, uHi] within [0, 1], holding u(x) of every point x of the triangle at every t. Why:
//        with d(t) = x(t) - a(t) and s(t) = b(t) - a(t), both linear in t, N(t) = d . s and
//        D(t) = s . s are quadratics whose values lie between their Bernstein coefficients (d0.s0,
//        (d0.s1 + d1.s0) / 2, d1.s1 and s0.s0, s0.s1, s1.s1), and N is affine in x, so over the
//        triangle between those of its corners; u = N / D then lies between the quotients of
//        those bounds. Rounding (a few roundings per dot product of differences of coordinates,
//        each within 2^-21 of |d|_1 |s|_1 or |s|_1^2): D's bounds are used only when the smallest
//        exceeds 2^-4 (|s0|_1 + |s1|_1)^2 (else the whole segment, [0, 1]: the segment shrank or
//        turned by more than about 40 degrees), which keeps D's relative error below 2^-17, so u is
//        off by at most 2^-21 max |d|_1 |s|_1 / D + 2^-16 |u|; GLC_FEET_SLACK (1 + |u| +
//        max |d|_1 |s|_1 / D) widens the interval beyond that.
//   vec4 glcRadialSegmentFootprint(p0, p1, p2, a, b, p0End, p1End, p2End, aEnd, bEnd, feet)
//        The cone (as glcRadialFootprint's) of every fiber direction x - foot(x) of the
//        triangle's points, from 12 differences p_i - s(u) at both ends of the substep, with u at
//        the two ends of an interval per corner. When every corner's own (unclamped) feet lie in
//        [0, 1], u is affine in x at each t (no clamping), so x - foot(x) = sum b_i (p_i - s(u_i))
//        with u_i corner i's foot, and the intervals are the corners' own: narrow, so the cone is
//        as tight as a point observer's beside the segment. Otherwise each corner takes the face's
//        `feet`, which hold every foot: x(t) - s(u)(t) for u in `feet` is a convex combination of
//        the 12 differences with the same t. Either way the 6-point argument of
//        glcRadialFootprint carries over. The points s(u) are computed in float, off the segment
//        by at most E = 2^-20 max|coordinate of a, b| (+ 2^-120 for flushing), which turns a
//        difference of length >= rho by at most E / rho rad (< 0.53 x for x = E / rho <= 1/4):
//        the cone's cosine is lowered by 2 E / rho, and a triangle within 4 E of those points
//        gets every direction.
//   bool glcRadialFeetMeet(vec2 a, vec2 b)
//        The two intervals overlap (closed): two triangles whose feet do not overlap share no fiber.
// With a segment observer a triangle whose cone is "every direction" must also have every foot
// ([0, 1]): such a triangle may touch the segment, and the theorem then frees nothing.

// Range > 2^-18 (the rounding above, relative to 1 + |u| + |d||s| / D); suggested 2^-14 (a foot
// interval widens by about 10^-4 of the segment's length).
const float GLC_FEET_SLACK = 6.103515625e-5f; // 2^-14
// 2^-20: what computing s(u) = a + u (b - a) in float may move it, relative to its coordinates.
const float GLC_SEGMENT_POINT_ROUNDOFF = 9.5367431640625e-7f;
const float GLC_SEGMENT_POINT_FLUSH = 7.5231638452626401e-37f; // 2^-120

vec2 glcRadialWholeSegment() {
    return vec2(0.0f, 1.0f);
}

// One corner's N(t) = (p(t) - a(t)) . s(t): (smallest, largest Bernstein coefficient, |d|_1 |s|_1).
vec3 glcRadialFootNumerator(vec3 p, vec3 a, vec3 s0, vec3 pEnd, vec3 aEnd, vec3 s1) {
    vec3 d0 = p - a, d1 = pEnd - aEnd;
    float c0 = dot(d0, s0), c1 = 0.5f * (dot(d0, s1) + dot(d1, s0)), c2 = dot(d1, s1);
    vec3 ad0 = abs(d0), ad1 = abs(d1), as0 = abs(s0), as1 = abs(s1);
    float size = (ad0.x + ad0.y + ad0.z + ad1.x + ad1.y + ad1.z) * (as0.x + as0.y + as0.z + as1.x + as1.y + as1.z);
    return vec3(min(min(c0, c1), c2), max(max(c0, c1), c2), size);
}

// One corner's u(p(t), t) over the substep, not clamped to [0, 1] and widened beyond its rounding;
// (1, 0), an empty interval, when D's bounds are not used (the segment turned or shrank).
vec2 glcRadialCornerFeet(vec3 p, vec3 a, vec3 s0, vec3 pEnd, vec3 aEnd, vec3 s1) {
    vec3 as0 = abs(s0), as1 = abs(s1);
    float sizeS = as0.x + as0.y + as0.z + as1.x + as1.y + as1.z;
    float dMin = min(min(dot(s0, s0), dot(s0, s1)), dot(s1, s1));
    float dMax = max(max(dot(s0, s0), dot(s0, s1)), dot(s1, s1));
    if (!(dMin > 0.0625f * sizeS * sizeS)) return vec2(1.0f, 0.0f); // 2^-4; also NaN
    vec3 n = glcRadialFootNumerator(p, a, s0, pEnd, aEnd, s1);
    float lo = n.x >= 0.0f ? n.x / dMax : n.x / dMin;
    float hi = n.y >= 0.0f ? n.y / dMin : n.y / dMax;
    float slackLo = GLC_FEET_SLACK * (1.0f + abs(lo) + n.z / dMin);
    float slackHi = GLC_FEET_SLACK * (1.0f + abs(hi) + n.z / dMin);
    lo = lo - slackLo;
    hi = hi + slackHi;
    if (!(lo <= hi)) return vec2(1.0f, 0.0f); // NaN or infinity
    return vec2(lo, hi);
}

bool glcRadialFeetEmpty(vec2 f) {
    return !(f.x <= f.y);
}

vec2 glcRadialFeet(vec3 p0, vec3 p1, vec3 p2, vec3 a, vec3 b, vec3 p0End, vec3 p1End, vec3 p2End, vec3 aEnd,
                   vec3 bEnd) {
    vec3 s0 = b - a, s1 = bEnd - aEnd;
    vec2 f0 = glcRadialCornerFeet(p0, a, s0, p0End, aEnd, s1);
    vec2 f1 = glcRadialCornerFeet(p1, a, s0, p1End, aEnd, s1);
    vec2 f2 = glcRadialCornerFeet(p2, a, s0, p2End, aEnd, s1);
    if (glcRadialFeetEmpty(f0) || glcRadialFeetEmpty(f1) || glcRadialFeetEmpty(f2)) return glcRadialWholeSegment();
    float lo = min(min(f0.x, f1.x), f2.x), hi = max(max(f0.y, f1.y), f2.y);
    return vec2(min(max(lo, 0.0f), 1.0f), min(max(hi, 0.0f), 1.0f));
}

bool glcRadialFeetMeet(vec2 a, vec2 b) {
    return a.x <= b.y && b.x <= a.y;
}

// min(v . axis / |v|) over the 6 differences p_i - q_i, p_iEnd - q_iEnd.
float glcRadialLeastCosine(vec3 axis, vec3 p0, vec3 p1, vec3 p2, vec3 q0, vec3 q1, vec3 q2, vec3 p0End, vec3 p1End,
                           vec3 p2End, vec3 q0End, vec3 q1End, vec3 q2End) {
    vec3 d0 = p0 - q0, d1 = p1 - q1, d2 = p2 - q2, e0 = p0End - q0End, e1 = p1End - q1End, e2 = p2End - q2End;
    return min(min(min(dot(axis, d0) / length(d0), dot(axis, d1) / length(d1)), dot(axis, d2) / length(d2)),
               min(min(dot(axis, e0) / length(e0), dot(axis, e1) / length(e1)), dot(axis, e2) / length(e2)));
}

// Sum of the 6 unit differences p_i - q_i, p_iEnd - q_iEnd (x: the sum, w: the shortest one's length;
// all 0 when one has no length).
vec4 glcRadialUnitSum(vec3 p0, vec3 p1, vec3 p2, vec3 q0, vec3 q1, vec3 q2, vec3 p0End, vec3 p1End, vec3 p2End,
                      vec3 q0End, vec3 q1End, vec3 q2End) {
    vec3 d0 = p0 - q0, d1 = p1 - q1, d2 = p2 - q2, e0 = p0End - q0End, e1 = p1End - q1End, e2 = p2End - q2End;
    float l0 = length(d0), l1 = length(d1), l2 = length(d2), m0 = length(e0), m1 = length(e1), m2 = length(e2);
    float shortest = min(min(min(l0, l1), l2), min(min(m0, m1), m2));
    if (!(shortest > 0.0f)) return vec4(0.0f, 0.0f, 0.0f, 0.0f);
    vec3 sum = d0 / l0 + d1 / l1 + d2 / l2 + e0 / m0 + e1 / m1 + e2 / m2;
    return vec4(sum, shortest);
}

bool glcRadialFeetWithin(vec2 f) {
    return f.x >= 0.0f && f.y <= 1.0f && f.x <= f.y;
}

vec4 glcRadialSegmentFootprint(vec3 p0, vec3 p1, vec3 p2, vec3 a, vec3 b, vec3 p0End, vec3 p1End, vec3 p2End,
                               vec3 aEnd, vec3 bEnd, vec2 feet) {
    vec3 s0 = b - a, s1 = bEnd - aEnd;
    // Each corner's own feet when all three lie within [0, 1] (then u is affine over the triangle,
    // unclamped, and x - foot(x) is the same convex combination of the corners' fiber vectors);
    // otherwise the face's feet for every corner.
    vec2 f0 = glcRadialCornerFeet(p0, a, s0, p0End, aEnd, s1);
    vec2 f1 = glcRadialCornerFeet(p1, a, s0, p1End, aEnd, s1);
    vec2 f2 = glcRadialCornerFeet(p2, a, s0, p2End, aEnd, s1);
    if (!(glcRadialFeetWithin(f0) && glcRadialFeetWithin(f1) && glcRadialFeetWithin(f2))) {
        f0 = feet;
        f1 = feet;
        f2 = feet;
    }
    vec4 fromLo = glcRadialUnitSum(p0, p1, p2, a + f0.x * s0, a + f1.x * s0, a + f2.x * s0, p0End, p1End, p2End,
                                   aEnd + f0.x * s1, aEnd + f1.x * s1, aEnd + f2.x * s1);
    vec4 fromHi = glcRadialUnitSum(p0, p1, p2, a + f0.y * s0, a + f1.y * s0, a + f2.y * s0, p0End, p1End, p2End,
                                   aEnd + f0.y * s1, aEnd + f1.y * s1, aEnd + f2.y * s1);
    float shortest = min(fromLo.w, fromHi.w);
    vec3 ma = max(abs(a), abs(b)), me = max(abs(aEnd), abs(bEnd));
    float moved = GLC_SEGMENT_POINT_ROUNDOFF * max(max(max(ma.x, ma.y), ma.z), max(max(me.x, me.y), me.z)) +
                  GLC_SEGMENT_POINT_FLUSH;
    if (!(shortest > 4.0f * moved)) return glcRadialEverywhere(); // also NaN
    vec3 sum = vec3(fromLo.x, fromLo.y, fromLo.z) + vec3(fromHi.x, fromHi.y, fromHi.z);
    float size = length(sum);
    if (!(size > 1.0e-3f)) return glcRadialEverywhere();
    vec3 axis = sum / size;
    float c = min(glcRadialLeastCosine(axis, p0, p1, p2, a + f0.x * s0, a + f1.x * s0, a + f2.x * s0, p0End, p1End,
                                       p2End, aEnd + f0.x * s1, aEnd + f1.x * s1, aEnd + f2.x * s1),
                  glcRadialLeastCosine(axis, p0, p1, p2, a + f0.y * s0, a + f1.y * s0, a + f2.y * s0, p0End, p1End,
                                       p2End, aEnd + f0.y * s1, aEnd + f1.y * s1, aEnd + f2.y * s1));
    c -= GLC_FOOTPRINT_SLACK + 2.0f * moved / shortest;
    if (!(c > GLC_FOOTPRINT_SLACK)) return glcRadialEverywhere();
    return vec4(axis, c);
}

#endif
