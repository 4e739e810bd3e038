#pragma once
// ContactResponse: penalty forces for the broad phase's candidate face pairs
// (shaders/passes/contact_response.comp, docs/collisions.md), summed per node in fixed point
// into DeviceBuffers::contactForces, which NodeUpdate adds and clears.

#include "core/contact_params.hpp"
#include "gl/program.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

namespace glcollide::passes {

/// The collision buffers the response reads (owned by the collision detection).
struct ContactInputs {
    const gl::Buffer* candidates = nullptr; ///< uvec2 face pairs
    const gl::Buffer* faceInfo = nullptr;   ///< GpuFaceInfo per face
    const gl::Buffer* objects = nullptr;    ///< GpuObject per object
    const gl::Buffer* counters = nullptr;   ///< GpuCollisionCounters (contactCount is added to)
    std::uint32_t candidateCount = 0;
};

class ContactResponsePass {
  public:
    static constexpr PassId kId = PassId::ContactResponse;
    static constexpr const char* kName = passName(kId);
    ContactResponsePass();
    void dispatch(const DeviceBuffers& buffers, const ContactInputs& inputs,
                  const ContactParams& params) const;

  private:
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
