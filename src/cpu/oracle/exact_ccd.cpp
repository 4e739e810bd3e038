#include "cpu/oracle/exact_ccd.hpp"

#include "cpu/oracle/ccd_query_csv.hpp"

#include <glcollide/error.hpp>

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <utility>

namespace glcollide::cpu {
namespace {

// ---------------------------------------------------------------------------------------------
// Polynomials in t over Q: coefficients lowest degree first, no trailing zeros (empty = 0).

using Poly = std::vector<mpq_class>;

void trim(Poly& p) {
    while (!p.empty() && sgn(p.back()) == 0) p.pop_back();
}
int degree(const Poly& p) {
    return static_cast<int>(p.size()) - 1;
}
bool isZero(const Poly& p) {
    return p.empty();
}
Poly add(const Poly& a, const Poly& b) {
    Poly r(std::max(a.size(), b.size()));
    for (std::size_t i = 0; i < a.size(); ++i) r[i] += a[i];
    for (std::size_t i = 0; i < b.size(); ++i) r[i] += b[i];
    trim(r);
    return r;
}
Poly negate(Poly a) {
    for (auto& c : a) c = -c;
    return a;
}
Poly sub(const Poly& a, const Poly& b) {
    return add(a, negate(b));
}
Poly mul(const Poly& a, const Poly& b) {
    if (a.empty() || b.empty()) return {};
    Poly r(a.size() + b.size() - 1);
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
    trim(r);
    return r;
}
mpq_class eval(const Poly& p, const mpq_class& x) {
    mpq_class r = 0;
    for (auto it = p.rbegin(); it != p.rend(); ++it) r = r * x + *it;
    return r;
}
int signAtRational(const Poly& p, const mpq_class& x) {
    return sgn(eval(p, x));
}
Poly derivative(const Poly& p) {
    Poly r;
    for (std::size_t i = 1; i < p.size(); ++i) r.push_back(p[i] * static_cast<long>(i));
    trim(r);
    return r;
}
/// Quotient and remainder of a / b (b nonzero).
std::pair<Poly, Poly> divide(Poly a, const Poly& b) {
    Poly q(a.size() >= b.size() ? a.size() - b.size() + 1 : 0);
    while (!a.empty() && a.size() >= b.size()) {
        const std::size_t shift = a.size() - b.size();
        const mpq_class factor = a.back() / b.back();
        q[shift] = factor;
        for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] -= factor * b[i];
        a.pop_back(); // exactly zero now
        trim(a);
    }
    trim(q);
    return {q, a};
}
Poly monic(Poly p) {
    if (p.empty()) return p;
    const mpq_class lead = p.back();
    for (auto& c : p) c /= lead;
    return p;
}
/// Monic greatest common divisor; gcd(0, 0) = 0.
Poly gcd(Poly a, Poly b) {
    while (!b.empty()) {
        Poly r = divide(a, b).second;
        a = std::move(b);
        b = std::move(r);
    }
    return monic(a);
}
/// The product of the distinct irreducible factors: same roots, each simple.
Poly squarefree(const Poly& p) {
    if (degree(p) < 1) return p;
    return monic(divide(p, gcd(p, derivative(p))).first);
}

// ---------------------------------------------------------------------------------------------
// Real roots by Sturm sequences.

using Sturm = std::vector<Poly>;

Sturm sturmSequence(const Poly& squarefreePoly) {
    Sturm s{squarefreePoly, derivative(squarefreePoly)};
    while (!s.back().empty()) {
        Poly r = negate(divide(s[s.size() - 2], s.back()).second);
        if (r.empty()) break;
        s.push_back(std::move(r));
    }
    if (s.back().empty()) s.pop_back();
    return s;
}
int signChanges(const Sturm& s, const mpq_class& x) {
    int changes = 0, previous = 0;
    for (const Poly& p : s) {
        const int sign = signAtRational(p, x);
        if (sign == 0) continue;
        if (previous != 0 && sign != previous) ++changes;
        previous = sign;
    }
    return changes;
}
/// Distinct roots in (lo, hi) of a squarefree polynomial with no root at lo or hi.
int rootsBetween(const Sturm& s, const mpq_class& lo, const mpq_class& hi) {
    return signChanges(s, lo) - signChanges(s, hi);
}

/// A real root of the squarefree polynomial `poly`: exactly `lo` when exact, otherwise the only
/// root of `poly` in the open interval (lo, hi), where poly changes sign (poly(lo), poly(hi) != 0).
struct Root {
    Poly poly;
    mpq_class lo, hi;
    bool exact = false;
};

void isolate(const Poly& f, const Sturm& s, mpq_class lo, mpq_class hi, std::vector<Root>& out) {
    const int n = rootsBetween(s, lo, hi);
    if (n == 0) return;
    if (n == 1) {
        out.push_back({f, lo, hi, false});
        return;
    }
    // Split where f does not vanish (f has finitely many roots, so this ends).
    mpq_class mid = (lo + hi) / 2;
    while (signAtRational(f, mid) == 0) mid = (lo + mid) / 2;
    isolate(f, s, lo, mid, out);
    isolate(f, s, mid, hi, out);
}

/// The distinct real roots of p (nonzero) in [0, 1], in increasing order.
std::vector<Root> rootsIn01(const Poly& p) {
    std::vector<Root> roots;
    if (degree(p) < 1) return roots;
    Poly f = squarefree(p);
    const bool atZero = signAtRational(f, 0) == 0, atOne = signAtRational(f, 1) == 0;
    if (atZero) roots.push_back({f, 0, 0, true});
    // Deflate the roots at 0 and 1 (simple: f is squarefree) so the interior has clean ends.
    Poly interior = f;
    if (atZero) interior = divide(interior, Poly{0, 1}).first;
    if (atOne) interior = divide(interior, Poly{-1, 1}).first;
    if (degree(interior) >= 1) isolate(interior, sturmSequence(interior), 0, 1, roots);
    if (atOne) roots.push_back({f, 1, 1, true});
    return roots;
}

/// Halves the root's interval (or finds it exactly at the midpoint).
void bisect(Root& r) {
    const mpq_class mid = (r.lo + r.hi) / 2;
    const int s = signAtRational(r.poly, mid);
    if (s == 0) {
        r.lo = r.hi = mid;
        r.exact = true;
    } else if (s == signAtRational(r.poly, r.lo)) {
        r.lo = mid;
    } else {
        r.hi = mid;
    }
}

/// The exact sign of q at the root (refining the root's interval when needed).
int signAt(const Poly& q, Root& r) {
    if (isZero(q)) return 0;
    if (r.exact) return signAtRational(q, r.lo);
    // q vanishes at r iff their gcd does; the gcd divides r.poly, whose only root in (lo, hi) is
    // r (simple), so the gcd changes sign across the interval exactly when r is its root.
    const Poly common = gcd(r.poly, q);
    if (degree(common) >= 1 && signAtRational(common, r.lo) != signAtRational(common, r.hi)) return 0;
    // Otherwise q(r) != 0: shrink the interval until q has no root in it; then q's sign there is
    // its sign at r.
    const Poly qRoots = squarefree(q);
    const Sturm s = degree(qRoots) >= 1 ? sturmSequence(qRoots) : Sturm{};
    while (!r.exact) {
        const bool clean =
            s.empty() || (signAtRational(qRoots, r.lo) != 0 && signAtRational(qRoots, r.hi) != 0 &&
                          rootsBetween(s, r.lo, r.hi) == 0);
        if (clean) return signAtRational(q, r.lo);
        bisect(r);
    }
    return signAtRational(q, r.lo);
}

/// The fraction with the smallest denominator in [lo, hi] (0 <= lo <= hi), by continued fractions.
mpq_class simplestBetween(const mpq_class& lo, const mpq_class& hi) {
    mpz_class whole;
    mpz_fdiv_q(whole.get_mpz_t(), lo.get_num_mpz_t(), lo.get_den_mpz_t());
    if (whole == lo) return lo;
    if (whole + 1 <= hi) return mpq_class(whole + 1);
    // lo and hi lie in (whole, whole + 1): recurse on the reciprocals of their fractional parts.
    return whole + 1 / simplestBetween(1 / (hi - whole), 1 / (lo - whole));
}

/// Shrinks the root's interval to width <= 2^-64, and finds a rational root exactly: the
/// simplest fraction in the final interval is tried (a rational root with a denominator below
/// 2^32 is always that fraction).
void refine(Root& r) {
    const mpq_class width(mpz_class(1), mpz_class(1) << 64);
    while (!r.exact && r.hi - r.lo > width) bisect(r);
    if (r.exact) return;
    const mpq_class candidate = simplestBetween(r.lo, r.hi);
    if (signAtRational(r.poly, candidate) == 0) r.lo = r.hi = candidate, r.exact = true;
}

// ---------------------------------------------------------------------------------------------
// Points moving linearly: vectors of polynomials in t.

struct PVec {
    Poly x, y, z;
};

PVec moving(const RationalPoint& at0, const RationalPoint& at1) {
    auto line = [](const mpq_class& a, const mpq_class& b) {
        Poly p{a, b - a};
        trim(p);
        return p;
    };
    return {line(at0.x, at1.x), line(at0.y, at1.y), line(at0.z, at1.z)};
}
PVec sub(const PVec& a, const PVec& b) {
    return {sub(a.x, b.x), sub(a.y, b.y), sub(a.z, b.z)};
}
PVec cross(const PVec& a, const PVec& b) {
    return {sub(mul(a.y, b.z), mul(a.z, b.y)), sub(mul(a.z, b.x), mul(a.x, b.z)),
            sub(mul(a.x, b.y), mul(a.y, b.x))};
}
Poly dot(const PVec& a, const PVec& b) {
    return add(add(mul(a.x, b.x), mul(a.y, b.y)), mul(a.z, b.z));
}
bool isZero(const PVec& v) {
    return isZero(v.x) && isZero(v.y) && isZero(v.z);
}
bool vanishesAt(const PVec& v, Root& r) {
    return signAt(v.x, r) == 0 && signAt(v.y, r) == 0 && signAt(v.z, r) == 0;
}
Poly commonDivisor(const PVec& v) {
    return gcd(gcd(v.x, v.y), v.z);
}

// ---------------------------------------------------------------------------------------------
// Earliest contact.

Root exactRoot(const mpq_class& t) {
    return {Poly{}, t, t, true};
}

ExactCcdResult hitAt(Root r) {
    refine(r);
    return {true, r.lo, r.hi};
}

/// The earlier of two answers: the minimum of two bracketed numbers lies in [min lo, min hi].
ExactCcdResult earliest(const ExactCcdResult& a, const ExactCcdResult& b) {
    if (!a.touch) return b;
    if (!b.touch) return a;
    return {true, std::min(a.toiLo, b.toiLo), std::min(a.toiHi, b.toiHi)};
}

/// The first root of `poly` in [0, 1] at which `touches` holds.
template <class Touches> ExactCcdResult firstRootWhere(const Poly& poly, Touches touches) {
    for (Root& r : rootsIn01(poly))
        if (touches(r)) return hitAt(r);
    return {};
}

/// p on the closed segment ab at the root (a zero-length segment is its point).
bool pointOnSegmentAt(Root& r, const PVec& p, const PVec& a, const PVec& b) {
    const PVec ap = sub(p, a), ab = sub(b, a);
    if (!vanishesAt(cross(ap, ab), r)) return false;
    if (signAt(dot(ab, ab), r) == 0) return vanishesAt(ap, r);
    return signAt(dot(ap, ab), r) >= 0 && signAt(dot(sub(p, b), sub(a, b)), r) >= 0;
}

ExactCcdResult pointPointCcd(const PVec& p, const PVec& a) {
    const PVec d = sub(p, a);
    if (isZero(d)) return hitAt(exactRoot(0));
    return firstRootWhere(commonDivisor(d), [](Root&) { return true; });
}

/// Point against moving closed segment: contact needs collinearity, whose times are the common
/// roots of the cross product; if it vanishes throughout, the first contact after t = 0 is the
/// point meeting an end.
ExactCcdResult pointSegmentCcd(const PVec& p, const PVec& a, const PVec& b) {
    const PVec c = cross(sub(p, a), sub(b, a));
    if (isZero(c)) {
        Root zero = exactRoot(0);
        if (pointOnSegmentAt(zero, p, a, b)) return hitAt(zero);
        return earliest(pointPointCcd(p, a), pointPointCcd(p, b));
    }
    return firstRootWhere(commonDivisor(c), [&](Root& r) { return pointOnSegmentAt(r, p, a, b); });
}

/// p in the closed triangle abc at a root where all four are coplanar.
bool pointInTriangleAt(Root& r, const PVec& p, const PVec& a, const PVec& b, const PVec& c) {
    const PVec n = cross(sub(b, a), sub(c, a));
    if (vanishesAt(n, r)) // zero area: the triangle is the union of its edges
        return pointOnSegmentAt(r, p, a, b) || pointOnSegmentAt(r, p, b, c) || pointOnSegmentAt(r, p, c, a);
    return signAt(dot(cross(sub(b, a), sub(p, a)), n), r) >= 0 &&
           signAt(dot(cross(sub(c, b), sub(p, b)), n), r) >= 0 &&
           signAt(dot(cross(sub(a, c), sub(p, c)), n), r) >= 0;
}

/// Closed segments a0a1 and b0b1 meet, at a root where all four ends are coplanar.
bool segmentsMeetAt(Root& r, const PVec& a0, const PVec& a1, const PVec& b0, const PVec& b1) {
    const PVec ea = sub(a1, a0), eb = sub(b1, b0), n = cross(ea, eb);
    if (vanishesAt(n, r)) // parallel or degenerate: they meet iff an end lies on the other segment
        return pointOnSegmentAt(r, a0, b0, b1) || pointOnSegmentAt(r, a1, b0, b1) ||
               pointOnSegmentAt(r, b0, a0, a1) || pointOnSegmentAt(r, b1, a0, a1);
    // The lines cross at a0 + u ea = b0 + v eb with u = su / nn, v = sv / nn.
    const PVec w = sub(b0, a0);
    const Poly nn = dot(n, n), su = dot(cross(w, eb), n), sv = dot(cross(w, ea), n);
    return signAt(su, r) >= 0 && signAt(sub(nn, su), r) >= 0 && signAt(sv, r) >= 0 &&
           signAt(sub(nn, sv), r) >= 0;
}

} // namespace

