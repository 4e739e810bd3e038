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

FTri tri(F a, F b, F c) {
    return {a, b, c};
}

// Corners rounded to float after adding the offset in double: the float pair closest to the
// intended one (the hard cases state what they test for the rounded values).
FTri shifted(const FTri& t, glm::dvec3 o) {
    FTri r;
    for (std::size_t k = 0; k < 3; ++k)
        r[k] = F(static_cast<float>(o.x + t[k].x), static_cast<float>(o.y + t[k].y),
                 static_cast<float>(o.z + t[k].z));
    return r;
}

// Rotating the corners and swapping the triangles change neither set, so the six variants share
// the hand-derived answer.
void addVariants(std::vector<NamedTriPair>& out, const std::string& name, HandAnswer expected,
                 const char* reason, const FTri& a, const FTri& b) {
    for (std::size_t r = 0; r < 3; ++r) {
        const FTri ar{a[r], a[(r + 1) % 3], a[(r + 2) % 3]};
        const FTri br{b[(r + 1) % 3], b[(r + 2) % 3], b[r]};
        out.push_back({name + " (rotation " + std::to_string(r) + ")", pairOf(ar, br), expected, reason});
        out.push_back(
            {name + " (swapped, rotation " + std::to_string(r) + ")", pairOf(br, ar), expected, reason});
    }
}

constexpr HandAnswer kMeet = HandAnswer::Intersect;
constexpr HandAnswer kApart = HandAnswer::Disjoint;

float up(float v) {
    return std::nextafter(v, std::numeric_limits<float>::infinity());
}
float down(float v) {
    return std::nextafter(v, -std::numeric_limits<float>::infinity());
}

} // namespace

const char* toString(TriTriSet set) {
    switch (set) {
    case TriTriSet::Uniform:
        return "uniform";
    case TriTriSet::Grid:
        return "grid";
    case TriTriSet::Coplanar:
        return "coplanar";
    case TriTriSet::Touching:
        return "touching";
    case TriTriSet::Ulp:
        return "ulp";
    case TriTriSet::Degenerate:
        return "degenerate";
    case TriTriSet::Scaled:
        return "scaled";
    }
    return "?";
}

glm::dvec3 corner(const FloatTriPair& p, int k) {
    const auto i = static_cast<std::size_t>(3 * k);
    return {p[i], p[i + 1], p[i + 2]};
}

bool exactPairIntersects(const FloatTriPair& p) {
    return exactTrianglesIntersect({corner(p, 0), corner(p, 1), corner(p, 2)},
                                   {corner(p, 3), corner(p, 4), corner(p, 5)});
}

