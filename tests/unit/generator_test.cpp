// Generators: exact counts, orientation, volumes.
#include "model/ghost_triangles.hpp"
#include "scene/scene_detail.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

using namespace glcollide;
using namespace glcollide::detail;

namespace {

std::size_t countKind(const Body& b, SpringKind k) {
    std::size_t n = 0;
    for (const Spring& s : b.springs) n += s.kind == k ? 1u : 0u;
    return n;
}

double enclosedVolume(const Body& b) {
    double v = 0.0;
    for (const Face& f : b.faces)
        v += glm::dot(b.positions[f[0]], glm::cross(b.positions[f[1]], b.positions[f[2]])) / 6.0;
    return v;
}

/// A sum of many signed volumes (det/6 terms) with an a-priori bound on its rounding error.
struct BoundedSum {
    long double value = 0.0L;
    long double absSum = 0.0L;    // Σ |term|
    long double termError = 0.0L; // Σ of each term's own rounding bound
    std::size_t terms = 0;
    /// Adds fl(u · (v × w)) / 6, where u, v, w are differences of exact doubles that were each rounded
    /// once. Each of the determinant's 6 monomials u_i v_j w_k then carries at most 9 roundings (3
    /// differences, 2 in the cross product, 3 in the dot product, 1 in the division), so the term's
    /// error is at most γ₉ · perm(|u|, |v|, |w|) / 6 < 10·unit_roundoff · perm / 6, where perm is
    /// the determinant with every product's sign made + and every entry made positive.
    void add(double det, const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& w) {
        const glm::dvec3 au = glm::abs(u), av = glm::abs(v), aw = glm::abs(w);
        const double perm = au.x * (av.y * aw.z + av.z * aw.y) + au.y * (av.z * aw.x + av.x * aw.z) +
                            au.z * (av.x * aw.y + av.y * aw.x);
        constexpr double unitRoundoff = std::numeric_limits<double>::epsilon() / 2.0;
        value += det / 6.0;
        absSum += std::abs(det / 6.0);
        termError += 10.0 * unitRoundoff * perm / 6.0;
        ++terms;
    }
    /// The terms' errors plus the long double recursive summation's, (n − 1)·u_ld·Σ|term| (Higham,
    /// Accuracy and Stability of Numerical Algorithms, §4.2; u_ld = u where long double is double).
    long double errorBound() const {
        constexpr long double unitRoundoff = std::numeric_limits<long double>::epsilon() / 2.0L;
        return termError + static_cast<long double>(terms) * unitRoundoff * absSum;
    }
};

/// The tets' volumes exactly as mass lumping computes them (tetDet / 6).
BoundedSum tetVolumes(const Body& b) {
    BoundedSum sum;
    for (const Tet& t : b.tets) {
        const glm::dvec3 &p0 = b.positions[t[0]], &p1 = b.positions[t[1]], &p2 = b.positions[t[2]],
                         &p3 = b.positions[t[3]];
        sum.add(tetDet(p0, p1, p2, p3), p1 - p0, p2 - p0, p3 - p0);
    }
    return sum;
}

/// The volume enclosed by the faces, Σ det(a, b, c) / 6, evaluated as a · ((b − a) × (c − a)) / 6
/// (the same value: a · (a × ·) = 0), which does not cancel for small faces far from the origin.
/// (a is not a rounded difference, which only makes the bound of BoundedSum::add looser.)
BoundedSum surfaceVolume(const Body& b) {
    BoundedSum sum;
    for (const Face& f : b.faces) {
        const glm::dvec3 a = b.positions[f[0]], u = b.positions[f[1]] - a, w = b.positions[f[2]] - a;
        sum.add(glm::dot(a, glm::cross(u, w)), a, u, w);
    }
    return sum;
}

/// A face with its smallest index first, winding kept.
Face canonical(Face f) {
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
}

double tetVolumeSum(const Body& b, bool requirePositive) {
    double v = 0.0;
    for (const Tet& t : b.tets) {
        const double d =
            tetDet(b.positions[t[0]], b.positions[t[1]], b.positions[t[2]], b.positions[t[3]]) / 6.0;
        if (requirePositive) {
            EXPECT_GT(d, 0.0);
        }
        v += d;
    }
    return v;
}

void expectUniqueSprings(const Body& b) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    for (const Spring& s : b.springs) {
        EXPECT_NE(s.a, s.b);
        EXPECT_TRUE(seen.insert(std::minmax(s.a, s.b)).second) << s.a << "-" << s.b;
    }
}

} // namespace