ExactCcdResult exactVertexFaceCcd(const RationalCcdQuery& q) {
    const PVec p = moving(q[0], q[4]), a = moving(q[1], q[5]), b = moving(q[2], q[6]), c = moving(q[3], q[7]);
    const Poly coplanar = dot(sub(p, a), cross(sub(b, a), sub(c, a)));
    if (!isZero(coplanar))
        return firstRootWhere(coplanar, [&](Root& r) { return pointInTriangleAt(r, p, a, b, c); });
    // Coplanar throughout: touching at t = 0, or the first contact is the point meeting an edge
    // (inside the triangle is open in the plane while the triangle has area; without area the
    // triangle is its edges).
    Root zero = exactRoot(0);
    if (pointInTriangleAt(zero, p, a, b, c)) return hitAt(zero);
    return earliest(earliest(pointSegmentCcd(p, a, b), pointSegmentCcd(p, b, c)), pointSegmentCcd(p, c, a));
}

ExactCcdResult exactEdgeEdgeCcd(const RationalCcdQuery& q) {
    const PVec a0 = moving(q[0], q[4]), a1 = moving(q[1], q[5]), b0 = moving(q[2], q[6]),
               b1 = moving(q[3], q[7]);
    const Poly coplanar = dot(cross(sub(a1, a0), sub(b1, b0)), sub(b0, a0));
    if (!isZero(coplanar))
        return firstRootWhere(coplanar, [&](Root& r) { return segmentsMeetAt(r, a0, a1, b0, b1); });
    // Coplanar throughout: touching at t = 0, or the first contact is an end meeting the other
    // segment (a proper crossing of non-parallel segments is open in the plane).
    Root zero = exactRoot(0);
    if (segmentsMeetAt(zero, a0, a1, b0, b1)) return hitAt(zero);
    return earliest(earliest(pointSegmentCcd(a0, b0, b1), pointSegmentCcd(a1, b0, b1)),
                    earliest(pointSegmentCcd(b0, a0, a1), pointSegmentCcd(b1, a0, a1)));
}

