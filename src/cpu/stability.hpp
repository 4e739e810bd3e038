#pragma once
// The automatic substep rule: the largest explicit (symplectic Euler) substep that stays stable
// for the stiffest spring at its lightest node. Derivation in docs/integration.md.

#include "core/contact_params.hpp"
#include "core/dynamics_params.hpp"
#include "model/flat_model.hpp"

#include <cstdint>

namespace glcollide::cpu {

struct StabilityLimit {
    double maxSubstep = 0.0; ///< s; +inf when nothing constrains the step
    std::uint32_t node = 0;  ///< the node that sets the limit
    double omega = 0.0;      ///< 1/s, bound on the highest angular frequency at that node
    double gamma = 0.0;      ///< 1/s, bound on the damping rate at that node
};

/// Largest substep h with h²ω² + 2hγ ≤ 4 at every free node, where ω² = 2·w·Σk and
/// γ = 2·w·Σc + c_air + wind drag rate (Gershgorin bounds on M⁻¹K and M⁻¹C), times `safety`.
/// With `contacts`, every node counts kContactsPerNodeForStability penalty contacts as extra
/// springs of the contact stiffness and damping.
StabilityLimit stableSubstep(const model::FlatModel& model, bool springs, const NodeForceParams& forces,
                             double safety = 0.9, const ContactParams* contacts = nullptr);

/// Simultaneous contacts per node the substep rule assumes (a vertex on a face, or an edge
/// crossing near another: one or two; deeper stacks than that stiffen the node further).
inline constexpr double kContactsPerNodeForStability = 4.0;

/// Substeps per frame: ceil(dt / maxSubstep), at least 1.
int substepsFor(double dt, const StabilityLimit& limit);

/// The most substeps per frame the engine accepts before declaring a scene too stiff.
inline constexpr int kMaxSubsteps = 100000;

} // namespace glcollide::cpu
