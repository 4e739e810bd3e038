// Continuous detection in the engine (docs/ccd.md, "In the engine"): the issue's fast ball. A 6 cm
// ball shot at 12 m/s at a cloth, implicit Euler at one substep per frame, passes the cloth within
// one substep: at neither end of it is the ball within the thickness of the cloth, so discrete
// detection finds nothing; continuous detection reports the crossing with a time of impact never
// later than the analytic one (the ball's lowest node reaching the cloth's plane: a convex body's
// first contact with a plane is at a vertex) and close to it.

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace glcollide {
namespace {

constexpr double kSpeed = 12.0;      // m/s, downwards
constexpr double kDt = 1.0 / 60.0;   // s, one substep per frame
constexpr double kClothHeight = 0.0; // m

Scene fastBall(const std::string& detection) {
    const std::string json =
        R"({"format_version": 1, "name": "fast ball", "effects": ["springs", "collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1},
      "collision": {"response": "penalty", "broad_phase": "bvh", "thickness": 0.01, "detection": ")" +
        detection + R"("},
      "objects": [
        {"name": "cloth", "generator": {"type": "cloth", "size": [0.6, 0.6], "resolution": [12, 12]},
         "transform": {"rotate_deg": [90, 0, 0]}, "mass": 0.1, "springs": {"stiffness": 100}},
        {"name": "ball", "generator": {"type": "sphere", "radius": 0.06, "subdivisions": 2}, "mass": 0.2,
         "springs": {"stiffness": 500}, "transform": {"translate": [0.013, 0.12, 0.007]}, "velocity": [0, -12, 0]}]})";
    return parseScene(json, ".", "fast ball");
}

/// The fraction of the substep at which the ball's lowest node reaches the cloth's plane.
double analyticTimeOfImpact(const Engine& engine, std::size_t* lowestNode) {
    const std::vector<glm::dvec3> x = engine.readPositions();
    const std::uint32_t first = engine.bodyFirstNodes()[1];
    std::size_t lowest = first;
    for (std::size_t i = first; i < x.size(); ++i)
        if (x[i].y < x[lowest].y) lowest = i;
    *lowestNode = lowest;
    return (x[lowest].y - kClothHeight) / (kSpeed * kDt);
}

TEST(ContinuousEngineGl, AFastBallThroughAClothIsSeenOnlyByContinuousDetection) {
    {
        Engine discrete(fastBall("discrete"));
        discrete.step();
        EXPECT_EQ(discrete.lastStep().collision.candidatePairs, 0u) << "the ball passes unseen";
        EXPECT_FALSE(discrete.lastStep().continuous);
        EXPECT_TRUE(discrete.readTimesOfImpact().empty());
        // After the substep the whole ball is below the cloth: it went through.
        const std::vector<glm::dvec3> x = discrete.readPositions();
        const std::uint32_t first = discrete.bodyFirstNodes()[1];
        EXPECT_LT(std::max_element(x.begin() + first, x.end(),
                                   [](const glm::dvec3& a, const glm::dvec3& b) { return a.y < b.y; })
                      ->y,
                  kClothHeight);
    }
    Engine continuous(fastBall("continuous"));
    std::size_t lowest = 0;
    const double expected = analyticTimeOfImpact(continuous, &lowest);
    ASSERT_GT(expected, 0.25);
    ASSERT_LT(expected, 0.35);
    continuous.step();
    const CollisionStats& c = continuous.lastStep().collision;
    EXPECT_TRUE(continuous.lastStep().continuous);
    EXPECT_GT(c.candidatePairs, 0u);
    EXPECT_GT(c.ccdVertexFaceHits, 0u);
    EXPECT_GT(c.ccdEdgeEdgeHits, 0u);
    EXPECT_EQ(c.ccdCapped, 0u);
    // Never later than the true earliest contact; within 2^-10 of a substep below it (the search
    // stops at the first narrow box, GLC_CCD_TOI_TOLERANCE = 2^-12).
    EXPECT_LE(c.ccdEarliestToi, expected * (1.0 + 1e-6)); // 1e-6: the float positions' rounding of y
    EXPECT_GT(c.ccdEarliestToi, expected - 1.0 / 1024.0);
    const std::vector<float> toi = continuous.readTimesOfImpact();
    ASSERT_EQ(toi.size(), continuous.nodeCount());
    EXPECT_LE(toi[lowest], expected * (1.0 + 1e-6));
    // The ball's top nodes and the cloth's far corner touch nothing.
    EXPECT_TRUE(std::isinf(toi[0])) << "a corner of the cloth, 0.3 m from the ball's path";
}

} // namespace
} // namespace glcollide
