#pragma once
// CPU twins of the dynamics passes, in double precision. Each function does for every node what
// the shader of the same stem does for one invocation (shaders/passes/<stem>.comp), in the same
// order of operations, so the differential GL tests compare like with like.

#include "core/dynamics_params.hpp"
#include "model/flat_model.hpp"

#include <glm/vec3.hpp>

#include <vector>

namespace glcollide::cpu {

/// Node arrays as the passes see them. inverseMasses == 0 marks a pinned node.
struct NodeState {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> velocities;
    std::vector<glm::dvec3> forces;
    std::vector<double> inverseMasses;
};

/// Twin of node_force.comp: gravity, viscous damping and face wind drag for each free node;
/// pinned nodes get zero force. `faceIndices`/`nodeFaces` are read only when params.wind.
void nodeForce(const NodeForceParams& params, const std::vector<std::uint32_t>& faceIndices,
               const model::Csr& nodeFaces, NodeState& state);

/// Twin of the spring part of spring_update.comp: Hooke force plus damping along each spring,
/// gathered per node in CSR order, added to state.forces. The whole pass (external force too) is
/// nodeForce(params.external, …) followed by this.
void springUpdate(const std::vector<model::FlatSpring>& springs, const model::Csr& nodeSprings,
                  NodeState& state);

/// Twin of node_update.comp: v += h·w·f; x += h·v; then the ground plane.
void nodeUpdate(const NodeUpdateParams& params, NodeState& state);

/// Energies of a state (J). Potential includes gravity (if given) and springs (if given).
struct Energy {
    double kinetic = 0, gravitational = 0, elastic = 0;
    /// The scale of a float sum's rounding: each term's magnitude as energy_guard.comp adds it
    /// (kinetic, |gravitational|, a spring's energy plus k·|length − L|·(length + L)).
    double magnitude = 0;
    [[nodiscard]] double total() const { return kinetic + gravitational + elastic; }
};
Energy energy(const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& velocities,
              const std::vector<double>& masses, const std::vector<double>& inverseMasses,
              const glm::dvec3* gravity, const std::vector<model::FlatSpring>* springs);

/// Backward Euler's incremental potential at the velocities v of one substep (decision 0024,
/// "Line search"), whose minimiser is the step: with x = x0 + h·v for free nodes (pinned: x0),
///   Φ(v) = Σ ½m|v − v0|² + ½h·c_air·m|v|² − m g·x + ½k_g·max(0, groundLevel − y)²
///        + Σ_springs ½k(|xb − xa| − L)² + ½h·c(u·(vb − va))²  (+ the contacts' ½k·depth², added
///        by the caller),
/// ∇Φ = M(v − v0) − h·f(x, v). Twin of newton_line_search.comp (no contacts); `magnitude` is the
/// scale of its float sum's rounding, each term's as the shader adds it.
struct PotentialParams {
    double h = 0.0;
    double airDamping = 0.0;      ///< 1/s
    glm::dvec3 gravity{0.0};      ///< m/s²
    double groundStiffness = 0.0; ///< N/m per node (0: no ground penalty)
    double groundLevel = 0.0;     ///< m
};
struct Potential {
    double total = 0.0;
    double magnitude = 0.0;
};
Potential incrementalPotential(const PotentialParams& params, const std::vector<glm::dvec3>& startPositions,
                               const std::vector<glm::dvec3>& startVelocities,
                               const std::vector<glm::dvec3>& velocities,
                               const std::vector<double>& inverseMasses,
                               const std::vector<model::FlatSpring>* springs);

} // namespace glcollide::cpu
