// Differential tests of NodeForce, SpringUpdate and NodeUpdate against their double-precision CPU
// twins (src/cpu/dynamics_twin.cpp) on seeded random inputs at sizes 1, L-1, L+1 and a large
// prime, L = GLC_WORKGROUP_SIZE (docs/design/decisions/0010-cpu-twins-and-exact-oracles.md). The GPU gets
// float inputs; the twin gets the same float values widened to double, so only the GPU's float arithmetic is
// being measured. Tolerances are float rounding bounds: u = 2^-24 (unit roundoff of float) times the sum of
// the magnitudes each result is built from, times a small constant for the operation count.

#include "core/gpu_layout.hpp"
#include "cpu/dynamics_twin.hpp"
#include "passes/dynamics_passes.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <cmath>
#include <random>

namespace glcollide {
namespace {

constexpr double kUnitRoundoff = 1.0 / 16777216.0; // 2^-24

struct RandomModel {
    cpu::NodeState state;
    std::vector<model::FlatSpring> springs;
    model::Csr nodeSprings;
    std::vector<std::uint32_t> faceIndices;
    model::Csr nodeFaces;
};

double toFloat(double v) {
    return static_cast<double>(static_cast<float>(v));
}

RandomModel makeRandomModel(std::uint32_t nodes, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> positive(0.5, 2.0), zeroOne(0.0, 1.0);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f); // float: exactly what the GPU gets
    RandomModel m;
    auto randomVector = [&](float scale) {
        const float x = unit(rng) * scale, y = unit(rng) * scale, z = unit(rng) * scale;
        return glm::dvec3(x, y, z);
    };
    for (std::uint32_t i = 0; i < nodes; ++i) {
        m.state.positions.push_back(randomVector(1.0f));
        m.state.velocities.push_back(randomVector(1.0f));
        m.state.forces.push_back(randomVector(10.0f));
        // About 5 % pinned: the passes must leave them alone.
        m.state.inverseMasses.push_back(zeroOne(rng) < 0.05 ? 0.0 : toFloat(positive(rng)));
    }
    if (nodes >= 2) {
        std::uniform_int_distribution<std::uint32_t> pick(0, nodes - 1);
        for (std::uint32_t s = 0; s < 3 * nodes; ++s) {
            std::uint32_t a = pick(rng), b = pick(rng);
            while (b == a) b = pick(rng);
            const double length = glm::length(m.state.positions[b] - m.state.positions[a]);
            m.springs.push_back({a, b, toFloat(length * (0.8 + 0.4 * zeroOne(rng))),
                                 toFloat(10.0 + 990.0 * zeroOne(rng)), toFloat(zeroOne(rng))});
        }
    }
    if (nodes >= 3) {
        std::uniform_int_distribution<std::uint32_t> pick(0, nodes - 1);
        while (m.faceIndices.size() < 6 * static_cast<std::size_t>(nodes)) {
            const std::uint32_t a = pick(rng), b = pick(rng), c = pick(rng);
            if (a == b || b == c || a == c) continue;
            const glm::dvec3 e1 = m.state.positions[b] - m.state.positions[a];
            const glm::dvec3 e2 = m.state.positions[c] - m.state.positions[a];
            // Keep faces well shaped (sin of the corner angle >= 0.1) so the normal is
            // well-conditioned and the float bound below holds.
            if (glm::length(glm::cross(e1, e2)) < 0.1 * glm::length(e1) * glm::length(e2)) continue;
            m.faceIndices.insert(m.faceIndices.end(), {a, b, c});
        }
    }
    m.nodeSprings = model::buildSpringAdjacency(nodes, m.springs);
    m.nodeFaces = model::buildAdjacency(nodes, m.faceIndices, 3);
    return m;
}

std::vector<glm::vec4> pack(const std::vector<glm::dvec3>& v, const std::vector<double>* w = nullptr) {
    std::vector<glm::vec4> out;
    for (std::size_t i = 0; i < v.size(); ++i)
        out.emplace_back(glm::vec3(v[i]), w ? static_cast<float>((*w)[i]) : 0.0f);
    return out;
}

template <typename T> gl::Buffer upload(const char* label, const std::vector<T>& data) {
    return gl::Buffer(label, data.size() * sizeof(T), data.empty() ? nullptr : data.data());
}

passes::DeviceBuffers uploadModel(const RandomModel& m) {
    passes::DeviceBuffers b;
    b.nodeCount = static_cast<std::uint32_t>(m.state.positions.size());
    b.faceCount = static_cast<std::uint32_t>(m.faceIndices.size() / 3);
    b.springCount = static_cast<std::uint32_t>(m.springs.size());
    b.positions = upload("positions", pack(m.state.positions, &m.state.inverseMasses));
    b.velocities = upload("velocities", pack(m.state.velocities));
    b.forces = upload("forces", pack(m.state.forces));
    b.faces = upload("faces", m.faceIndices);
    std::vector<gpu::GpuSpring> springs;
    for (const auto& s : m.springs)
        springs.push_back({s.a, s.b, static_cast<float>(s.restLength), static_cast<float>(s.stiffness),
                           static_cast<float>(s.damping), 0u, 0u, 0u});
    b.springs = upload("springs", springs);
    b.nodeSpringOffsets = upload("nodeSpringOffsets", m.nodeSprings.offsets);
    b.nodeSpringList = upload("nodeSpringList", m.nodeSprings.items);
    b.nodeFaceOffsets = upload("nodeFaceOffsets", m.nodeFaces.offsets);
    b.nodeFaceList = upload("nodeFaceList", m.nodeFaces.items);
    return b;
}

std::vector<glm::dvec4> download(const gl::Buffer& buffer, std::uint32_t count) {
    std::vector<glm::vec4> raw(count);
    buffer.download(0, count * sizeof(glm::vec4), raw.data());
    return {raw.begin(), raw.end()};
}

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
    for (bool accumulate : {false, true}) {
        RandomModel m = makeRandomModel(n, 2000 + n);
        const std::vector<glm::dvec3> initialForces = m.state.forces;
        passes::DeviceBuffers b = uploadModel(m);
        SpringUpdateParams p{accumulate};
        passes::SpringUpdatePass(p).dispatch(b);
        const auto gpu = download(b.forces, n);
        cpu::springUpdate(p, m.springs, m.nodeSprings, m.state);
        for (std::uint32_t i = 0; i < n; ++i) {
            double scale = accumulate ? glm::length(initialForces[i]) : 0.0;
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
                << "node " << i << (accumulate ? " accumulate" : " overwrite");
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