TEST(GeneratorCloth, CountsAndLayout) {
    for (auto [nx, ny] : {std::pair{2, 2}, std::pair{5, 3}, std::pair{32, 32}}) {
        const Body b = generateCloth(2.0, 1.0, nx, ny, true, true);
        const auto unx = static_cast<std::size_t>(nx), uny = static_cast<std::size_t>(ny);
        EXPECT_EQ(b.positions.size(), unx * uny);
        EXPECT_EQ(b.faces.size(), 2 * (unx - 1) * (uny - 1));
        EXPECT_EQ(countKind(b, SpringKind::Structural), (unx - 1) * uny + unx * (uny - 1));
        EXPECT_EQ(countKind(b, SpringKind::Shear), 2 * (unx - 1) * (uny - 1));
        EXPECT_EQ(countKind(b, SpringKind::Bend), (unx - 2) * uny + unx * (uny - 2));
        expectUniqueSprings(b);
        // Row 0 is the top edge, node 0 its left end; XY plane centred at the origin.
        EXPECT_EQ(b.positions[0], glm::dvec3(-1.0, 0.5, 0.0));
        EXPECT_EQ(b.positions[unx - 1], glm::dvec3(1.0, 0.5, 0.0));
        EXPECT_EQ(b.positions.back(), glm::dvec3(1.0, -0.5, 0.0));
        for (const Face& f : b.faces) {
            const glm::dvec3 n =
                glm::cross(b.positions[f[1]] - b.positions[f[0]], b.positions[f[2]] - b.positions[f[0]]);
            EXPECT_GT(n.z, 0.0); // counter-clockwise seen from +Z
        }
    }
    const Body plain = generateCloth(1.0, 1.0, 4, 4, false, false);
    EXPECT_EQ(plain.springs.size(), countKind(plain, SpringKind::Structural));
}

// The sleeve of issue 24: a tube around Y, faces away from the axis, its two end rings the only
// boundary loops (model::boundaryLoops, independent of the generator's indexing).
TEST(GeneratorTube, CountsOrientationAndTwoOpenEnds) {
    for (auto [around, along] : {std::pair{3, 2}, std::pair{16, 12}}) {
        const Body b = generateTube(0.1, 0.4, around, along);
        const auto ua = static_cast<std::size_t>(around), ul = static_cast<std::size_t>(along);
        EXPECT_EQ(b.positions.size(), ua * ul);
        EXPECT_EQ(b.faces.size(), 2 * ua * (ul - 1));
        EXPECT_TRUE(b.springs.empty());                       // the scene adds a surface's springs
        EXPECT_EQ(b.positions[0], glm::dvec3(0.1, 0.2, 0.0)); // ring 0 at the top, node 0 on +X
        EXPECT_NEAR(b.positions.back().y, -0.2, 1e-15);
        for (const Face& f : b.faces) {
            const glm::dvec3 a = b.positions[f[0]],
                             n = glm::cross(b.positions[f[1]] - a, b.positions[f[2]] - a);
            const glm::dvec3 centre = (a + b.positions[f[1]] + b.positions[f[2]]) / 3.0;
            EXPECT_GT(glm::dot(n, glm::dvec3(centre.x, 0.0, centre.z)), 0.0); // away from the axis
        }
        const auto loops = model::boundaryLoops(b.faces, b.positions.size());
        ASSERT_EQ(loops.size(), 2u);
        for (const auto& loop : loops) {
            EXPECT_TRUE(loop.closed);
            EXPECT_EQ(loop.nodes.size(), ua);
        }
    }
}

