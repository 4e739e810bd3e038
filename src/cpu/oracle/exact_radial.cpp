#include "cpu/oracle/exact_radial.hpp"

namespace glcollide::cpu {
namespace {

struct Q3 {
    mpq_class x, y, z;
};
Q3 exact(const glm::vec3& v) {
    return {mpq_class(static_cast<double>(v.x)), mpq_class(static_cast<double>(v.y)),
            mpq_class(static_cast<double>(v.z))};
}
Q3 operator-(const Q3& a, const Q3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
mpq_class triple(const Q3& a, const Q3& b, const Q3& c) {
    return (a.y * b.z - a.z * b.y) * c.x + (a.z * b.x - a.x * b.z) * c.y + (a.x * b.y - a.y * b.x) * c.z;
}
// The triple product's terms in absolute value, summed: the scale its rounding is relative to.
mpq_class tripleMagnitude(const Q3& a, const Q3& b, const Q3& c) {
    const auto m = [](const mpq_class& v) { return mpq_class(abs(v)); };
    return (m(a.y) * m(b.z) + m(a.z) * m(b.y)) * m(c.x) + (m(a.z) * m(b.x) + m(a.x) * m(b.z)) * m(c.y) +
           (m(a.x) * m(b.y) + m(a.y) * m(b.x)) * m(c.z);
}

// B0, 3 B1, 3 B2, B3 with D the trilinear form `product` of a = p1 - p0, b = p2 - p0, c = p0 - q.
template <typename Product>
std::array<mpq_class, 4> bernstein(const RadialPoints& start, const RadialPoints& end, Product product) {
    std::array<Q3, 4> s, e;
    for (int i = 0; i < 4; ++i) s[i] = exact(start[i]), e[i] = exact(end[i]);
    const Q3 a0 = s[1] - s[0], b0 = s[2] - s[0], c0 = s[0] - s[3];
    const Q3 a1 = e[1] - e[0], b1 = e[2] - e[0], c1 = e[0] - e[3];
    return {product(a0, b0, c0), product(a1, b0, c0) + product(a0, b1, c0) + product(a0, b0, c1),
            product(a1, b1, c0) + product(a1, b0, c1) + product(a0, b1, c1), product(a1, b1, c1)};
}

} // namespace

std::array<mpq_class, 4> exactRadialCoefficients(const RadialPoints& start, const RadialPoints& end) {
    return bernstein(start, end, triple);
}

std::array<mpq_class, 4> exactRadialMagnitudes(const RadialPoints& start, const RadialPoints& end) {
    return bernstein(start, end, tripleMagnitude);
}

bool exactlyRadialPositive(const RadialPoints& start, const RadialPoints& end) {
    for (const mpq_class& b : exactRadialCoefficients(start, end))
        if (sgn(b) <= 0) return false;
    return true;
}

mpq_class exactRadialPhi(const RadialPoints& start, const RadialPoints& end, const mpq_class& t) {
    std::array<Q3, 4> x;
    for (int i = 0; i < 4; ++i) {
        const Q3 s = exact(start[i]), e = exact(end[i]);
        x[i] = {s.x + t * (e.x - s.x), s.y + t * (e.y - s.y), s.z + t * (e.z - s.z)};
    }
    return triple(x[1] - x[0], x[2] - x[0], x[0] - x[3]);
}

} // namespace glcollide::cpu
