// Differential tests of NodeForce, SpringUpdate and NodeUpdate against their double-precision CPU
// twins (src/cpu/dynamics_twin.cpp) on seeded random inputs at sizes 1, L-1, L+1 and a large
// prime, L = GLC_WORKGROUP_SIZE (docs/design/decisions/0010-cpu-twins-and-exact-oracles.md). The GPU gets
// float inputs; the twin gets the same float values widened to double, so only the GPU's float arithmetic is
// being measured. Tolerances are float rounding bounds: u = 2^-24 (unit roundoff of float) times the sum of
// the magnitudes each result is built from, times a small constant for the operation count.

#include "core/gpu_layout.hpp"
#include "cpu/dynamics_twin.hpp"
#include "passes/dynamics_passes.hpp"
#include "support/random_dynamics_model.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <random>

namespace glcollide {
namespace {

using namespace testing_support;

const std::uint32_t kSizes[] = {1, GLC_WORKGROUP_SIZE - 1, GLC_WORKGROUP_SIZE + 1, 10007};

class DynamicsGl : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(DynamicsGl, NodeForceMatchesTwin) {
    const std::uint32_t n = GetParam();
    for (int variant = 0; variant < 8; ++variant) {
        RandomModel m = makeRandomModel(n, 1000 + n);
        NodeForceParams p;
        p.gravity = variant & 1;
        p.damping = variant & 2;
        p.wind = variant & 4;
        p.gravityAcceleration = {0.3, -9.81, 0.7};
        p.dampingCoefficient = 0.37;
        p.windVelocity = {4.0, -1.0, 2.5};
        p.windDrag = 1.3;
        passes::DeviceBuffers b = uploadModel(m);
        passes::NodeForcePass(p).dispatch(b, p);
        const auto gpu = download(b.forces, n);
        cpu::nodeForce(p, m.faceIndices, m.nodeFaces, m.state);
        for (std::uint32_t i = 0; i < n; ++i) {
            const double w = m.state.inverseMasses[i];
            double scale = 0.0; // magnitudes the force is summed from
            if (w > 0.0) {
                const double mass = 1.0 / w;
                scale += mass * glm::length(p.gravityAcceleration) +
                         p.dampingCoefficient * mass * glm::length(m.state.velocities[i]);
                if (p.wind)
                    for (std::uint32_t k = m.nodeFaces.offsets[i]; k < m.nodeFaces.offsets[i + 1]; ++k) {
                        const std::uint32_t f = m.nodeFaces.items[k];
                        const auto& x = m.state.positions;
                        const glm::dvec3 e1 = x[m.faceIndices[3 * f + 1]] - x[m.faceIndices[3 * f]];
                        const glm::dvec3 e2 = x[m.faceIndices[3 * f + 2]] - x[m.faceIndices[3 * f]];
                        // |e1||e2| bounds twice the area; the 10x covers 1/sin(angle) of the normal.
                        scale += p.windDrag * glm::length(e1) * glm::length(e2) * 10.0 *
                                 (glm::length(p.windVelocity) + 3.0) / 6.0;
                    }
            }
            const double tolerance = 32.0 * kUnitRoundoff * scale;
            const glm::dvec3 diff = glm::dvec3(gpu[i]) - m.state.forces[i];
            ASSERT_LE(glm::length(diff), tolerance) << "node " << i << " variant " << variant;
            ASSERT_EQ(gpu[i].w, 0.0);
        }
    }
}

TEST_P(DynamicsGl, SpringUpdateMatchesTwin) {
    const std::uint32_t n = GetParam();
    for (bool external : {false, true}) { // with gravity and air damping added in the same dispatch
        RandomModel m = makeRandomModel(n, 2000 + n);
        passes::DeviceBuffers b = uploadModel(m);
        SpringUpdateParams p;
        p.external.gravity = p.external.damping = external;
        p.external.gravityAcceleration = {0.3, -9.81, 0.7};
        p.external.dampingCoefficient = 0.37;
        passes::SpringUpdatePass(p).dispatch(b, p);
        const auto gpu = download(b.forces, n);
        cpu::nodeForce(p.external, m.faceIndices, m.nodeFaces, m.state);
        cpu::springUpdate(m.springs, m.nodeSprings, m.state);
        for (std::uint32_t i = 0; i < n; ++i) {
            const double w = m.state.inverseMasses[i];
            double scale = 0.0; // magnitudes the force is summed from
            if (external && w > 0.0)
                scale += glm::length(p.external.gravityAcceleration) / w +
                         p.external.dampingCoefficient / w * glm::length(m.state.velocities[i]);
            for (std::uint32_t k = m.nodeSprings.offsets[i]; k < m.nodeSprings.offsets[i + 1]; ++k) {
                const model::FlatSpring& s = m.springs[m.nodeSprings.items[k]];
                const glm::dvec3 xa = m.state.positions[s.a], xb = m.state.positions[s.b];
                const double length = glm::length(xb - xa);
                const double coords = glm::length(xa) + glm::length(xb);
                const double dv = glm::length(m.state.velocities[s.b] - m.state.velocities[s.a]);
                const double magnitude = s.stiffness * std::abs(length - s.restLength) + s.damping * dv;
                // length carries an absolute error ~u·|coords| (from xb - xa); the direction a
                // relative error ~u·coords/length, which scales the whole spring force.
                scale += s.stiffness * (length + s.restLength + coords) + s.damping * dv +
                         magnitude * (1.0 + coords / length);
            }
            const double tolerance = 16.0 * kUnitRoundoff * scale;
            ASSERT_LE(glm::length(glm::dvec3(gpu[i]) - m.state.forces[i]), tolerance)
                << "node " << i << (external ? " with external force" : "");
        }
    }
}

TEST_P(DynamicsGl, NodeUpdateMatchesTwin) {
    const std::uint32_t n = GetParam();
    for (int variant = 0; variant < 4; ++variant) {
        RandomModel m = makeRandomModel(n, 3000 + n);
        NodeUpdateParams p;
        p.h = 1e-2;
        p.forces = variant & 1;
        p.ground = variant & 2;
        p.groundHeight = 0.1;
        p.restitution = 0.3;
        p.friction = 0.4;
        // Keep every node's new height at least 1e-4 away from the plane: nearer, float and
        // double may take different sides of the ground test, which is not an arithmetic error.
        for (std::size_t i = 0; i < n; ++i) {
            const glm::dvec3 v =
                p.forces ? m.state.velocities[i] + p.h * m.state.inverseMasses[i] * m.state.forces[i]
                         : m.state.velocities[i];
            const double y = m.state.positions[i].y + p.h * v.y;
            if (std::abs(y - p.groundHeight) < 1e-4)
                m.state.positions[i].y = toFloat(m.state.positions[i].y + 3e-4);
        }
        passes::DeviceBuffers b = uploadModel(m);
        passes::NodeUpdatePass(p).dispatch(b, p);
        const auto gpuX = download(b.positions, n);
        const auto gpuV = download(b.velocities, n);
        const cpu::NodeState before = m.state;
        cpu::nodeUpdate(p, m.state);
        for (std::uint32_t i = 0; i < n; ++i) {
            const double w = before.inverseMasses[i];
            const double vScale = glm::length(before.velocities[i]) + p.h * w * glm::length(before.forces[i]);
            // v: two roundings per term; x adds h·v to |x|; ground/friction rescale v (<= 4 ops).
            const double vTolerance = 16.0 * kUnitRoundoff * vScale * (1.0 + p.friction * 2.0);
            const double xTolerance = 8.0 * kUnitRoundoff * (glm::length(before.positions[i]) + p.h * vScale);
            ASSERT_LE(glm::length(glm::dvec3(gpuV[i]) - m.state.velocities[i]), vTolerance) << "node " << i;
            ASSERT_LE(glm::length(glm::dvec3(gpuX[i]) - m.state.positions[i]), xTolerance) << "node " << i;
            ASSERT_EQ(gpuX[i].w, static_cast<float>(w)) << "inverse mass must pass through unchanged";
            if (w == 0.0) {
                ASSERT_EQ(glm::dvec3(gpuX[i]), before.positions[i]) << "pinned node moved";
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Sizes, DynamicsGl, ::testing::ValuesIn(kSizes));

} // namespace
} // namespace glcollide
