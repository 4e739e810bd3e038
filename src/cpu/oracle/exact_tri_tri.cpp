#include "cpu/oracle/exact_tri_tri.hpp"

#include <gmpxx.h>

#include <vector>

namespace glcollide::cpu {
namespace {

struct QVec {
    mpq_class x, y, z;
};

QVec toQ(const glm::dvec3& v) {
    return {mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)};
}
QVec sub(const QVec& a, const QVec& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
QVec cross(const QVec& a, const QVec& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
mpq_class dot(const QVec& a, const QVec& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
bool isZero(const QVec& v) {
    return sgn(v.x) == 0 && sgn(v.y) == 0 && sgn(v.z) == 0;
}
bool equal(const QVec& a, const QVec& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

/// Sign of det[b-a, c-a, d-a]: d above (+), on (0) or below (-) the plane abc.
int orient3d(const QVec& a, const QVec& b, const QVec& c, const QVec& d) {
    return sgn(dot(cross(sub(b, a), sub(c, a)), sub(d, a)));
}

/// 2D view of a plane: drops coordinate `axis` (0, 1, 2), chosen so the projection is injective
/// on the plane or line the shapes lie in.
struct Projection {
    int axis = 2;
    mpq_class u(const QVec& v) const { return axis == 0 ? v.y : v.x; }
    mpq_class w(const QVec& v) const { return axis == 2 ? v.y : v.z; }
    int orient2d(const QVec& a, const QVec& b, const QVec& c) const {
        return sgn((u(b) - u(a)) * (w(c) - w(a)) - (w(b) - w(a)) * (u(c) - u(a)));
    }
};

/// Drop the axis where `normal` is largest: injective on any plane with that normal.
Projection projectionForNormal(const QVec& n) {
    const mpq_class ax = abs(n.x), ay = abs(n.y), az = abs(n.z);
    if (ax >= ay && ax >= az) return {0};
    if (ay >= az) return {1};
    return {2};
}

/// Drop the axis where `direction` is smallest: injective on any line with that direction.
Projection projectionForDirection(const QVec& d) {
    const mpq_class ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
    if (ax <= ay && ax <= az) return {0};
    if (ay <= az) return {1};
    return {2};
}

/// p on the closed segment ab, all three collinear in the projection `pr`.
bool onSegment2d(const Projection& pr, const QVec& a, const QVec& b, const QVec& p) {
    const mpq_class pu = pr.u(p), pw = pr.w(p), au = pr.u(a), bu = pr.u(b), aw = pr.w(a), bw = pr.w(b);
    const bool inU = (au <= bu) ? (au <= pu && pu <= bu) : (bu <= pu && pu <= au);
    const bool inW = (aw <= bw) ? (aw <= pw && pw <= bw) : (bw <= pw && pw <= aw);
    return inU && inW;
}

/// Closed segments ab and cd in the projection.
bool segmentsIntersect2d(const Projection& pr, const QVec& a, const QVec& b, const QVec& c, const QVec& d) {
    const int o1 = pr.orient2d(a, b, c), o2 = pr.orient2d(a, b, d);
    const int o3 = pr.orient2d(c, d, a), o4 = pr.orient2d(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && onSegment2d(pr, a, b, c)) || (o2 == 0 && onSegment2d(pr, a, b, d)) ||
           (o3 == 0 && onSegment2d(pr, c, d, a)) || (o4 == 0 && onSegment2d(pr, c, d, b));
}

/// p in the closed (non-degenerate) triangle abc, all coplanar, in the projection.
bool pointInTriangle2d(const Projection& pr, const QVec& a, const QVec& b, const QVec& c, const QVec& p) {
    const int s1 = pr.orient2d(a, b, p), s2 = pr.orient2d(b, c, p), s3 = pr.orient2d(c, a, p);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

/// A triangle's point set: a proper triangle, a segment (collinear corners) or a point.
struct Shape {
    std::vector<QVec> v; // 3, 2 or 1 points
};

Shape shapeOf(const Triangle& t) {
    const QVec a = toQ(t[0]), b = toQ(t[1]), c = toQ(t[2]);
    if (!isZero(cross(sub(b, a), sub(c, a)))) return {{a, b, c}};
    // Collinear: the hull is the segment between the farthest pair.
    const mpq_class ab = dot(sub(b, a), sub(b, a)), bc = dot(sub(c, b), sub(c, b)),
                    ca = dot(sub(a, c), sub(a, c));
    if (sgn(ab) == 0 && sgn(bc) == 0) return {{a}};
    if (ab >= bc && ab >= ca) return {{a, b}};
    if (bc >= ca) return {{b, c}};
    return {{c, a}};
}

bool pointPoint(const QVec& p, const QVec& q) {
    return equal(p, q);
}

bool pointSegment(const QVec& p, const QVec& a, const QVec& b) {
    if (!isZero(cross(sub(b, a), sub(p, a)))) return false;
    const mpq_class t = dot(sub(p, a), sub(b, a));
    return sgn(t) >= 0 && t <= dot(sub(b, a), sub(b, a));
}

bool pointTriangle(const QVec& p, const QVec& a, const QVec& b, const QVec& c) {
    if (orient3d(a, b, c, p) != 0) return false;
    return pointInTriangle2d(projectionForNormal(cross(sub(b, a), sub(c, a))), a, b, c, p);
}

bool segmentSegment(const QVec& a, const QVec& b, const QVec& c, const QVec& d) {
    if (orient3d(a, b, c, d) != 0) return false; // skew lines never meet
    // A normal of the common plane; none when all four points are collinear.
    QVec n = cross(sub(b, a), sub(c, a));
    if (isZero(n)) n = cross(sub(b, a), sub(d, a));
    const Projection pr = !isZero(n) ? projectionForNormal(n) : projectionForDirection(sub(b, a));
    return segmentsIntersect2d(pr, a, b, c, d);
}

bool segmentTriangle(const QVec& p, const QVec& q, const QVec& a, const QVec& b, const QVec& c) {
    const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
    if (sp * sq > 0) return false;
    if (sp == 0 && sq == 0) { // coplanar: an endpoint inside, or the segment crosses an edge
        const Projection pr = projectionForNormal(cross(sub(b, a), sub(c, a)));
        return pointInTriangle2d(pr, a, b, c, p) || pointInTriangle2d(pr, a, b, c, q) ||
               segmentsIntersect2d(pr, p, q, a, b) || segmentsIntersect2d(pr, p, q, b, c) ||
               segmentsIntersect2d(pr, p, q, c, a);
    }
    // The segment meets the plane in one point; it lies in the closed triangle iff the line pq
    // passes on the same side (or on) each of the triangle's directed edges.
    const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

bool triangleTriangle(const Shape& s, const Shape& t) {
    const QVec &a = s.v[0], &b = s.v[1], &c = s.v[2];
    const QVec &d = t.v[0], &e = t.v[1], &f = t.v[2];
    // Early out: all of one triangle strictly on one side of the other's plane.
    const int d1 = orient3d(a, b, c, d), d2 = orient3d(a, b, c, e), d3 = orient3d(a, b, c, f);
    if ((d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0)) return false;
    const int e1 = orient3d(d, e, f, a), e2 = orient3d(d, e, f, b), e3 = orient3d(d, e, f, c);
    if ((e1 > 0 && e2 > 0 && e3 > 0) || (e1 < 0 && e2 < 0 && e3 < 0)) return false;
    // Two closed triangles meet iff an edge of one meets the other: for non-coplanar ones the
    // intersection is a segment whose ends lie on edges; for coplanar ones either edges cross or
    // one triangle contains a vertex (hence an edge) of the other.
    return segmentTriangle(a, b, d, e, f) || segmentTriangle(b, c, d, e, f) ||
           segmentTriangle(c, a, d, e, f) || segmentTriangle(d, e, a, b, c) ||
           segmentTriangle(e, f, a, b, c) || segmentTriangle(f, d, a, b, c);
}

bool shapesIntersect(const Shape& s, const Shape& t) {
    if (s.v.size() < t.v.size()) return shapesIntersect(t, s); // s has the higher dimension
    const std::vector<QVec>& p = s.v;
    const std::vector<QVec>& q = t.v;
    if (p.size() == 3) {
        if (q.size() == 3) return triangleTriangle(s, t);
        if (q.size() == 2) return segmentTriangle(q[0], q[1], p[0], p[1], p[2]);
        return pointTriangle(q[0], p[0], p[1], p[2]);
    }
    if (p.size() == 2)
        return q.size() == 2 ? segmentSegment(p[0], p[1], q[0], q[1]) : pointSegment(q[0], p[0], p[1]);
    return pointPoint(p[0], q[0]);
}

} // namespace

bool exactTrianglesIntersect(const Triangle& a, const Triangle& b) {
    return shapesIntersect(shapeOf(a), shapeOf(b));
}

} // namespace glcollide::cpu
