// Engine::setPull (issue 25: the viewer's mouse perturbation goes through the engine's API): the
// pull's own pass against the symplectic Euler step written out by hand, on a cloth with no effect
// at all, so the pulled node's only force is the pull and every other node keeps its state.

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace glcollide {
namespace {

constexpr double kDt = 0.01; // s, one substep per frame (below)

Scene freeCloth(const std::string& extraObject = "") {
    const std::string json = R"({"format_version": 1, "name": "pull", "effects": [],
      "time": {"dt": 0.01, "frames": 1, "substeps": 1},
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [4, 4]},
                   "mass": 0.5)" +
                             extraObject + "}]}";
    return parseScene(json, ".", "pull test");
}

// Float rounding of v += h·w·(k·(t − x) − c·v) on the GPU: u = 2^-24 per operation. The target is
// rounded to float (|t|·u), t − x cancels, so its error is bounded by (|t| + |x|)·u per rounding,
// and about 6 more roundings follow, each relative to the result: 8·u·(h·w·k·(|t| + |x|) + |Δv|)
// bounds all of them with room to spare.
double tolerance(double hwk, const glm::dvec3& t, const glm::dvec3& x, double dv) {
    const double u = std::ldexp(1.0, -24);
    return 8.0 * u * (hwk * (glm::length(t) + glm::length(x)) + std::abs(dv));
}

TEST(NodePullGl, OneSubstepChangesThePulledNodesVelocityByHKDisplacementOverMass) {
    const Scene scene = freeCloth();
    Engine engine(scene, {false});
    ASSERT_EQ(engine.substepInfo().substeps, 1);
    ASSERT_EQ(engine.substepInfo().substepLength, kDt);
    const std::uint32_t node = 7;
    const double mass = scene.bodies[0].masses[node];
    const std::vector<glm::dvec3> x0 = engine.readPositions();
    const NodePull pull{node, x0[node] + glm::dvec3(0.3, -0.2, 0.1), 2.5, 0.0};
    engine.setPull(pull);
    engine.step();
    const std::vector<glm::dvec3> v1 = engine.readVelocities(), x1 = engine.readPositions();
    const double hwk = kDt * pull.stiffness / mass;
    const glm::dvec3 dv = hwk * (pull.target - x0[node]); // from rest: the whole velocity
    for (int c = 0; c < 3; ++c) {
        const double tol = tolerance(hwk, pull.target, x0[node], dv[c]);
        EXPECT_NEAR(v1[node][c], dv[c], tol) << "component " << c;
        // Symplectic Euler moves x with the new velocity; one more rounding of x + h·v.
        EXPECT_NEAR(x1[node][c], x0[node][c] + kDt * v1[node][c],
                    4.0 * std::ldexp(1.0, -24) * (std::abs(x0[node][c]) + kDt * std::abs(v1[node][c])));
    }
    for (std::uint32_t i = 0; i < engine.nodeCount(); ++i) {
        if (i == node) continue;
        EXPECT_EQ(v1[i], glm::dvec3(0.0)) << "node " << i << " has no force";
        EXPECT_EQ(x1[i], x0[i]) << "node " << i;
    }
}

// Under the intersection-free response the energy guard checks each substep against its start; the
// pull does work on the scene, so its kick is part of the start, not a rise to take back out: with
// the guard on, the frames are the frames with it off (bit for bit) and it never acts.
TEST(NodePullGl, TheEnergyGuardLeavesThePullsWorkAlone) {
    const auto run = [](bool guard) {
        const std::string json =
            R"({"format_version": 1, "name": "pull guard", "effects": ["springs", "self_collisions"],
          "time": {"dt": 0.01, "frames": 1, "substeps": 2, "integrator": "implicit_euler"},
          "collision": {"broad_phase": "bvh", "thickness": 0.01, "response": "intersection_free",
                        "energy_guard": )" +
            std::string(guard ? "true" : "false") + R"(},
          "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [4, 4]},
                       "mass": 0.5, "springs": {"stiffness": 50}}]})";
        Engine engine(parseScene(json, ".", "pull guard"));
        const std::vector<glm::dvec3> x0 = engine.readPositions();
        engine.setPull(NodePull{7, x0[7] + glm::dvec3(0.0, 0.3, 0.0), 5.0, 0.0});
        std::uint32_t acted = 0;
        for (int frame = 0; frame < 10; ++frame) {
            engine.step();
            acted += engine.lastStep().collision.energyGuardSubsteps;
        }
        EXPECT_EQ(acted, 0u) << "guard " << guard;
        const std::vector<glm::dvec3> x = engine.readPositions();
        EXPECT_GT(x[7].y - x0[7].y, 0.01) << "the pulled node rises";
        return x;
    };
    EXPECT_EQ(run(true), run(false));
}

