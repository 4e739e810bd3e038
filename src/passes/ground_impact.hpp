#pragma once
// GroundImpact — the ground's restitution at any step (decision 0024, "Restitution at any step";
// shaders/passes/ground_impact.comp). A node that comes down onto the ground within a substep is
// stopped there by the implicit solve's ground penalty or by SafeStep's cut, and the ground's
// velocity response, which acts on nodes already in its band at the start of a substep, never
// sees it moving: at one substep per frame a ground of restitution 0.8 bounced nothing. This pass
// runs after SafeStep and before the energy guard: every node that started above the band and ends
// in it gets the ground's velocity response (common/ground_response.glsl) at its impact speed, its
// free fall from x0 to the band from its start velocity (StartVelocities): it leaves with e
// times that speed, and Coulomb friction is bounded by (1 + e) times it. The intersection-free
// response only; built when the ground has a restitution above 0. Timed as part of SafeStep. CPU
// twin: cpu::groundImpact.

#include "core/dynamics_params.hpp"
#include "gl/program.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

#include <cstdint>

namespace glcollide::passes {

class GroundImpactPass {
  public:
    static constexpr PassId kId = PassId::SafeStep; ///< timed with the safe step it finishes
    static constexpr const char* kName = "GroundImpact";

    GroundImpactPass(std::uint32_t nodeCount, const GroundImpactParams& params);
    /// The impacts of the step x0 → x1 (positions → predictedPositions) on the velocities; `start`
    /// holds the velocities at the start of the substep (StartVelocities::buffer).
    void dispatch(const DeviceBuffers& buffers, const gl::Buffer& start) const;

  private:
    std::uint32_t m_nodeCount;
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
