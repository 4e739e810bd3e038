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

} // namespace glcollide::cpu
