#pragma once
// The two device buffers a collision detection reads (positions as vec4 with w = 1, faces), made
// from float positions, for the GL tests that drive passes::CollisionDetection directly.

#include "gl/handles.hpp"
#include "passes/device_buffers.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::test {

inline std::vector<glm::vec4> positionsWithUnitW(const std::vector<glm::vec3>& positions) {
    std::vector<glm::vec4> p;
    p.reserve(positions.size());
    for (const glm::vec3& x : positions) p.emplace_back(x, 1.0f);
    return p;
}

inline passes::DeviceBuffers collisionBuffers(const std::vector<glm::vec3>& positions,
                                              const std::vector<std::uint32_t>& faceIndices) {
    passes::DeviceBuffers b;
    b.nodeCount = static_cast<std::uint32_t>(positions.size());
    b.faceCount = static_cast<std::uint32_t>(faceIndices.size() / 3);
    b.positions = gl::makeBuffer("positions", positionsWithUnitW(positions));
    b.faces = gl::makeBuffer("faces", faceIndices);
    return b;
}

} // namespace glcollide::test
