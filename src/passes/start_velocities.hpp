#pragma once
// Every node's velocity at the start of the substep (GLC_BIND_START_VELOCITIES), for the passes
// that judge an impact after the step: GroundImpact and ContactImpact (decision 0024, "Restitution
// at any step"). The substep's stages change the velocities (the filters before the solve, the
// solve, the cuts); the impact speed is computed from where the substep began.

#include "gl/handles.hpp"
#include "passes/device_buffers.hpp"

#include <cstdint>

namespace glcollide::passes {

class StartVelocities {
  public:
    explicit StartVelocities(std::uint32_t nodeCount);
    /// Copies the velocities; call before the substep's first stage.
    void record(const DeviceBuffers& buffers) const;
    [[nodiscard]] const gl::Buffer& buffer() const { return m_velocities; }

  private:
    std::uint32_t m_nodeCount;
    gl::Buffer m_velocities; ///< vec4 per node
};

} // namespace glcollide::passes
