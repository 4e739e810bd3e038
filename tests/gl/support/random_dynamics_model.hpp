#pragma once
// Seeded random node/spring/face models for the dynamics GL tests (dynamics_gl_test.cpp,
// implicit_gl_test.cpp), their upload to DeviceBuffers and read-back. The GPU gets float inputs;
// the twin gets the same float values widened to double.

#include "core/gpu_layout.hpp"
#include "cpu/dynamics_twin.hpp"
#include "gl/handles.hpp"
#include "model/flat_model.hpp"
#include "passes/device_buffers.hpp"
#include "passes/row_layout.hpp"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <random>
#include <vector>

namespace glcollide::testing_support {

inline constexpr double kUnitRoundoff = 1.0 / 16777216.0; // 2^-24

struct RandomModel {
    cpu::NodeState state;
    std::vector<model::FlatSpring> springs;
    model::Csr nodeSprings;
    std::vector<std::uint32_t> faceIndices;
    model::Csr nodeFaces;
};

inline double toFloat(double v) {
    return static_cast<double>(static_cast<float>(v));
}

inline RandomModel makeRandomModel(std::uint32_t nodes, std::uint32_t seed) {
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

inline std::vector<glm::vec4> pack(const std::vector<glm::dvec3>& v, const std::vector<double>* w = nullptr) {
    std::vector<glm::vec4> out;
    for (std::size_t i = 0; i < v.size(); ++i)
        out.emplace_back(glm::vec3(v[i]), w ? static_cast<float>((*w)[i]) : 0.0f);
    return out;
}

template <typename T> gl::Buffer upload(const char* label, const std::vector<T>& data) {
    return gl::Buffer(label, data.size() * sizeof(T), data.empty() ? nullptr : data.data());
}

inline passes::DeviceBuffers uploadModel(const RandomModel& m) {
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
    b.heavyNodes = upload("heavyNodes", passes::heavyRowNodes(m.nodeSprings.offsets));
    b.nodeFaceOffsets = upload("nodeFaceOffsets", m.nodeFaces.offsets);
    b.nodeFaceList = upload("nodeFaceList", m.nodeFaces.items);
    return b;
}

inline std::vector<glm::dvec4> download(const gl::Buffer& buffer, std::uint32_t count) {
    std::vector<glm::vec4> raw(count);
    buffer.download(0, count * sizeof(glm::vec4), raw.data());
    return {raw.begin(), raw.end()};
}

} // namespace glcollide::testing_support
