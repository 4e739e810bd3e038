#include "cpu/oracle/tri_tri_cases.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <random>

namespace glcollide::cpu {
namespace {

using F = glm::vec3;
using FTri = std::array<F, 3>;

FloatTriPair pairOf(const FTri& a, const FTri& b) {
    FloatTriPair p{};
    for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) {
            p[static_cast<std::size_t>(3 * k + c)] = a[static_cast<std::size_t>(k)][c];
            p[static_cast<std::size_t>(9 + 3 * k + c)] = b[static_cast<std::size_t>(k)][c];
        }
    }
    return p;
}

FTri tri(F a, F b, F c) { return {a, b, c}; }

// Corners rounded to float after adding the offset in double: the float pair closest to the
// intended one (the hard cases state what they test for the rounded values).
FTri shifted(const FTri& t, glm::dvec3 o) {
    FTri r;
    for (std::size_t k = 0; k < 3; ++k)
        r[k] = F(static_cast<float>(o.x + t[k].x), static_cast<float>(o.y + t[k].y), static_cast<float>(o.z + t[k].z));
    return r;
}

void addVariants(std::vector<NamedTriPair>& out, const std::string& name, const FTri& a, const FTri& b) {
    for (std::size_t r = 0; r < 3; ++r) {
        const FTri ar{a[r], a[(r + 1) % 3], a[(r + 2) % 3]};
        const FTri br{b[(r + 1) % 3], b[(r + 2) % 3], b[r]};
        out.push_back({name + " (rotation " + std::to_string(r) + ")", pairOf(ar, br)});
        out.push_back({name + " (swapped, rotation " + std::to_string(r) + ")", pairOf(br, ar)});
    }
}

float up(float v) { return std::nextafter(v, std::numeric_limits<float>::infinity()); }
float down(float v) { return std::nextafter(v, -std::numeric_limits<float>::infinity()); }

} // namespace

const char* toString(TriTriSet set) {
    switch (set) {
    case TriTriSet::Uniform: return "uniform";
    case TriTriSet::Grid: return "grid";
    case TriTriSet::Coplanar: return "coplanar";
    case TriTriSet::Touching: return "touching";
    case TriTriSet::Ulp: return "ulp";
    case TriTriSet::Degenerate: return "degenerate";
    case TriTriSet::Scaled: return "scaled";
    }
    return "?";
}

glm::dvec3 corner(const FloatTriPair& p, int k) {
    const auto i = static_cast<std::size_t>(3 * k);
    return {p[i], p[i + 1], p[i + 2]};
}

bool exactPairIntersects(const FloatTriPair& p) {
    return exactTrianglesIntersect({corner(p, 0), corner(p, 1), corner(p, 2)}, {corner(p, 3), corner(p, 4), corner(p, 5)});
}

