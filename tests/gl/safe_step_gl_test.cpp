// One SafeStep round on the GPU (shaders/passes/safe_step.comp) against its CPU twin
// (cpu::safeStepRound), on random nodes in five objects: some with times of impact, some crossing
// the ground, some still; cut rounds, freeze rounds and the last resort. Decision 0024.

#include "core/gpu_layout.hpp"
#include "cpu/safe_step_twin.hpp"
#include "gl/handles.hpp"
#include "passes/device_buffers.hpp"
#include "passes/safe_step.hpp"

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <bit>
#include <cmath>
#include <random>
#include <string>

namespace glcollide {
namespace {

constexpr std::uint32_t kNoImpact = 0x7F800000u;

struct Case {
    float fraction;
    bool everyNode;
    bool ground;
};

class SafeStepRoundGl : public ::testing::TestWithParam<Case> {};

TEST_P(SafeStepRoundGl, MatchesTheTwin) {
    const Case c = GetParam();
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f), unit(0.0f, 1.0f);
    const std::uint32_t nodes = 300;
    cpu::SafeStepRoundInput in;
    in.objectFirst = {0, 40, 41, 150, 220}; // five objects, one of a single node
    in.fraction = c.fraction;
    in.everyNode = c.everyNode;
    in.ground = c.ground;
    in.groundHeight = 0.0f;
    in.h = 1.0f / 60.0f;
    std::vector<glm::vec3> end(nodes), velocity(nodes);
    for (std::uint32_t i = 0; i < nodes; ++i) {
        const glm::vec3 x0(coordinate(rng), 0.05f + unit(rng), coordinate(rng));
        in.start.push_back(x0);
        in.inverseMass.push_back(i % 37 == 0 ? 0.0f : 2.0f);
        // A fifth stay still, a fifth may cross the ground, the rest move a little.
        const float kind = unit(rng);
        glm::vec3 x1 = x0 + 0.1f * glm::vec3(coordinate(rng), coordinate(rng), coordinate(rng));
        if (kind < 0.2f)
            x1 = x0;
        else if (kind < 0.4f)
            x1.y = -0.3f * unit(rng);
        end[i] = x1;
        velocity[i] = (x1 - x0) / in.h;
        // Times of impact on a quarter of the nodes, none on object 3 (150 ... 219).
        const bool impact = (i < 150 || i >= 220) && unit(rng) < 0.25f;
        in.nodeToi.push_back(impact ? std::bit_cast<std::uint32_t>(unit(rng)) : kNoImpact);
    }

    passes::DeviceBuffers b;
    b.nodeCount = nodes;
    std::vector<glm::vec4> x0(nodes), x1(nodes), v(nodes);
    for (std::uint32_t i = 0; i < nodes; ++i) {
        x0[i] = glm::vec4(in.start[i], in.inverseMass[i]);
        x1[i] = glm::vec4(end[i], in.inverseMass[i]);
        v[i] = glm::vec4(velocity[i], 0.0f);
    }
    b.positions = gl::makeBuffer("positions", x0);
    b.predictedPositions = gl::makeBuffer("predictedPositions", x1);
    b.velocities = gl::makeBuffer("velocities", v);
    std::vector<gpu::GpuObject> objects;
    for (std::size_t o = 0; o < in.objectFirst.size(); ++o) {
        const std::uint32_t last = o + 1 < in.objectFirst.size() ? in.objectFirst[o + 1] : nodes;
        objects.push_back({in.objectFirst[o], last - in.objectFirst[o], 0, 0, 0, 0, 0, 0});
    }
    const gl::Buffer objectBuffer = gl::makeBuffer("objects", objects);
    const gl::Buffer toiBuffer = gl::makeBuffer("nodeToi", in.nodeToi);
    const gl::Buffer counters = gl::makeBuffer(
        "collisionCounters", std::vector<gpu::GpuCollisionCounters>{gpu::GpuCollisionCounters{}});

    passes::SafeStepPass pass(passes::SafeStepSettings{}, static_cast<std::uint32_t>(objects.size()),
                              c.ground, in.groundHeight);
    pass.setSubstep(in.h);
    pass.round(b, passes::SafeStepInputs{&toiBuffer, &objectBuffer, &counters}, c.fraction, c.everyNode);

    const cpu::SafeStepRoundResult twin = cpu::safeStepRound(in, end, velocity);
    std::vector<glm::vec4> gpuEnd(nodes), gpuVelocity(nodes);
    b.predictedPositions.download(0, nodes * sizeof(glm::vec4), gpuEnd.data());
    b.velocities.download(0, nodes * sizeof(glm::vec4), gpuVelocity.data());
    gpu::GpuCollisionCounters stats{};
    counters.download(0, sizeof stats, &stats);
    EXPECT_EQ(stats.stats[GLC_STAT_SAFE_STEP_CUTS], twin.cuts);
    EXPECT_EQ(stats.stats[GLC_STAT_SAFE_STEP_GROUND], twin.groundCrossings);
    if (!c.everyNode) {
        EXPECT_GT(twin.cuts, 0u) << "the case must cut something";
    }
    // Tolerance: the shader may contract x0 + s·(x1 − x0) and compute the ground's time with
    // GLSL's division (2.5 ulp), which moves s by a few ulps: 2^-18 of the step (≤ 1.2 m here)
    // for positions, over h for velocities.
    const float positionTolerance = std::ldexp(1.0f, -18) * 1.2f;
    for (std::uint32_t i = 0; i < nodes; ++i) {
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(gpuEnd[i][k], end[i][k], positionTolerance) << "node " << i;
            EXPECT_NEAR(gpuVelocity[i][k], velocity[i][k], 2.0f * positionTolerance / in.h) << "node " << i;
        }
        EXPECT_EQ(gpuEnd[i].w, in.inverseMass[i]) << "x1 keeps the inverse mass";
    }
    // The cut is per object: in an object with a time of impact every moving node advanced by the
    // same fraction of its step (the twin's own check of the rule, independent of the GPU).
    if (!c.everyNode && c.fraction > 0.0f) {
        for (std::uint32_t i = 0; i < in.objectFirst[1]; ++i) {
            const glm::vec3 full = glm::vec3(x1[i]) - in.start[i];
            if (glm::length(full) == 0.0f) continue;
            const float moved = glm::length(end[i] - in.start[i]) / glm::length(full);
            EXPECT_LE(moved, c.fraction * (1.0f + 1e-5f)) << "node " << i;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Rounds, SafeStepRoundGl,
                         ::testing::Values(Case{0.8f, false, false}, Case{0.8f, false, true},
                                           Case{0.0f, false, true}, Case{0.0f, true, false}));

} // namespace
} // namespace glcollide
