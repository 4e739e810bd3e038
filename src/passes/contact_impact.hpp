#pragma once
// ContactImpact — restitution between bodies at any step (decision 0024, "Restitution between
// bodies"; shaders/passes/contact_impact.comp). A pair that meets within a substep is stopped there
// by the implicit solve's contact penalty or by SafeStep's cut, so contacts between bodies were
// inelastic at any step. After SafeStep (and GroundImpact) and before the energy guard, every
// vertex-face and edge-edge contact of the final state whose pair had an impact in the substep —
// its free flight from x0 along the contact's normal, from the start velocities (StartVelocities),
// reaches the thickness faster than the resting speed — leaves with at least e times its impact
// speed, with Coulomb friction bounded by the impact's normal change: rounds of projected Jacobi on
// each pair's accumulated impulse (collision.restitution_iterations), the velocity changes summed
// per node in fixed point (integer atomics). Positions are not changed. The intersection-free
// response only; built when collision.restitution is above 0. Timed as part of SafeStep. CPU twin:
// cpu::contactImpact.

#include "core/contact_params.hpp"
#include "core/dynamics_params.hpp"
#include "gl/program.hpp"
#include "passes/contact_response.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

#include <cstdint>

namespace glcollide::passes {

class ContactImpactPass {
  public:
    static constexpr PassId kId = PassId::SafeStep; ///< timed with the safe step it finishes
    static constexpr const char* kName = "ContactImpact";

    /// `contact`: the response's settings (thickness, friction, fixed-point scale and cap, substep).
    ContactImpactPass(std::uint32_t nodeCount, const ContactImpactParams& params,
                      const ContactParams& contact);
    /// The impacts of the step x0 → x1 (positions → predictedPositions) among the pairs of
    /// `inputs` on the velocities; `start` holds the velocities at the start of the substep.
    void dispatch(const DeviceBuffers& buffers, const ContactInputs& inputs, const gl::Buffer& start) const;

  private:
    std::uint32_t m_nodeCount;
    ContactImpactParams m_params;
    ContactParams m_contact;
    gl::ComputeProgram m_program;
    mutable gl::Buffer
        m_impulses; ///< float per list slot: each pair's accumulated impulse, grown with the lists
};

} // namespace glcollide::passes
