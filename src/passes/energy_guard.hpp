#pragma once
// EnergyGuard — contact adds no energy (decision 0024, "Energy guard"). Between SafeStep's cut
// and its commit, the candidate state's total energy (kinetic, gravity, springs, the ground's and
// the contacts' penalty energy) is summed on the GPU in a fixed order and compared with the start
// of the substep's; a rise beyond the sum's float resolution is taken out of the kinetic energy
// by one velocity scale for the whole scene, or, when the rise is potential energy the kinetic
// cannot pay, by pulling the whole step back towards x0 (energy_guard.comp). Every time it acts
// is counted (CollisionStats::energyGuard*): it is a fail-safe for what the implicit contacts
// leave. It assumes a closed scene (no wind; pinned nodes at rest): the scene refuses wind.

#include "passes/collision_detection.hpp"
#include "passes/contact_response.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

#include <glm/vec3.hpp>

#include <cstdint>

namespace glcollide::passes {

/// What the energy sums: the scene's potentials and the contacts' penalty.
struct EnergyGuardParams {
    glm::dvec3 gravity{0.0};      ///< m/s²; 0 without the gravity effect
    bool springs = false;         ///< the springs effect: their elastic energy counts
    bool contacts = false;        ///< a collision effect: the feature pairs' ½·k·depth² counts
    double thickness = 0.0;       ///< m: the contacts' thickness
    double stiffness = 0.0;       ///< N/m: the contacts' penalty stiffness
    double groundStiffness = 0.0; ///< N/m per node: the implicit solve's ground penalty (0: none)
    double groundLevel = 0.0;     ///< m: the ground's height plus its band
};

/// The sums' shared inputs (common/energy_sum.glsl), for EnergyGuard and NewtonLineSearch alike:
/// sets the potentials' uniforms of `program` (u_springCount: `springCount`, 0 without springs).
void setPotentialUniforms(const gl::ComputeProgram& program, const EnergyGuardParams& params,
                          std::uint32_t springCount);
/// Binds the springs and, with contacts, the faces, face info, objects and feature-pair lists
/// (throws naming `pass` when they are missing); returns the terms summed over (nodes, springs and
/// the lists' capacities), the count EnergyGuardPass::resolutionFactor takes.
std::uint64_t bindPotentialInputs(const DeviceBuffers& buffers, const ContactInputs* contacts,
                                  const EnergyGuardParams& params, std::uint32_t springCount,
                                  const char* pass);

/// What the guard did over the frame (cleared when a frame starts).
struct EnergyGuardCounts {
    std::uint32_t acted = 0; ///< substeps whose energy rose beyond the resolution
    std::uint32_t pulledBack =
        0; ///< of those, substeps whose step was pulled back (the kinetic energy could not pay)
    std::uint32_t backToStart = 0; ///< of those, substeps pulled back all the way to x0 at rest
    double removed = 0.0;          ///< J taken out (velocity scales and pull-backs)
    double unremoved = 0.0;        ///< J of rises left in the state (rounding at x0 only)
    double largestExcess = 0.0;    ///< J: the largest rise found
    double total = 0.0;            ///< J: the float sum of the energy the last substep ended with
    double kinetic = 0.0;          ///< J: its kinetic part
    double contact = 0.0;          ///< J: its penalty part (the contacts' and the ground's)
};

class EnergyGuardPass {
  public:
    static constexpr PassId kId = PassId::EnergyGuard;
    static constexpr const char* kName = passName(kId);
    /// Pull-back rounds that halve the step before the last one returns to x0 at rest.
    static constexpr int kHalvingRounds = 6;

    EnergyGuardPass(const EnergyGuardParams& params, std::uint32_t springCount);

    /// Sums the current positions' energy as the start of the next substep (a frame's start: the
    /// host may have moved nodes since the last substep). `contacts`: the last detection's lists
    /// (nullptr without collision effects).
    void record(const DeviceBuffers& buffers, const ContactInputs* contacts) const;
    /// After SafeStep's cut, before its commit: sums the candidate state (predictedPositions,
    /// velocities), compares it with the start and scales the velocities or pulls the step back
    /// (each pull-back is checked again by `collision`'s CCD).
    void dispatch(const DeviceBuffers& buffers, const ContactInputs* contacts,
                  CollisionDetection& collision) const;
    /// The frame's counts (reads back) and clearing them.
    [[nodiscard]] EnergyGuardCounts frameCounts() const;
    void clearFrameCounts() const;

    /// The relative resolution of the sums: a float sum of terms of magnitude scale S, each rounded
    /// a few times (≤ 8 ulps), added in a chain at most `depth` long (the serial part of one
    /// invocation, the two trees, the decide group's serial part), is off by at most
    /// (depth + 8)·2⁻²⁴·S (Higham, Accuracy and Stability of Numerical Algorithms, §4.2).
    [[nodiscard]] static double resolutionFactor(std::uint64_t terms);

  private:
    struct Decision {
        bool record = false; ///< only record the total as the start
        std::uint32_t round = 0;
        bool last = false;
    };
    /// The terms and the decide dispatches over the state bound as the candidate.
    void sumAndDecide(const DeviceBuffers& buffers, const ContactInputs* contacts, Decision decision) const;
    [[nodiscard]] bool pullBackNeeded() const;
    /// x = x0 + alpha·(x − x0) and v = alpha·v for every moving node of the candidate.
    void pullBack(const DeviceBuffers& buffers, float alpha) const;

    EnergyGuardParams m_params;
    std::uint32_t m_springCount;
    mutable gl::Buffer m_state;                                ///< GpuEnergyGuard
    mutable std::uint32_t m_pulledBack = 0, m_backToStart = 0; ///< frame counts kept by the host
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