// The elbow of scenes/elbow.json: bent by 90 degrees in its middle third. Each ring is a circle of
// the radius around its mean, perpendicular to the axis; the top ring where the straight tube's is,
// the last ring's centre where the arc's end plus a third of the length along +X puts it; faces
// away from the axis; still two open ends.
TEST(GeneratorTube, ABentTubeKeepsItsRingsRoundAndFacingOut) {
    const int around = 16, along = 13;
    const double radius = 0.05, length = 0.6, third = length / 3.0, arc = third / (std::numbers::pi / 2.0);
    const Body b = generateTube(radius, length, around, along, 90.0);
    const Body straight = generateTube(radius, length, around, along);
    const auto ua = static_cast<std::size_t>(around);
    std::vector<glm::dvec3> centres;
    for (std::size_t j = 0; j < static_cast<std::size_t>(along); ++j) {
        glm::dvec3 c(0.0);
        for (std::size_t i = 0; i < ua; ++i) c += b.positions[j * ua + i];
        c /= static_cast<double>(around);
        centres.push_back(c);
        for (std::size_t i = 0; i < ua; ++i) // 1e-12: a few roundings of coordinates below 1
            EXPECT_NEAR(glm::length(b.positions[j * ua + i] - c), radius, 1e-12) << j << ", " << i;
    }
    for (std::size_t i = 0; i < ua; ++i) EXPECT_EQ(b.positions[i], straight.positions[i]); // the top ring
    const glm::dvec3 end = glm::dvec3(arc, 0.5 * length - third - arc, 0.0) + glm::dvec3(third, 0.0, 0.0);
    EXPECT_NEAR(glm::length(centres.back() - end), 0.0, 1e-12);
    for (const Face& f : b.faces) {
        const glm::dvec3 a = b.positions[f[0]], n = glm::cross(b.positions[f[1]] - a, b.positions[f[2]] - a);
        const glm::dvec3 centre = (a + b.positions[f[1]] + b.positions[f[2]]) / 3.0;
        const glm::dvec3 axis = 0.5 * (centres[f[0] / ua] + centres[f[2] / ua]);
        EXPECT_GT(glm::dot(n, centre - axis), 0.0);
    }
    EXPECT_EQ(model::boundaryLoops(b.faces, b.positions.size()).size(), 2u);
    // The smallest bends (down to a subnormal angle) give the straight tube, never inf or NaN.
    // 1e-310 degrees is a subnormal angle in radians (1.7e-312), whose own rounding (its unit in the
    // last place, 4.9e-324, is 3e-12 of it) moves points by up to 3e-12 of coordinates below 1 m:
    // 1e-11 bounds that and the roundings of the formula.
    for (double degrees : {1e-12, 1e-300, 1e-310, 4.9e-324}) {
        const Body nearlyStraight = generateTube(radius, length, around, along, degrees);
        for (std::size_t k = 0; k < straight.positions.size(); ++k)
            EXPECT_NEAR(glm::length(nearlyStraight.positions[k] - straight.positions[k]), 0.0, 1e-11)
                << degrees;
    }
}

