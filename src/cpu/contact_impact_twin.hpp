#pragma once
// CPU twin of ContactImpact (shaders/passes/contact_impact.comp, decision 0024 "Restitution between
// bodies"), in double: the contacts of the final state x1 (contactGeometries, sides from x1 itself),
// each pair's impact speed from its free flight along the contact's normal from x0 and the start
// velocities, and the same Jacobi rounds (count, impulses, apply) on the velocities. The GPU sums its
// impulses in fixed point (0.5/forceScale N per contribution) and in float.

#include "core/dynamics_params.hpp"
#include "cpu/contact_twin.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::cpu {

struct ContactImpactInput {
    ContactInput end;                                       ///< positions: x1; inverse masses, faces, objects
    const std::vector<glm::dvec3>* start = nullptr;         ///< x0 per node
    const std::vector<glm::dvec3>* startVelocity = nullptr; ///< v at the start of the substep
};

struct ContactImpactResult {
    std::uint32_t impacts = 0;              ///< contacts that had an impact (the pairs the rounds act on)
    std::vector<std::uint32_t> pairsOnNode; ///< per node: impact pairs that move it (the GPU's count)
    /// m/s: the largest velocity change one pair gives a node in round 0, which sets the GPU's
    /// fixed-point scale (contact_impact.comp's addVelocityChange).
    double largestChange = 0.0;
};

/// Units per m/s of the GPU's fixed-point velocity sums for `largestChange` (contact_impact.comp,
/// mode 4): the power of two that leaves room for 1024 contributions of four times that change.
double contactImpactScale(double largestChange);

/// The impacts on `velocity` (v after the step, changed in place).
ContactImpactResult contactImpact(const ContactParams& contact, const ContactImpactParams& params,
                                  const ContactImpactInput& in, const FeaturePairList& pairs,
                                  std::vector<glm::dvec3>& velocity);

} // namespace glcollide::cpu