TEST(NodePullGl, DampingActsAgainstTheNodesVelocityAndRemovingThePullStopsIt) {
    const Scene scene = freeCloth();
    Engine engine(scene, {false});
    const std::uint32_t node = 3;
    const double mass = scene.bodies[0].masses[node];
    const glm::dvec3 target = engine.readPositions()[node] + glm::dvec3(0.0, 0.5, 0.0);
    engine.setPull(NodePull{node, target, 4.0, 0.3});
    engine.step();
    const glm::dvec3 va = engine.readVelocities()[node], xa = engine.readPositions()[node];
    engine.step();
    const glm::dvec3 vb = engine.readVelocities()[node];
    const double h = kDt, w = 1.0 / mass;
    const glm::dvec3 expected = va + h * w * (4.0 * (target - xa) - 0.3 * va);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(vb[c], expected[c],
                    tolerance(h * w * 4.0, target, xa, expected[c] - va[c]) +
                        8.0 * std::ldexp(1.0, -24) * std::abs(va[c]))
            << "component " << c;
    // No pull: no force on a cloth without effects, so the velocity stays as it is.
    engine.setPull(std::nullopt);
    EXPECT_FALSE(engine.pull().has_value());
    engine.step();
    EXPECT_EQ(engine.readVelocities()[node], vb);
}

TEST(NodePullGl, RunsOnlyWhileSetAndAddsNoPassToThePipeline) {
    Engine engine(freeCloth(), {false});
    const auto pipeline = engine.pipeline();
    engine.step();
    const double without = engine.lastStep().dispatchesPerSubstep;
    engine.setPull(NodePull{0, glm::dvec3(0.0, 1.0, 0.0), 1.0, 0.0});
    engine.step();
    EXPECT_EQ(engine.lastStep().dispatchesPerSubstep, without + 1.0); // the pull's one dispatch
    engine.setPull(std::nullopt);
    engine.step();
    EXPECT_EQ(engine.lastStep().dispatchesPerSubstep, without);
    EXPECT_EQ(engine.pipeline(), pipeline);
}

TEST(NodePullGl, APinnedNodeIsNotMoved) {
    const Scene scene = freeCloth(R"(, "pinned": [0])");
    Engine engine(scene, {false});
    const glm::dvec3 x0 = engine.readPositions()[0];
    engine.setPull(NodePull{0, x0 + glm::dvec3(1.0), 100.0, 0.0});
    engine.step();
    EXPECT_EQ(engine.readPositions()[0], x0);
    EXPECT_EQ(engine.readVelocities()[0], glm::dvec3(0.0));
}

TEST(NodePullGl, BadPullsAreErrors) {
    Engine engine(freeCloth(), {false});
    const std::uint32_t n = engine.nodeCount();
    EXPECT_THROW(engine.setPull(NodePull{n, glm::dvec3(0.0), 1.0, 0.0}), Error);
    EXPECT_THROW(engine.setPull(NodePull{0, glm::dvec3(NAN, 0.0, 0.0), 1.0, 0.0}), Error);
    EXPECT_THROW(engine.setPull(NodePull{0, glm::dvec3(0.0), -1.0, 0.0}), Error);
    EXPECT_THROW(engine.setPull(NodePull{0, glm::dvec3(0.0), 1.0, INFINITY}), Error);
    EXPECT_FALSE(engine.pull().has_value()); // a rejected pull leaves none set
}

} // namespace
} // namespace glcollide