TEST(GeneratorTetBox, BoundaryVolumeAndOrientation) {
    for (auto cells :
         {std::array<int, 3>{1, 1, 1}, std::array<int, 3>{3, 2, 4}, std::array<int, 3>{5, 1, 2}}) {
        const glm::dvec3 size(0.5, 2.0, 1.5);
        const Body b = generateTetBox(size, cells);
        const auto cx = static_cast<std::size_t>(cells[0]), cy = static_cast<std::size_t>(cells[1]),
                   cz = static_cast<std::size_t>(cells[2]);
        EXPECT_EQ(b.positions.size(), (cx + 1) * (cy + 1) * (cz + 1));
        EXPECT_EQ(b.tets.size(), 6 * cx * cy * cz);
        EXPECT_EQ(b.faces.size(), 2 * 2 * (cx * cy + cy * cz + cx * cz));
        // Sums of a few hundred exactly representable-ish terms: 1e-12 relative is generous.
        EXPECT_NEAR(tetVolumeSum(b, true), size.x * size.y * size.z, 1e-12);
        EXPECT_NEAR(enclosedVolume(b), size.x * size.y * size.z, 1e-12);
        expectUniqueSprings(b);
        // Every edge of every tet is a spring (and nothing else is).
        EXPECT_EQ(b.springs.size(), tetEdgeSprings(b.tets).size());
    }
}

TEST(GeneratorSphere, IcosphereCountsAndVolume) {
    for (int s = 0; s <= 5; ++s) {
        SCOPED_TRACE("subdivisions " + std::to_string(s));
        const double r = 0.7;
        const Body b = generateSphere(r, s);
        const std::size_t faces = 20u << (2 * s);
        const std::size_t surfaceVerts = 10u * (1u << (2 * s)) + 2u;
        EXPECT_EQ(b.faces.size(), faces);
        // One icosphere shell per level 0 … s (the surface is level s) and the centre.
        std::size_t nodes = 1;
        for (int k = 0; k <= s; ++k) nodes += 10u * (1u << (2 * k)) + 2u;
        EXPECT_EQ(b.positions.size(), nodes);
        EXPECT_LE(static_cast<double>(b.positions.size()), 1.4 * static_cast<double>(surfaceVerts));
        // 20 centre tets; 7 per level-(k − 1) triangle between shells k − 1 and k.
        EXPECT_EQ(b.tets.size(), 20u + 140u * ((1u << (2 * s)) - 1u) / 3u);
        // Springs are exactly the unique tet edges: a ball has Euler characteristic
        // V − E + F − T = 1 with F = (4T + boundary faces) / 2 triangles.
        EXPECT_EQ(b.springs.size(), b.positions.size() + b.tets.size() + faces / 2 - 1);
        expectUniqueSprings(b);
        std::set<std::pair<std::uint32_t, std::uint32_t>> springs, edges;
        for (const Spring& sp : b.springs) springs.insert(std::minmax(sp.a, sp.b));
        for (const Tet& t : b.tets)
            for (std::size_t i = 0; i < 4; ++i)
                for (std::size_t j = i + 1; j < 4; ++j) edges.insert(std::minmax(t[i], t[j]));
        EXPECT_EQ(springs, edges);
        for (const Spring& sp : b.springs) EXPECT_EQ(sp.kind, SpringKind::Edge);
        // The tets' boundary is the surface, triangle for triangle and winding for winding.
        std::multiset<Face> boundary, surface;
        for (const Face& f : boundaryFaces(b.tets, "sphere")) boundary.insert(canonical(f));
        for (const Face& f : b.faces) surface.insert(canonical(f));
        EXPECT_EQ(boundary, surface);
        // Every tet positive; together they fill the surface polyhedron exactly, up to rounding.
        const BoundedSum tets = tetVolumes(b), enclosed = surfaceVolume(b);
        for (const Tet& t : b.tets)
            EXPECT_GT(tetDet(b.positions[t[0]], b.positions[t[1]], b.positions[t[2]], b.positions[t[3]]),
                      0.0);
        EXPECT_LE(std::abs(tets.value - enclosed.value), tets.errorBound() + enclosed.errorBound());
        if constexpr (std::numeric_limits<long double>::digits > std::numeric_limits<double>::digits) {
            EXPECT_LT(tets.errorBound() + enclosed.errorBound(), 1e-13L * enclosed.value); // a tight check
        }
        // The surface polyhedron lies in the ball and contains the ball of radius `inner`, the
        // nearest face plane's distance (it is star-shaped about the centre: every face sees it
        // from inside). Its volume is between the two balls'.
        double inner = r;
        for (const Face& f : b.faces) {
            const glm::dvec3 &p0 = b.positions[f[0]], &p1 = b.positions[f[1]], &p2 = b.positions[f[2]];
            const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
            EXPECT_GT(glm::dot(n, p0), 0.0);
            inner = std::min(inner, glm::dot(n, p0));
        }
        const double v = static_cast<double>(enclosed.value);
        EXPECT_LT(v, 4.0 / 3.0 * std::numbers::pi * r * r * r);
        EXPECT_GE(v, 4.0 / 3.0 * std::numbers::pi * inner * inner * inner);
        EXPECT_GT(v, 0.6 * 4.0 / 3.0 * std::numbers::pi * r * r * r);
        // Surface nodes first, as on the icosphere; interior nodes strictly inside; centre last.
        for (std::size_t i = 0; i < surfaceVerts; ++i)
            EXPECT_NEAR(glm::length(b.positions[i]), r, 1e-15); // one normalisation, one scale: ~2 ulp
        for (std::size_t i = surfaceVerts; i < b.positions.size(); ++i)
            EXPECT_LT(glm::length(b.positions[i]), r);
        for (const Face& f : b.faces)
            for (std::uint32_t i : f) EXPECT_LT(i, surfaceVerts);
        EXPECT_EQ(b.positions.back(), glm::dvec3(0.0));
    }
}

