#include "passes/start_velocities.hpp"

#include <epoxy/gl.h>

#include <vector>

namespace glcollide::passes {

StartVelocities::StartVelocities(std::uint32_t nodeCount)
    : m_nodeCount(nodeCount),
      m_velocities(gl::makeBuffer("startVelocities", std::vector<float>(4 * std::size_t{nodeCount}, 0.0f))) {}

void StartVelocities::record(const DeviceBuffers& b) const {
    if (m_nodeCount == 0) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after the last substep's shader writes of v
    gl::copyBufferData(b.velocities, m_velocities, m_velocities.bytes());
}

} // namespace glcollide::passes
