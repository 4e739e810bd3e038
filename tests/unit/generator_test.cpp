// Generators: exact counts, orientation, volumes.
#include "scene/scene_detail.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>
#include <set>

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
    for (int s = 0; s <= 3; ++s) {
        const double r = 0.7;
        const Body b = generateSphere(r, s);
        const std::size_t faces = 20u << (2 * s);
        const std::size_t surfaceVerts = 10u * (1u << (2 * s)) + 2u;
        EXPECT_EQ(b.faces.size(), faces);
        EXPECT_EQ(b.positions.size(), surfaceVerts + 1);
        EXPECT_EQ(b.tets.size(), faces);
        // Springs: surface edges (3F/2) plus one radial edge per surface vertex.
        EXPECT_EQ(b.springs.size(), faces * 3 / 2 + surfaceVerts);
        expectUniqueSprings(b);
        EXPECT_EQ(boundaryFaces(b.tets, "sphere").size(), faces);
        const double v = tetVolumeSum(b, true);
        EXPECT_NEAR(enclosedVolume(b), v, 1e-12);
        // The inscribed polyhedron approaches the ball from below.
        EXPECT_LT(v, 4.0 / 3.0 * std::numbers::pi * r * r * r);
        EXPECT_GT(v, 0.6 * 4.0 / 3.0 * std::numbers::pi * r * r * r);
        for (std::size_t i = 0; i + 1 < b.positions.size(); ++i)
            EXPECT_NEAR(glm::length(b.positions[i]), r, 1e-15); // one normalisation, one scale: ~2 ulp
        EXPECT_EQ(b.positions.back(), glm::dvec3(0.0));
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
