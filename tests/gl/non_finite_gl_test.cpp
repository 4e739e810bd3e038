// Non-finite states (docs/reliability.md, "Non-finite states"): NodeUpdate detects a non-finite
// position or velocity on the device and the engine reports the first one (frame, substep,
// object, node) in StepStats::nonFinite instead of continuing silently.

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace glcollide {
namespace {

/// A chain of `nodes` nodes hanging from a pinned first node, springs of stiffness `k` between
/// neighbours, the last node pulled 5 cm down.
Body chain(const std::string& name, int nodes, double k) {
    Body body;
    body.name = name;
    for (int i = 0; i < nodes; ++i) {
        body.positions.push_back({0.0, -0.1 * i - (i + 1 == nodes ? 0.05 : 0.0), 0.0});
        body.velocities.push_back(glm::dvec3(0.0));
        body.masses.push_back(0.5);
        body.pinned.push_back(i == 0 ? 1 : 0);
    }
    for (int i = 0; i + 1 < nodes; ++i)
        body.springs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1), 0.1, k, 0.0,
                                SpringKind::Edge});
    return body;
}

/// Body 0 (2 nodes, k = 200 N/m) is stable at h = 1 ms; body 1 (4 nodes) diverges when its
/// stiffness puts ωh far above 2.
Scene twoChains(double secondStiffness) {
    Scene scene;
    scene.name = "two-chains";
    scene.effects = {Effect::Springs};
    scene.bodies.push_back(chain("stable", 2, 200.0));
    scene.bodies.push_back(chain("stiff", 4, secondStiffness));
    scene.time.dt = 4e-3;
    scene.time.substeps = 4; // h = 1 ms: ωh ≈ 28 for k = 1e8, 0.04 for k = 200
    return scene;
}

bool anyNonFinite(const std::vector<glm::dvec3>& v) {
    return std::any_of(v.begin(), v.end(), [](const glm::dvec3& p) {
        return !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z);
    });
}

void expectDivergenceReported(const EngineOptions& options) {
    Engine engine(twoChains(1e8), options);
    ASSERT_FALSE(engine.warnings().empty());    // explicit substeps below the stability limit
    std::optional<std::uint64_t> firstReadBack; // first frame whose read-back state is non-finite
    for (int frame = 1; frame <= 100 && !firstReadBack; ++frame) {
        engine.step();
        const NonFiniteReport& r = engine.lastStep().nonFinite;
        if (anyNonFinite(engine.readPositions()) || anyNonFinite(engine.readVelocities()))
            firstReadBack = engine.lastStep().frame;
        // Never before the state is non-finite, never after.
        EXPECT_EQ(r.found, firstReadBack.has_value()) << "frame " << frame;
    }
    ASSERT_TRUE(firstReadBack) << "the stiff chain did not diverge";
    const NonFiniteReport first = engine.lastStep().nonFinite;
    ASSERT_TRUE(first.found);
    EXPECT_EQ(first.frame, *firstReadBack);
    EXPECT_GE(first.substep, 0);
    EXPECT_LT(first.substep, engine.substepInfo().substeps);
    EXPECT_EQ(first.object, 1u);
    EXPECT_GE(first.node, 1u); // node 0 is pinned
    EXPECT_LT(first.node, 4u);
    EXPECT_EQ(first.globalNode, engine.bodyFirstNodes()[1] + first.node);
    // Body 0 stayed finite: only the second body diverged.
    const std::vector<glm::dvec3> positions = engine.readPositions();
    EXPECT_TRUE(std::isfinite(positions[0].y) && std::isfinite(positions[1].y));

    // Later frames keep reporting the first occurrence.
    for (int frame = 0; frame < 5; ++frame) {
        engine.step();
        const NonFiniteReport& r = engine.lastStep().nonFinite;
        EXPECT_TRUE(r.found);
        EXPECT_EQ(r.frame, first.frame);
        EXPECT_EQ(r.substep, first.substep);
        EXPECT_EQ(r.object, first.object);
        EXPECT_EQ(r.node, first.node);
    }
}

TEST(NonFiniteGl, DivergingBodyIsReportedInTheFrameItHappens) {
    expectDivergenceReported({});
}

TEST(NonFiniteGl, ReportedWithoutGpuTiming) {
    EngineOptions options;
    options.gpuTiming = false;
    expectDivergenceReported(options);
}

TEST(NonFiniteGl, OverflowingForceIsReportedAtOnce) {
    // A node 3e38 m away (finite in float) stretches its springs so far that k·Δx overflows: the
    // velocities of its neighbours and itself become infinite in the first substep. The lowest of
    // them is node 1 of body 1.
    Scene scene = twoChains(200.0);
    scene.bodies[1].positions[2] = {0.0, -3e38, 0.0};
    Engine engine(scene);
    engine.step();
    const NonFiniteReport& r = engine.lastStep().nonFinite;
    ASSERT_TRUE(r.found);
    EXPECT_EQ(r.frame, 1u);
    EXPECT_EQ(r.substep, 0);
    EXPECT_EQ(r.object, 1u);
    EXPECT_EQ(r.node, 1u);
    EXPECT_EQ(r.globalNode, 3u);
    EXPECT_TRUE(anyNonFinite(engine.readVelocities()));
}

TEST(NonFiniteGl, StableSceneIsNeverReported) {
    Engine engine(twoChains(200.0));
    EXPECT_TRUE(engine.warnings().empty());
    for (int frame = 1; frame <= 200; ++frame) {
        engine.step();
        ASSERT_FALSE(engine.lastStep().nonFinite.found) << "frame " << frame;
    }
    EXPECT_FALSE(anyNonFinite(engine.readPositions()));
    const std::vector<std::string> buffers = engine.allocatedBuffers();
    EXPECT_NE(std::find(buffers.begin(), buffers.end(), "health"), buffers.end());
}

TEST(NonFiniteGl, CheckCanBeTurnedOff) {
    EngineOptions options;
    options.checkFinite = false;
    Engine engine(twoChains(1e8), options);
    for (int frame = 1; frame <= 30; ++frame) engine.step();
    EXPECT_TRUE(anyNonFinite(engine.readPositions())); // it diverged ...
    EXPECT_FALSE(engine.lastStep().nonFinite.found);   // ... unchecked
    const std::vector<std::string> buffers = engine.allocatedBuffers();
    EXPECT_EQ(std::find(buffers.begin(), buffers.end(), "health"), buffers.end());
}

} // namespace
} // namespace glcollide
