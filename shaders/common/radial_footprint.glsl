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

#endif