TEST(GeneratorSphere, BoundedValenceAndShape) {
    // The ball has no hub: every node's spring count stays below a constant that does not grow with
    // the subdivisions (measured maxima 12, 15, 18, 19, 19, 19, also 19 at 6 and 7). Its tets
    // keep their shape: longest over shortest edge at most 2.02 (the transition from a shell to
    // the next finer one halves edges) and 6·volume at least 0.108 longest edge³ (measured, s ≤ 5;
    // checked with a little room).
    for (int s = 0; s <= 5; ++s) {
        SCOPED_TRACE("subdivisions " + std::to_string(s));
        const Body b = generateSphere(1.5, s);
        std::vector<int> valence(b.positions.size(), 0);
        for (const Spring& sp : b.springs) ++valence[sp.a], ++valence[sp.b];
        EXPECT_LE(*std::max_element(valence.begin(), valence.end()), 20);
        EXPECT_EQ(valence.back(), 12); // the centre: the 12 icosahedron nodes of the innermost shell
        for (const Tet& t : b.tets) {
            double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
            for (std::size_t i = 0; i < 4; ++i)
                for (std::size_t j = i + 1; j < 4; ++j) {
                    const double len = glm::length(b.positions[t[i]] - b.positions[t[j]]);
                    shortest = std::min(shortest, len);
                    longest = std::max(longest, len);
                }
            EXPECT_LE(longest, 2.05 * shortest);
            EXPECT_GE(tetDet(b.positions[t[0]], b.positions[t[1]], b.positions[t[2]], b.positions[t[3]]),
                      0.1 * longest * longest * longest);
        }
    }
}

TEST(GeneratorSprings, BendAcrossInteriorEdges) {
    // Two triangles sharing edge 1-2: one bend spring between 0 and 3.
    const std::vector<Face> faces{{0, 1, 2}, {2, 1, 3}};
    const auto bend = surfaceBendSprings(faces);
    ASSERT_EQ(bend.size(), 1u);
    EXPECT_EQ(bend[0].a, 0u);
    EXPECT_EQ(bend[0].b, 3u);
    EXPECT_EQ(bend[0].kind, SpringKind::Bend);
    // A closed tetrahedron surface: every opposite pair is already an edge, so no bend springs.
    const std::vector<Face> tet{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    EXPECT_TRUE(surfaceBendSprings(tet).empty());
}
