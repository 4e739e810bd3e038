#include "cpu/fast_tri_tri.hpp"

#include <cmath>
#include <utility>

namespace glcollide::cpu {
namespace {

using V = glm::vec3;

// Written out (not glm::dot/cross) so the order of every float operation is the shader's.
V sub(const V& a, const V& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
V cross(const V& a, const V& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
float dot(const V& a, const V& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

struct V2 {
    float x, y;
};

bool edgeEdge(V2 v0, V2 a, V2 u0, V2 u1) {
    const float bx = u0.x - u1.x, by = u0.y - u1.y;
    const float cx = v0.x - u0.x, cy = v0.y - u0.y;
    const float f = a.y * bx - a.x * by;
    const float d = by * cx - bx * cy;
    if ((f > 0.0f && d >= 0.0f && d <= f) || (f < 0.0f && d <= 0.0f && d >= f)) {
        const float e = a.x * cy - a.y * cx;
        if (f > 0.0f) {
            if (e >= 0.0f && e <= f) return true;
        } else {
            if (e <= 0.0f && e >= f) return true;
        }
    }
    return false;
}

bool edgeAgainstTriEdges(V2 v0, V2 v1, V2 u0, V2 u1, V2 u2) {
    const V2 a{v1.x - v0.x, v1.y - v0.y};
    return edgeEdge(v0, a, u0, u1) || edgeEdge(v0, a, u1, u2) || edgeEdge(v0, a, u2, u0);
}

bool pointInTri(V2 v0, V2 u0, V2 u1, V2 u2) {
    float a = u1.y - u0.y, b = -(u1.x - u0.x), c = -a * u0.x - b * u0.y;
    const float d0 = a * v0.x + b * v0.y + c;
    a = u2.y - u1.y;
    b = -(u2.x - u1.x);
    c = -a * u1.x - b * u1.y;
    const float d1 = a * v0.x + b * v0.y + c;
    a = u0.y - u2.y;
    b = -(u0.x - u2.x);
    c = -a * u2.x - b * u2.y;
    const float d2 = a * v0.x + b * v0.y + c;
    return d0 * d1 > 0.0f && d0 * d2 > 0.0f;
}

bool coplanar(const V& n, const V& v0, const V& v1, const V& v2, const V& u0, const V& u1, const V& u2) {
    const V a{std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
    int i0 = 0, i1 = 0;
    if (a.x > a.y) {
        if (a.x > a.z)
            i0 = 1, i1 = 2;
        else
            i0 = 0, i1 = 1;
    } else {
        if (a.z > a.y)
            i0 = 0, i1 = 1;
        else
            i0 = 0, i1 = 2;
    }
    auto p = [&](const V& v) { return V2{v[i0], v[i1]}; };
    const V2 pv0 = p(v0), pv1 = p(v1), pv2 = p(v2), pu0 = p(u0), pu1 = p(u1), pu2 = p(u2);
    if (edgeAgainstTriEdges(pv0, pv1, pu0, pu1, pu2)) return true;
    if (edgeAgainstTriEdges(pv1, pv2, pu0, pu1, pu2)) return true;
    if (edgeAgainstTriEdges(pv2, pv0, pu0, pu1, pu2)) return true;
    return pointInTri(pv0, pu0, pu1, pu2) || pointInTri(pu0, pv0, pv1, pv2);
}

struct Interval {
    float a = 0, b = 0, c = 0, x0 = 0, x1 = 0;
};

// NEWCOMPUTE_INTERVALS; false when the triangles are coplanar.
bool interval(float vv0, float vv1, float vv2, float d0, float d1, float d2, float d0d1, float d0d2,
              Interval& r) {
    if (d0d1 > 0.0f)
        r = {vv2, (vv0 - vv2) * d2, (vv1 - vv2) * d2, d2 - d0, d2 - d1};
    else if (d0d2 > 0.0f)
        r = {vv1, (vv0 - vv1) * d1, (vv2 - vv1) * d1, d1 - d0, d1 - d2};
    else if (d1 * d2 > 0.0f || d0 != 0.0f)
        r = {vv0, (vv1 - vv0) * d0, (vv2 - vv0) * d0, d0 - d1, d0 - d2};
    else if (d1 != 0.0f)
        r = {vv1, (vv0 - vv1) * d1, (vv2 - vv1) * d1, d1 - d0, d1 - d2};
    else if (d2 != 0.0f)
        r = {vv2, (vv0 - vv2) * d2, (vv1 - vv2) * d2, d2 - d0, d2 - d1};
    else
        return false;
    return true;
}

} // namespace

bool fastTrianglesIntersect(const FloatTriangle& a, const FloatTriangle& b) {
    const V &v0 = a[0], &v1 = a[1], &v2 = a[2], &u0 = b[0], &u1 = b[1], &u2 = b[2];
    const V n1 = cross(sub(v1, v0), sub(v2, v0));
    const float d1 = -dot(n1, v0);
    float du0 = dot(n1, u0) + d1, du1 = dot(n1, u1) + d1, du2 = dot(n1, u2) + d1;
    if (std::fabs(du0) < kFastTriTriEpsilon) du0 = 0.0f;
    if (std::fabs(du1) < kFastTriTriEpsilon) du1 = 0.0f;
    if (std::fabs(du2) < kFastTriTriEpsilon) du2 = 0.0f;
    const float du0du1 = du0 * du1, du0du2 = du0 * du2;
    if (du0du1 > 0.0f && du0du2 > 0.0f) return false;

    const V n2 = cross(sub(u1, u0), sub(u2, u0));
    const float d2 = -dot(n2, u0);
    float dv0 = dot(n2, v0) + d2, dv1 = dot(n2, v1) + d2, dv2 = dot(n2, v2) + d2;
    if (std::fabs(dv0) < kFastTriTriEpsilon) dv0 = 0.0f;
    if (std::fabs(dv1) < kFastTriTriEpsilon) dv1 = 0.0f;
    if (std::fabs(dv2) < kFastTriTriEpsilon) dv2 = 0.0f;
    const float dv0dv1 = dv0 * dv1, dv0dv2 = dv0 * dv2;
    if (dv0dv1 > 0.0f && dv0dv2 > 0.0f) return false;

    const V dir = cross(n1, n2);
    float mx = std::fabs(dir.x);
    int index = 0;
    const float bb = std::fabs(dir.y), cc = std::fabs(dir.z);
    if (bb > mx) mx = bb, index = 1;
    if (cc > mx) mx = cc, index = 2;

    Interval i1, i2;
    if (!interval(v0[index], v1[index], v2[index], dv0, dv1, dv2, dv0dv1, dv0dv2, i1))
        return coplanar(n1, v0, v1, v2, u0, u1, u2);
    if (!interval(u0[index], u1[index], u2[index], du0, du1, du2, du0du1, du0du2, i2))
        return coplanar(n1, v0, v1, v2, u0, u1, u2);

    const float xx = i1.x0 * i1.x1, yy = i2.x0 * i2.x1, xxyy = xx * yy;
    float tmp = i1.a * xxyy;
    float s0 = tmp + i1.b * i1.x1 * yy, s1 = tmp + i1.c * i1.x0 * yy;
    tmp = i2.a * xxyy;
    float t0 = tmp + i2.b * xx * i2.x1, t1 = tmp + i2.c * xx * i2.x0;
    if (s0 > s1) std::swap(s0, s1);
    if (t0 > t1) std::swap(t0, t1);
    return !(s1 < t0 || t1 < s0);
}

} // namespace glcollide::cpu