RationalCcdQuery rationalQuery(const std::array<glm::dvec3, 8>& points) {
    RationalCcdQuery q;
    for (std::size_t i = 0; i < 8; ++i)
        q[i] = {mpq_class(points[i].x), mpq_class(points[i].y), mpq_class(points[i].z)};
    return q;
}

std::vector<SampleCcdQuery> readSampleCcdQueries(const std::string& path) {
    std::vector<SampleCcdQuery> queries;
    for (CcdCsvQuery& q : readCcdQueryCsv(path)) {
        if (!q.truth)
            throw Error(path + ":" + std::to_string(q.lines[0]) + ": the query has no ground-truth column");
        queries.push_back({std::move(q.points), *q.truth});
    }
    return queries;
}

std::vector<RationalCcdQuery> readCcdQueryPoints(const std::string& path) {
    std::vector<RationalCcdQuery> points;
    for (CcdCsvQuery& q : readCcdQueryCsv(path)) points.push_back(std::move(q.points));
    return points;
}

void writeSampleCcdQueries(const std::string& path, const std::vector<SampleCcdQuery>& queries) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    for (const SampleCcdQuery& q : queries)
        for (const RationalPoint& p : q.points) {
            for (const mpq_class* c : {&p.x, &p.y, &p.z})
                out << c->get_num().get_str() << ',' << c->get_den().get_str() << ',';
            out << (q.truth ? 1 : 0) << '\n';
        }
    if (!out.flush()) throw std::runtime_error(path + ": cannot write");
}

} // namespace glcollide::cpu