std::vector<NamedTriPair> hardTriTriCases() {
    std::vector<NamedTriPair> c;
    const FTri unit = tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    // Coplanar.
    addVariants(c, "coplanar overlap", kMeet,
                "B's corner (0.25, 0.25, 0) lies inside A (x, y > 0, x + y < 1)", unit,
                tri({0.25f, 0.25f, 0}, {2, 0.25f, 0}, {0.25f, 2, 0}));
    addVariants(c, "coplanar, one inside the other", kMeet,
                "all of B's corners have x, y > 0 and x + y <= 0.4 < 1: B lies inside A", unit,
                tri({0.1f, 0.1f, 0}, {0.2f, 0.1f, 0}, {0.1f, 0.2f, 0}));
    addVariants(c, "coplanar disjoint across the hypotenuse", kApart,
                "B has x + y >= 2 everywhere, A has x + y <= 1", unit, tri({1, 1, 0}, {2, 1, 0}, {1, 2, 0}));
    addVariants(c, "coplanar, vertex on the hypotenuse", kMeet,
                "B's corner (0.5, 0.5, 0) has x + y = 1 exactly: on A's hypotenuse", unit,
                tri({0.5f, 0.5f, 0}, {2, 0.5f, 0}, {0.5f, 2, 0}));
    addVariants(c, "coplanar, one float step off the hypotenuse", kApart,
                "B has x >= 0.5 + 2^-24 and y >= 0.5 everywhere, so x + y > 1 >= A's x + y", unit,
                tri({up(0.5f), 0.5f, 0}, {2, 0.5f, 0}, {up(0.5f), 2, 0}));
    addVariants(c, "coplanar, edges overlapping collinearly", kMeet,
                "B's corner (0.5, 0, 0) lies on A's edge y = 0, 0 <= x <= 1", unit,
                tri({0.5f, 0, 0}, {2, 0, 0}, {1, -1, 0}));
    addVariants(c, "coplanar, edges collinear and apart", kApart,
                "B has x >= 1 + 2^-23 everywhere, A has x <= 1", unit,
                tri({up(1.0f), 0, 0}, {2, 0, 0}, {1.5f, -1, 0}));
    // Touching.
    addVariants(c, "shared vertex", kMeet, "both contain the corner (1, 0, 0)", unit,
                tri({1, 0, 0}, {2, 0, 1}, {2, 1, 0}));
    addVariants(c, "shared edge", kMeet, "both contain the edge (0, 0, 0)-(1, 0, 0)", unit,
                tri({0, 0, 0}, {1, 0, 0}, {0, -1, 0.5f}));
    addVariants(c, "identical triangles", kMeet, "the same triangle", unit, unit);
    addVariants(c, "vertex touching the face", kMeet, "B's corner (0.25, 0.25, 0) lies inside A", unit,
                tri({0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}, {1, 1, 1}));
    addVariants(c, "one denormal step above the face", kApart,
                "B's corners all have z > 0 (the smallest denormal, 1, 1); A lies in z = 0", unit,
                tri({0.25f, 0.25f, up(0.0f)}, {0.25f, 0.25f, 1}, {1, 1, 1}));
    addVariants(c, "1e-30 above the face", kApart,
                "B's corners all have z > 0 (1e-30, 1, 1); A lies in z = 0", unit,
                tri({0.25f, 0.25f, 1e-30f}, {0.25f, 0.25f, 1}, {1, 1, 1}));
    addVariants(c, "vertex on an edge from above", kMeet, "B's corner (0.5, 0, 0) lies on A's edge y = 0",
                unit, tri({0.5f, 0, 0}, {0.5f, -1, 1}, {0.5f, 1, 1}));
    // Edge crossing edge at one point: T2 in the plane x = 0.5 meets z = 0 along y in [-5/3, 0].
    const FTri t2 = tri({0.5f, -1, -1}, {0.5f, 1, 1}, {0.5f, -3, 2});
    addVariants(c, "edge crosses edge at one point", kMeet,
                "B meets z = 0 along y in [-5/3, 0] at x = 0.5; A holds (0.5, 0, 0)", unit, t2);
    addVariants(c, "edge crossing moved 2^-20 away", kApart,
                "the shift is exact in float: B meets z = 0 only at y <= -2^-20 < 0, A has y >= 0", unit,
                shifted(t2, {0, -0x1p-20, 0}));
    addVariants(c, "edge crossing moved one ulp away", kApart,
                "B meets z = 0 only at y <= -3 * 2^-25 < 0 (its corners' y moved down one ulp), A has y >= 0",
                unit, tri({0.5f, down(-1.0f), -1}, {0.5f, down(1.0f), 1}, {0.5f, -3, 2}));
    // Slanted plane z = x/2 + y/4: (0.25, 0.25) lies at z = 0.1875 exactly.
    const FTri slanted = tri({0, 0, 0}, {1, 0, 0.5f}, {0, 1, 0.25f});
    const float z = 0.1875f;
    addVariants(c, "apex on a slanted plane", kMeet,
                "(0.25, 0.25, 0.1875) satisfies z = x/2 + y/4 exactly and lies inside A's projection",
                slanted, tri({0.25f, 0.25f, z}, {0.25f, 0.25f, 2}, {1, 1, 2}));
    addVariants(c, "apex one ulp above a slanted plane", kApart,
                "all of B's corners lie above the plane z = x/2 + y/4 of A", slanted,
                tri({0.25f, 0.25f, up(z)}, {0.25f, 0.25f, 2}, {1, 1, 2}));
    addVariants(c, "apex one ulp below a slanted plane", kMeet,
                "B's vertical edge at (0.25, 0.25) runs from below A's plane to above it, crossing inside A",
                slanted, tri({0.25f, 0.25f, down(z)}, {0.25f, 0.25f, 2}, {1, 1, 2}));
    // Small triangles far from the origin (float spacing at 1e4 is 2^-10 ~ 1e-3: near-degenerate).
    const glm::dvec3 o{1e4, -1e4, 1e4};
    const FTri farA = shifted(tri({0, 0, 0}, {1e-3f, 0, 0}, {0, 1e-3f, 0}), o);
    addVariants(c, "far away, crossing", kMeet,
                "rounded to float (spacing 2^-10 at 1e4), B's edge at A's corner (x0, y0) spans z0 -/+ "
                "2^-10: it passes through that corner",
                farA, shifted(tri({2e-4f, 2e-4f, -1e-3f}, {2e-4f, 2e-4f, 1e-3f}, {5e-4f, 3e-4f, 0}), o));
    addVariants(c, "far away, above", kMeet,
                "1e-9 is below half the float spacing at 1e4, so after rounding B's first corner is A's "
                "corner (x0, y0, z0): touching",
                farA, shifted(tri({2e-4f, 2e-4f, 1e-9f}, {2e-4f, 2e-4f, 1e-3f}, {5e-4f, 3e-4f, 1e-3f}), o));
    FTri touching = shifted(tri({2e-4f, 2e-4f, 0}, {2e-4f, 2e-4f, 1e-3f}, {5e-4f, 3e-4f, 1e-3f}), o);
    addVariants(c, "far away, touching", kMeet, "after rounding B's first corner is A's corner (x0, y0, z0)",
                farA, touching);
    touching[0].z = up(touching[0].z);
    addVariants(c, "far away, one ulp above", kApart,
                "after rounding all of B's corners have z = z0 + 2^-10, A lies in z = z0", farA, touching);
    const FTri farB = shifted(tri({0, 0, 0}, {0.0625f, 0, 0}, {0, 0.0625f, 0}), {1e4, 1e4, 1e4});
    addVariants(c, "far away exact, apex on the face", kMeet,
                "all offsets are exact in float; B's apex o + (1/64, 1/64, 0) lies inside A (legs 1/16)",
                farB,
                shifted(tri({0.015625f, 0.015625f, 0}, {0.015625f, 0.015625f, 1}, {0.03125f, 0, 1}),
                        {1e4, 1e4, 1e4}));
    // Tiny.
    const FTri tiny = tri({0, 0, 0}, {1e-6f, 0, 0}, {0, 1e-6f, 0});
    addVariants(
        c, "tiny crossing", kMeet,
        "B's edge x = y = 2e-7 spans z = -1e-6 .. 1e-6 and crosses z = 0 inside A (x + y = 4e-7 < 1e-6)",
        tiny, tri({2e-7f, 2e-7f, -1e-6f}, {2e-7f, 2e-7f, 1e-6f}, {5e-7f, 3e-7f, 0}));
    addVariants(c, "tiny, 1e-13 above", kApart, "B's corners all have z > 0; A lies in z = 0", tiny,
                tri({2e-7f, 2e-7f, 1e-13f}, {2e-7f, 2e-7f, 1e-6f}, {5e-7f, 3e-7f, 1e-6f}));
    addVariants(c, "tiny, touching", kMeet,
                "B's corner (2.5e-7, 2.5e-7, 0) lies inside A (x + y = 5e-7 < 1e-6)", tiny,
                tri({2.5e-7f, 2.5e-7f, 0}, {2e-7f, 2e-7f, 1e-6f}, {5e-7f, 3e-7f, 1e-6f}));
    // Zero-area triangles.
    const FTri segment = tri({0.25f, 0.25f, -1}, {0.25f, 0.25f, 1}, {0.25f, 0.25f, 0.5f});
    addVariants(c, "degenerate segment piercing the face", kMeet,
                "the segment x = y = 0.25, z in [-1, 1] passes (0.25, 0.25, 0) inside A", unit, segment);
    addVariants(c, "degenerate segment missing", kApart,
                "the segment x = y = 1.25 meets z = 0 only at x + y = 2.5 > 1, outside A", unit,
                shifted(segment, {1, 1, 0}));
    addVariants(c, "degenerate segment ending on the face", kMeet,
                "the segment's end (0.25, 0.25, 0) lies inside A", unit,
                tri({0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}, {0.25f, 0.25f, 0.5f}));
    addVariants(c, "degenerate segment in the plane, crossing an edge", kMeet,
                "the segment y = 0.5, x in [-1, 1] holds (0, 0.5, 0), on A's edge x = 0", unit,
                tri({-1, 0.5f, 0}, {0, 0.5f, 0}, {1, 0.5f, 0}));
    addVariants(c, "degenerate segment in the plane, outside", kApart,
                "the segment has y = -0.5 < 0, A has y >= 0", unit,
                tri({-1, -0.5f, 0}, {0, -0.5f, 0}, {1, -0.5f, 0}));
    const FTri point = tri({0.25f, 0.25f, 0}, {0.25f, 0.25f, 0}, {0.25f, 0.25f, 0});
    addVariants(c, "point on the face", kMeet, "the point (0.25, 0.25, 0) lies inside A", unit, point);
    addVariants(c, "point on an edge", kMeet, "the point (0.5, 0, 0) lies on A's edge y = 0", unit,
                tri({0.5f, 0, 0}, {0.5f, 0, 0}, {0.5f, 0, 0}));
    addVariants(c, "point one denormal step above", kApart, "the point has z > 0; A lies in z = 0", unit,
                tri({0.25f, 0.25f, up(0.0f)}, {0.25f, 0.25f, up(0.0f)}, {0.25f, 0.25f, up(0.0f)}));
    addVariants(c, "same point", kMeet, "the same point", point, point);
    addVariants(c, "points one ulp apart", kApart, "the points differ in x by one ulp", point,
                tri({up(0.25f), 0.25f, 0}, {up(0.25f), 0.25f, 0}, {up(0.25f), 0.25f, 0}));
    addVariants(c, "point on a degenerate segment", kMeet,
                "(0.25, 0.25, 0) lies on the segment from (0, 0, 0) to (0.5, 0.5, 0)", point,
                tri({0, 0, 0}, {0.5f, 0.5f, 0}, {0.125f, 0.125f, 0}));
    addVariants(c, "point just off a degenerate segment", kApart,
                "the segment from 0 to (0.5, 0.5 + 2^-24, 0) has y = 0.25 + 2^-25 at x = 0.25", point,
                tri({0, 0, 0}, {0.5f, up(0.5f), 0}, {0, 0, 0}));
    const FTri s1 = tri({0, 0, 0}, {1, 1, 0}, {0.5f, 0.5f, 0});
    const FTri s2 = tri({0, 1, 0}, {1, 0, 0}, {0.25f, 0.75f, 0});
    addVariants(c, "two degenerate segments crossing", kMeet,
                "the diagonals y = x and x + y = 1 of the unit square cross at (0.5, 0.5, 0), in both", s1,
                s2);
    addVariants(c, "skew degenerate segments", kApart,
                "one segment lies in z = 0, the other in z = float(1e-9) > 0", s1, shifted(s2, {0, 0, 1e-9}));
    addVariants(c, "degenerate segments one ulp apart", kApart,
                "one segment lies in z = 0, the other in z = the smallest denormal > 0", s1,
                tri({0, 1, up(0.0f)}, {1, 0, up(0.0f)}, {0.25f, 0.75f, up(0.0f)}));
    const FTri collinearA = tri({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
    addVariants(c, "collinear segments touching at an end", kMeet,
                "[0, 2] and [2, 4] on the x axis share (2, 0, 0)", collinearA,
                tri({2, 0, 0}, {3, 0, 0}, {4, 0, 0}));
    addVariants(c, "collinear segments apart", kApart, "[0, 2] and [2.5, 4] on the x axis", collinearA,
                tri({2.5f, 0, 0}, {3, 0, 0}, {4, 0, 0}));
    addVariants(c, "collinear segments one ulp apart", kApart, "[0, 2] and [2 + 2^-22, 4] on the x axis",
                collinearA, tri({up(2.0f), 0, 0}, {3, 0, 0}, {4, 0, 0}));
    addVariants(c, "parallel segments", kApart,
                "one segment lies in y = 0, the other in y = the smallest denormal > 0", collinearA,
                tri({0, up(0.0f), 0}, {3, up(0.0f), 0}, {1, up(0.0f), 0}));
    // Denormal and huge coordinates.
    const float dn = 1e-40f; // denormal
    const FTri denormalTri = tri({0, 0, 0}, {dn, 0, 0}, {0, dn, 0});
    addVariants(
        c, "denormal triangle pierced", kMeet,
        "B's edge x = y = dn/4 (rounded) spans z = -dn .. dn and crosses z = 0 inside A (x + y <= dn/2)",
        denormalTri, tri({dn / 4, dn / 4, -dn}, {dn / 4, dn / 4, dn}, {dn, dn, 0}));
    addVariants(c, "denormal triangle missed", kApart,
                "B meets z = 0 along (dn, dn, 0)-(2dn, 2dn, 0), where x + y >= 2dn > dn, outside A",
                denormalTri, tri({dn, dn, -dn}, {dn, dn, dn}, {2 * dn, 2 * dn, 0}));
    addVariants(c, "denormal triangle, touching at a corner", kMeet, "both contain the corner (dn, 0, 0)",
                denormalTri, tri({dn, 0, 0}, {2 * dn, 0, dn}, {2 * dn, dn, 0}));
    const float h = 3e38f;
    const FTri hugeTri = tri({-h, -h, 0}, {h, -h, 0}, {0, h, 0});
    addVariants(c, "huge triangles crossing", kMeet,
                "B's edge x = y = 0, z in [-h, h] passes the origin, inside A", hugeTri,
                tri({0, 0, -h}, {0, 0, h}, {h, h, h}));
    addVariants(c, "huge triangle touched by a vertex", kMeet, "B's corner (0, 0, 0) lies inside A", hugeTri,
                tri({0, 0, 0}, {0, 0, h}, {h, h, h}));
    addVariants(c, "huge triangle, vertex a denormal step above", kApart,
                "B's corners all have z > 0; A lies in z = 0", hugeTri,
                tri({0, 0, up(0.0f)}, {0, 0, h}, {h, h, h}));
    addVariants(c, "huge and tiny: tiny triangle on a huge one", kMeet,
                "B's corner (0, 0, 0) lies inside A, in A's plane", hugeTri,
                tri({0, 0, 0}, {1e-30f, 0, 0}, {0, 1e-30f, 0}));
    addVariants(c, "1e30 coordinates, apex on a slanted plane", kMeet,
                "float(0.1875e30) is 2^73 below 3/16 float(1e30): the apex is just under A's plane; B's "
                "vertical edge crosses it inside A",
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
    FTri gridTri(int n, float step) {
        return tri(gridPoint(n, step), gridPoint(n, step), gridPoint(n, step));
    }

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
        auto p = [&] {
            return (o + static_cast<float>(integer(-3, 3)) * u + static_cast<float>(integer(-3, 3)) * v) *
                   0.25f;
        };
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
        case 0:
            return pairOf(a, tri(a[i], r1, r2)); // shared corner
        case 1:
            return pairOf(a, tri(a[i], a[j], r1)); // shared edge
        case 2: {                                  // corner on the face
            const int w0 = integer(0, 4), w1 = integer(0, 4 - w0), w2 = 4 - w0 - w1;
            const F p = (static_cast<float>(w0) * a[i] + static_cast<float>(w1) * a[j] +
                         static_cast<float>(w2) * a[k]) *
                        0.25f;
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
        case 0:
            return tri(p, p, p); // point
        case 1:
            return tri(p, p + d, p + 2.0f * d); // segment, middle corner
        case 2:
            return tri(p + d, p, p + d); // segment, repeated corner
        case 3: {                        // point on `other`
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
        const glm::dvec3 offset = integer(0, 1) == 0
                                      ? glm::dvec3(0.0)
                                      : glm::dvec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * 1e4;
        for (std::size_t k = 0; k < 18; ++k)
            p[k] = static_cast<float>(offset[static_cast<int>(k % 3)] + p[k] * scale);
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
        case TriTriSet::Uniform:
            out.push_back(g.uniformPair());
            break;
        case TriTriSet::Grid:
            out.push_back(g.gridPair());
            break;
        case TriTriSet::Coplanar:
            out.push_back(g.coplanarPair());
            break;
        case TriTriSet::Touching:
            out.push_back(g.touchingPair());
            break;
        case TriTriSet::Ulp:
            out.push_back(g.ulpPair());
            break;
        case TriTriSet::Degenerate:
            out.push_back(g.degeneratePair());
            break;
        case TriTriSet::Scaled:
            out.push_back(g.scaledPair());
            break;
        }
    }
    return out;
}

} // namespace glcollide::cpu
