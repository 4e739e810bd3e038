// Violated pairs (issue 24; decision 0025, "The premise without a winding-number pass"): the CPU
// twin cpu::radialViolatedPairs against the GMP oracle (cpu::exactTrianglesIntersect) on a tube
// whose two openings are closed by ghost fans (model::ghostTriangles), at rest and with a wall
// node pushed through one fan. A real face that crosses a ghost face makes the closed surface
// non-embedded: the theorem's premise fails, and the surface's observer must not cull.

#include "cpu/oracle/exact_tri_tri.hpp"
#include "cpu/radial_twin.hpp"
#include "model/ghost_triangles.hpp"
#include "tube_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace glcollide {
namespace {

// A tube around +Z (`ring` nodes per ring, `rings` rings from z = 0 to `length`), faces outward,
// both openings closed by ghost fans: faceIndices real faces first, then ghost faces; positions
// real nodes, then ghost nodes (float, as the GPU holds them).
struct ClosedTube {
    std::vector<std::uint32_t> faceIndices;
    std::size_t realFaces = 0;
    std::vector<glm::dvec3> realPositions;
    model::GhostTriangles ghosts;
    std::vector<glm::vec3> positions() const {
        std::vector<glm::vec3> x(realPositions.begin(), realPositions.end());
        for (const glm::dvec3& g : model::ghostNodePositions(ghosts, realPositions)) x.emplace_back(g);
        return x;
    }
};

ClosedTube closedTube(std::uint32_t ring, std::uint32_t rings, double radius, double length) {
    ClosedTube t;
    const detail::SurfaceMesh m = test::tube(ring, rings, radius, length);
    t.realPositions = m.positions;
    std::vector<model::Triangle> faces(m.faces.begin(), m.faces.end());
    model::GhostSettings fillAll;
    fillAll.maxPerimeter = std::numeric_limits<double>::infinity();
    t.ghosts = model::ghostTriangles(faces, t.realPositions, fillAll);
    t.realFaces = faces.size();
    for (const model::Triangle& f : faces) t.faceIndices.insert(t.faceIndices.end(), f.begin(), f.end());
    for (const model::Triangle& f : t.ghosts.faces)
        t.faceIndices.insert(t.faceIndices.end(), f.begin(), f.end());
    return t;
}

// The oracle's answer: every pair with at least one ghost face, sharing no node, that intersects
// exactly (GMP, on the same float coordinates).
std::vector<cpu::RadialFacePair> oracleViolatedPairs(const std::vector<std::uint32_t>& faceIndices,
                                                     std::size_t realFaces, const std::vector<glm::vec3>& x) {
    const std::size_t faces = faceIndices.size() / 3;
    const auto triangle = [&](std::size_t f) {
        return cpu::Triangle{glm::dvec3(x[faceIndices[3 * f]]), glm::dvec3(x[faceIndices[3 * f + 1]]),
                             glm::dvec3(x[faceIndices[3 * f + 2]])};
    };
    std::vector<cpu::RadialFacePair> pairs;
    for (std::size_t g = realFaces; g < faces; ++g)
        for (std::size_t f = 0; f < g; ++f) {
            bool shared = false;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    shared = shared || faceIndices[3 * f + i] == faceIndices[3 * g + j];
            if (!shared && cpu::exactTrianglesIntersect(triangle(f), triangle(g)))
                pairs.push_back({static_cast<std::uint32_t>(f), static_cast<std::uint32_t>(g)});
        }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

TEST(RadialViolated, AClosedTubeAtRestHasNone) {
    const ClosedTube t = closedTube(12, 5, 0.3, 0.8);
    ASSERT_EQ(t.ghosts.faces.size(), 24u) << "both openings filled, 12 ghost faces each";
    const std::vector<glm::vec3> x = t.positions();
    EXPECT_TRUE(cpu::radialViolatedPairs(t.faceIndices, t.realFaces, x).empty());
    EXPECT_TRUE(oracleViolatedPairs(t.faceIndices, t.realFaces, x).empty());
}

// A wall node of the second ring pushed to z = −0.1 near the axis: its faces pass through the
// plane of the z = 0 opening inside it, so they cross that opening's ghost fan. Every pair the
// oracle finds, and only those, is reported; the other opening's fan is not crossed.
TEST(RadialViolated, AWallPushedThroughAnOpeningCrossesItsFan) {
    const std::uint32_t ring = 12;
    ClosedTube t = closedTube(ring, 5, 0.3, 0.8);
    t.realPositions[ring] = glm::dvec3(0.05, 0.02, -0.1); // node (0, 1)
    const std::vector<glm::vec3> x = t.positions();
    const std::vector<cpu::RadialFacePair> twin = cpu::radialViolatedPairs(t.faceIndices, t.realFaces, x);
    const std::vector<cpu::RadialFacePair> oracle = oracleViolatedPairs(t.faceIndices, t.realFaces, x);
    EXPECT_EQ(twin, oracle);
    ASSERT_FALSE(twin.empty()) << "the pushed faces must cross the fan";
    for (const cpu::RadialFacePair& p : twin) {
        EXPECT_LT(p[0], t.realFaces) << "a real face against a ghost face (the fans do not cross each other)";
        const std::uint32_t ghostFace = p[1] - static_cast<std::uint32_t>(t.realFaces);
        EXPECT_EQ(t.ghosts.faceGhostNode[ghostFace], t.ghosts.faceGhostNode[0])
            << "the fan of the z = 0 opening (the loop with the lowest node comes first)";
    }
}

// Two ghost fans that cross each other (the tube squashed so that its far opening passes through
// the near one) are violated pairs too: both are part of the closed surface.
TEST(RadialViolated, GhostFansThatCrossEachOtherAreReported) {
    const std::uint32_t ring = 8, rings = 3;
    ClosedTube t = closedTube(ring, rings, 0.3, 0.4);
    // Fold the far ring back to z = 0, half the radius, turned by half a step: its fan lies in the
    // plane of the near fan, inside it (coplanar, overlapping).
    for (std::uint32_t i = 0; i < ring; ++i) {
        const double angle = 2.0 * std::numbers::pi * (i + 0.5) / ring;
        t.realPositions[(rings - 1) * ring + i] =
            glm::dvec3(0.15 * std::cos(angle), 0.15 * std::sin(angle), 0.0);
    }
    const std::vector<glm::vec3> x = t.positions();
    const std::vector<cpu::RadialFacePair> twin = cpu::radialViolatedPairs(t.faceIndices, t.realFaces, x);
    EXPECT_EQ(twin, oracleViolatedPairs(t.faceIndices, t.realFaces, x));
    bool ghostWithGhost = false;
    for (const cpu::RadialFacePair& p : twin) ghostWithGhost = ghostWithGhost || p[0] >= t.realFaces;
    EXPECT_TRUE(ghostWithGhost);
}

} // namespace
} // namespace glcollide
