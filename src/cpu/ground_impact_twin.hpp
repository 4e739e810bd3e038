#pragma once
// CPU twin of GroundImpact (shaders/passes/ground_impact.comp, decision 0024 "Restitution at any
// step"), in float like the shader: a node that started the substep above the ground's band and
// ends it in the band leaves with at least e times its impact speed, its free fall from x0 to the
// band's top, and Coulomb friction bounded by the impact's normal change (1 + e)·vImp.

#include "core/dynamics_params.hpp"

#include <glm/vec3.hpp>

#include <vector>

namespace glcollide::cpu {

struct GroundImpactInput {
    std::vector<glm::vec3> start;         ///< x0 per node
    std::vector<glm::vec3> end;           ///< x1 per node (as SafeStep left it)
    std::vector<glm::vec3> startVelocity; ///< v at the start of the substep
    std::vector<float> inverseMass;       ///< per node (0: pinned)
};

/// The impacts on `velocity` (v after the step, changed in place); returns how many nodes changed.
std::size_t groundImpact(const GroundImpactParams& params, const GroundImpactInput& in,
                         std::vector<glm::vec3>& velocity);

} // namespace glcollide::cpu