std::vector<NamedTriPair> hardTriTriCases() {
    std::vector<NamedTriPair> c;
    const FTri unit = tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    // Coplanar.
    addVariants(c, "coplanar overlap", unit, tri({0.25f, 0.25f, 0}, {2, 0.25f, 0}, {0.25f, 2, 0}));
    addVariants(c, "coplanar, one inside the other", unit, tri({0.1f, 0.1f, 0}, {0.2f, 0.1f, 0}, {0.1f, 0.2f, 0}));
    addVariants(c, "coplanar disjoint across the hypotenuse", unit, tri({1, 1, 0}, {2, 1, 0}, {1, 2, 0}));
    addVariants(c, "coplanar, vertex on the hypotenuse", unit, tri({0.5f, 0.5f, 0}, {2, 0.5f, 0}, {0.5f, 2, 0}));
    addVariants(c, "coplanar, one float step off the hypotenuse", unit,
                tri({up(0.5f), 0.5f, 0}, {2, 0.5f, 0}, {up(0.5f), 2, 0}));
    addVariants(c, "coplanar, edges overlapping collinearly", unit, tri({0.5f, 0, 0}, {2, 0, 0}, {1, -1, 0}));
    addVariants(c, "coplanar, edges collinear and apart", unit, tri({up(1.0f), 0, 0}, {2, 0, 0}, {1.5f, -1, 0}));
    // Touching.
    addVariants(c, "shared vertex", unit, tri({1, 0, 0}, {2, 0, 1}, {2, 1, 0}));
    addVariants(c, "shared edge", unit, tri({0, 0, 0}, {1, 0, 0}, {0, -1, 0.5f}));
    addVariants(c, "identical triangles", unit, unit);
    addVariants(c, "vertex touching the face", unit, tri({0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}, {1, 1, 1}));
    addVariants(c, "one denormal step above the face", unit, tri({0.25f, 0.25f, up(0.0f)}, {0.25f, 0.25f, 1}, {1, 1, 1}));
    addVariants(c, "1e-30 above the face", unit, tri({0.25f, 0.25f, 1e-30f}, {0.25f, 0.25f, 1}, {1, 1, 1}));
    addVariants(c, "vertex on an edge from above", unit, tri({0.5f, 0, 0}, {0.5f, -1, 1}, {0.5f, 1, 1}));
    // Edge crossing edge at one point: T2 in the plane x = 0.5 meets z = 0 along y in [-5/3, 0].
    const FTri t2 = tri({0.5f, -1, -1}, {0.5f, 1, 1}, {0.5f, -3, 2});
    addVariants(c, "edge crosses edge at one point", unit, t2);
    addVariants(c, "edge crossing moved 2^-20 away", unit, shifted(t2, {0, -0x1p-20, 0}));
    addVariants(c, "edge crossing moved one ulp away", unit,
                tri({0.5f, down(-1.0f), -1}, {0.5f, down(1.0f), 1}, {0.5f, -3, 2}));
    // Slanted plane z = x/2 + y/4: (0.25, 0.25) lies at z = 0.1875 exactly.
    const FTri slanted = tri({0, 0, 0}, {1, 0, 0.5f}, {0, 1, 0.25f});
    const float z = 0.1875f;
    addVariants(c, "apex on a slanted plane", slanted, tri({0.25f, 0.25f, z}, {0.25f, 0.25f, 2}, {1, 1, 2}));
    addVariants(c, "apex one ulp above a slanted plane", slanted, tri({0.25f, 0.25f, up(z)}, {0.25f, 0.25f, 2}, {1, 1, 2}));
    addVariants(c, "apex one ulp below a slanted plane", slanted, tri({0.25f, 0.25f, down(z)}, {0.25f, 0.25f, 2}, {1, 1, 2}));
    // Small triangles far from the origin (float spacing at 1e4 is 2^-10 ~ 1e-3: near-degenerate).
    const glm::dvec3 o{1e4, -1e4, 1e4};
    const FTri farA = shifted(tri({0, 0, 0}, {1e-3f, 0, 0}, {0, 1e-3f, 0}), o);
    addVariants(c, "far away, crossing", farA, shifted(tri({2e-4f, 2e-4f, -1e-3f}, {2e-4f, 2e-4f, 1e-3f}, {5e-4f, 3e-4f, 0}), o));
    addVariants(c, "far away, above", farA, shifted(tri({2e-4f, 2e-4f, 1e-9f}, {2e-4f, 2e-4f, 1e-3f}, {5e-4f, 3e-4f, 1e-3f}), o));
    FTri touching = shifted(tri({2e-4f, 2e-4f, 0}, {2e-4f, 2e-4f, 1e-3f}, {5e-4f, 3e-4f, 1e-3f}), o);
    addVariants(c, "far away, touching", farA, touching);
    touching[0].z = up(touching[0].z);
    addVariants(c, "far away, one ulp above", farA, touching);
    const FTri farB = shifted(tri({0, 0, 0}, {0.0625f, 0, 0}, {0, 0.0625f, 0}), {1e4, 1e4, 1e4});
    addVariants(c, "far away exact, apex on the face", farB,
                shifted(tri({0.015625f, 0.015625f, 0}, {0.015625f, 0.015625f, 1}, {0.03125f, 0, 1}), {1e4, 1e4, 1e4}));
    // Tiny.
    const FTri tiny = tri({0, 0, 0}, {1e-6f, 0, 0}, {0, 1e-6f, 0});
    addVariants(c, "tiny crossing", tiny, tri({2e-7f, 2e-7f, -1e-6f}, {2e-7f, 2e-7f, 1e-6f}, {5e-7f, 3e-7f, 0}));
    addVariants(c, "tiny, 1e-13 above", tiny, tri({2e-7f, 2e-7f, 1e-13f}, {2e-7f, 2e-7f, 1e-6f}, {5e-7f, 3e-7f, 1e-6f}));
    addVariants(c, "tiny, touching", tiny, tri({2.5e-7f, 2.5e-7f, 0}, {2e-7f, 2e-7f, 1e-6f}, {5e-7f, 3e-7f, 1e-6f}));
    // Zero-area triangles.
    const FTri segment = tri({0.25f, 0.25f, -1}, {0.25f, 0.25f, 1}, {0.25f, 0.25f, 0.5f});
    addVariants(c, "degenerate segment piercing the face", unit, segment);
    addVariants(c, "degenerate segment missing", unit, shifted(segment, {1, 1, 0}));
    addVariants(c, "degenerate segment ending on the face", unit, tri({0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}, {0.25f, 0.25f, 0.5f}));
    addVariants(c, "degenerate segment in the plane, crossing an edge", unit, tri({-1, 0.5f, 0}, {0, 0.5f, 0}, {1, 0.5f, 0}));
    addVariants(c, "degenerate segment in the plane, outside", unit, tri({-1, -0.5f, 0}, {0, -0.5f, 0}, {1, -0.5f, 0}));
    const FTri point = tri({0.25f, 0.25f, 0}, {0.25f, 0.25f, 0}, {0.25f, 0.25f, 0});
    addVariants(c, "point on the face", unit, point);
    addVariants(c, "point on an edge", unit, tri({0.5f, 0, 0}, {0.5f, 0, 0}, {0.5f, 0, 0}));
    addVariants(c, "point one denormal step above", unit,
                tri({0.25f, 0.25f, up(0.0f)}, {0.25f, 0.25f, up(0.0f)}, {0.25f, 0.25f, up(0.0f)}));
    addVariants(c, "same point", point, point);
    addVariants(c, "points one ulp apart", point, tri({up(0.25f), 0.25f, 0}, {up(0.25f), 0.25f, 0}, {up(0.25f), 0.25f, 0}));
    addVariants(c, "point on a degenerate segment", point, tri({0, 0, 0}, {0.5f, 0.5f, 0}, {0.125f, 0.125f, 0}));
    addVariants(c, "point just off a degenerate segment", point, tri({0, 0, 0}, {0.5f, up(0.5f), 0}, {0, 0, 0}));
    const FTri s1 = tri({0, 0, 0}, {1, 1, 0}, {0.5f, 0.5f, 0});
    const FTri s2 = tri({0, 1, 0}, {1, 0, 0}, {0.25f, 0.75f, 0});
    addVariants(c, "two degenerate segments crossing", s1, s2);
    addVariants(c, "skew degenerate segments", s1, shifted(s2, {0, 0, 1e-9}));
    addVariants(c, "degenerate segments one ulp apart", s1, tri({0, 1, up(0.0f)}, {1, 0, up(0.0f)}, {0.25f, 0.75f, up(0.0f)}));
    const FTri collinearA = tri({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
    addVariants(c, "collinear segments touching at an end", collinearA, tri({2, 0, 0}, {3, 0, 0}, {4, 0, 0}));
    addVariants(c, "collinear segments apart", collinearA, tri({2.5f, 0, 0}, {3, 0, 0}, {4, 0, 0}));
    addVariants(c, "collinear segments one ulp apart", collinearA, tri({up(2.0f), 0, 0}, {3, 0, 0}, {4, 0, 0}));
    addVariants(c, "parallel segments", collinearA, tri({0, up(0.0f), 0}, {3, up(0.0f), 0}, {1, up(0.0f), 0}));
    // Denormal and huge coordinates.
    const float dn = 1e-40f; // denormal
    const FTri denormalTri = tri({0, 0, 0}, {dn, 0, 0}, {0, dn, 0});
    addVariants(c, "denormal triangle pierced", denormalTri, tri({dn / 4, dn / 4, -dn}, {dn / 4, dn / 4, dn}, {dn, dn, 0}));
    addVariants(c, "denormal triangle missed", denormalTri, tri({dn, dn, -dn}, {dn, dn, dn}, {2 * dn, 2 * dn, 0}));
    addVariants(c, "denormal triangle, touching at a corner", denormalTri, tri({dn, 0, 0}, {2 * dn, 0, dn}, {2 * dn, dn, 0}));
    const float h = 3e38f;
    const FTri hugeTri = tri({-h, -h, 0}, {h, -h, 0}, {0, h, 0});
    addVariants(c, "huge triangles crossing", hugeTri, tri({0, 0, -h}, {0, 0, h}, {h, h, h}));
    addVariants(c, "huge triangle touched by a vertex", hugeTri, tri({0, 0, 0}, {0, 0, h}, {h, h, h}));
    addVariants(c, "huge triangle, vertex a denormal step above", hugeTri, tri({0, 0, up(0.0f)}, {0, 0, h}, {h, h, h}));
    addVariants(c, "huge and tiny: tiny triangle on a huge one", hugeTri, tri({0, 0, 0}, {1e-30f, 0, 0}, {0, 1e-30f, 0}));
    addVariants(c, "1e30 coordinates, apex on a slanted plane",
                tri({0, 0, 0}, {1e30f, 0, 0.5e30f}, {0, 1e30f, 0.25e30f}),
                tri({0.25e30f, 0.25e30f, 0.1875e30f}, {0.25e30f, 0.25e30f, 2e30f}, {1e30f, 1e30f, 2e30f}));
    return c;
}

namespace {

class Generator {
public:
    explicit Generator(std::uint32_t seed) : m_rng(seed) {}

    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(m_rng); }
    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(m_rng); }
    /// Grid point: integers in [-n, n] times `step` (a power of two, so exact).
    F gridPoint(int n, float step) {
        return F(static_cast<float>(integer(-n, n)) * step, static_cast<float>(integer(-n, n)) * step,
                 static_cast<float>(integer(-n, n)) * step);
    }
    FTri gridTri(int n, float step) { return tri(gridPoint(n, step), gridPoint(n, step), gridPoint(n, step)); }

    FloatTriPair uniformPair() {
        const F centre(uniform(-1, 1) * 0.6f, uniform(-1, 1) * 0.6f, uniform(-1, 1) * 0.6f);
        FTri a, b;
        for (F& v : a) v = F(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * 0.5f;
        for (F& v : b) v = centre + F(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * 0.5f;
        return pairOf(a, b);
    }

    FloatTriPair gridPair() { return pairOf(gridTri(2, 0.5f), gridTri(2, 0.5f)); }

    FloatTriPair coplanarPair() {
        // Lattice points o + i u + j v of the plane spanned by the integer vectors u, v: exact.
        F u, v;
        do {
            u = gridPoint(3, 1.0f);
            v = gridPoint(3, 1.0f);
        } while (glm::length(glm::cross(u, v)) == 0.0f);
        const F o = gridPoint(4, 1.0f);
        auto p = [&] { return (o + static_cast<float>(integer(-3, 3)) * u + static_cast<float>(integer(-3, 3)) * v) * 0.25f; };
        return pairOf(tri(p(), p(), p()), tri(p(), p(), p()));
    }

    /// B touches A by construction (exact in float: dyadic grid, dyadic weights).
    FloatTriPair touchingPair() {
        FTri a;
        do a = gridTri(8, 0.125f);
        while (glm::length(glm::cross(a[1] - a[0], a[2] - a[0])) == 0.0f);
        const auto i = static_cast<std::size_t>(integer(0, 2)), j = (i + 1) % 3, k = (i + 2) % 3;
        const F r1 = gridPoint(8, 0.125f), r2 = gridPoint(8, 0.125f);
        switch (integer(0, 4)) {
        case 0: return pairOf(a, tri(a[i], r1, r2));    // shared corner
        case 1: return pairOf(a, tri(a[i], a[j], r1));  // shared edge
        case 2: {                                        // corner on the face
            const int w0 = integer(0, 4), w1 = integer(0, 4 - w0), w2 = 4 - w0 - w1;
            const F p = (static_cast<float>(w0) * a[i] + static_cast<float>(w1) * a[j] + static_cast<float>(w2) * a[k]) * 0.25f;
            return pairOf(a, tri(p, r1, r2));
        }
        case 3: { // an edge of B crosses an edge of A at its point q
            const int w = integer(0, 4);
            const F q = (static_cast<float>(w) * a[i] + static_cast<float>(4 - w) * a[j]) * 0.25f;
            const F d = gridPoint(4, 0.125f);
            return pairOf(a, tri(q - d, q + d, r1));
        }
        default: { // coplanar: B's corner on A's edge, B in A's plane
            const F q = (a[i] + a[j]) * 0.5f;
            return pairOf(a, tri(q, q + (a[k] - a[i]), q - (a[k] - a[j])));
        }
        }
    }

    FloatTriPair ulpPair() {
        FloatTriPair p = touchingPair();
        const auto c = static_cast<std::size_t>(9 + integer(0, 8));
        p[c] = integer(0, 1) == 0 ? up(p[c]) : down(p[c]);
        return p;
    }

    FTri degenerateTri(const FTri& other) {
        const F p = gridPoint(4, 0.25f), d = gridPoint(2, 0.25f);
        switch (integer(0, 4)) {
        case 0: return tri(p, p, p);                                           // point
        case 1: return tri(p, p + d, p + 2.0f * d);                            // segment, middle corner
        case 2: return tri(p + d, p, p + d);                                   // segment, repeated corner
        case 3: {                                                              // point on `other`
            const F q = (other[0] + other[1] + 2.0f * other[2]) * 0.25f;
            return tri(q, q, q);
        }
        default: { // segment through a point of `other`
            const F q = (other[0] + other[1]) * 0.5f;
            return tri(q - d, q + d, q);
        }
        }
    }

    FloatTriPair degeneratePair() {
        const FTri a = gridTri(4, 0.25f);
        const FTri b = degenerateTri(a);
        return integer(0, 2) == 0 ? pairOf(degenerateTri(b), b) : pairOf(a, b);
    }

    FloatTriPair scaledPair() {
        FloatTriPair p = integer(0, 1) == 0 ? gridPair() : touchingPair();
        const float scale = std::ldexp(1.0f, integer(-20, 20));
        const glm::dvec3 offset = integer(0, 1) == 0 ? glm::dvec3(0.0)
                                                     : glm::dvec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * 1e4;
        for (std::size_t k = 0; k < 18; ++k) p[k] = static_cast<float>(offset[static_cast<int>(k % 3)] + p[k] * scale);
        return p;
    }

private:
    std::mt19937 m_rng;
};

} // namespace

std::vector<FloatTriPair> randomTriTriPairs(TriTriSet set, std::size_t count, std::uint32_t seed) {
    Generator g(seed);
    std::vector<FloatTriPair> out;
    out.reserve(count);
    for (std::size_t n = 0; n < count; ++n) {
        switch (set) {
        case TriTriSet::Uniform: out.push_back(g.uniformPair()); break;
        case TriTriSet::Grid: out.push_back(g.gridPair()); break;
        case TriTriSet::Coplanar: out.push_back(g.coplanarPair()); break;
        case TriTriSet::Touching: out.push_back(g.touchingPair()); break;
        case TriTriSet::Ulp: out.push_back(g.ulpPair()); break;
        case TriTriSet::Degenerate: out.push_back(g.degeneratePair()); break;
        case TriTriSet::Scaled: out.push_back(g.scaledPair()); break;
        }
    }
    return out;
}

} // namespace glcollide::cpu
