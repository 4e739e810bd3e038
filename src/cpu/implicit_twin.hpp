#pragma once
// CPU twin of the implicit Euler velocity update (shaders/passes/implicit_*.comp), in double
// precision, and an exact dense solve of the same linear system for tests.
//
// The system of one substep (Baraff & Witkin 1998, one Newton step of backward Euler):
//   A Δv = b,  A = M(1 + h·c_air) + Σ_springs (h·C_s + h²·K_s) as a graph Laplacian,
//              b = h·f(x, v) + h²·Σ_springs K_s (v_j − v_i)   (per node i)
// with K_s = k·[u uᵀ + max(0, 1 − L/l)(I − u uᵀ)] (the transverse term clamped at 0 for
// compressed springs, so K_s is positive semidefinite) and C_s = c·u uᵀ. Pinned nodes keep
// Δv = 0 (their rows and columns are removed). A is then symmetric positive definite.
//
// With an ImplicitContactSet (the contact term, implicit_contact_find.comp and the
// GLC_IMPLICIT_CONTACTS variants of the solver) every contact c (nodes n, weights a, normal u,
// depth δ) adds the force f_i = a_i·k·δ·u and the stiffness ∂f_i/∂x_j = −k·a_i a_j u uᵀ:
//   b_i += h·a_i·k·δ·u − h²·k·a_i·u (u·Σ_j a_j v_j)   (all four nodes' v, pinned ones too)
//   A_ij += h²·k·a_i a_j u uᵀ                            (free nodes only: positive semidefinite)

#include "core/dynamics_params.hpp"
#include "cpu/contact_twin.hpp"
#include "cpu/dynamics_twin.hpp"
#include "model/flat_model.hpp"

#include <glm/mat3x3.hpp>

#include <vector>

namespace glcollide::cpu {

/// The 3×3 block h·C_s + h²·K_s of one spring between i and j, as α·I + β·u uᵀ.
struct SpringBlock {
    glm::dvec3 u{0.0};              ///< unit direction from i to j
    double alpha = 0;               ///< h²·k·max(0, 1 − L/l)
    double beta = 0;                ///< h·c + h²·k·(1 − max(0, 1 − L/l))
    double force = 0;               ///< k(l − L) + c·u·(v_j − v_i): the force on i along u
    double transverseStiffness = 0; ///< k·max(0, 1 − L/l)
    double alongStiffness = 0;      ///< k − transverseStiffness (K_s = kT·I + kA·u uᵀ)
    bool valid = false;             ///< false for coincident ends (no direction: no force, no block)
};
SpringBlock springBlock(const model::FlatSpring& s, const glm::dvec3& xi, const glm::dvec3& xj,
                        const glm::dvec3& vi, const glm::dvec3& vj, double h);

/// The contacts of one implicit solve and their stiffness k (N/m).
struct ImplicitContactSet {
    std::vector<ContactGeometry> contacts;
    double stiffness = 0.0;
};

/// The contacts of the feature pairs for the implicit solve: contactGeometries at params.thickness
/// and params.substep (the side rule), crossings at any depth (Crossings::AtAnyDepth: a Newton
/// step's predicted end may have gone through), with params.stiffness; and, with
/// params.solveMargin > 0, the pairs beyond the thickness but within the margin that approach at
/// in.velocities (GLC_APPROACH_SLACK), with depth 0: stiffness, no force (decision 0024,
/// "Approaching pairs in the solve"). Needs in.velocities when the margin is > 0.
ImplicitContactSet implicitContacts(const ContactParams& params, const ContactInput& in,
                                    const FeaturePairList& pairs);

/// What one solve did.
struct ImplicitSolveStats {
    int iterations = 0;          ///< CG updates until ‖r‖ ≤ tol·‖b‖ (maxIterations if never)
    double relativeResidual = 0; ///< ‖r‖/‖b‖ at the end (0 when b = 0)
    bool converged = false;
};

/// Twin of implicit_setup + implicit_cg_direction + implicit_cg_update: adds the PCG solution Δv to
/// state.velocities. state.forces holds the external forces (NodeForce output, or zeros) plus the
/// contact forces. Same algorithm and order as the GPU (block-Jacobi PCG starting from Δv = 0).
ImplicitSolveStats implicitVelocityUpdate(const ImplicitParams& params,
                                          const std::vector<model::FlatSpring>& springs,
                                          const model::Csr& nodeSprings, NodeState& state,
                                          const ImplicitContactSet* contacts = nullptr);

/// The exact Δv of the same system, by dense Cholesky factorisation of A in double (test oracle;
/// O(n³): small systems only). Pinned nodes get 0.
std::vector<glm::dvec3> implicitVelocityChangeDense(const ImplicitParams& params,
                                                    const std::vector<model::FlatSpring>& springs,
                                                    const model::Csr& nodeSprings, const NodeState& state,
                                                    const ImplicitContactSet* contacts = nullptr);

/// The Newton step (implicit_newton_setup.comp): at the state's positions x1 and velocities v1,
/// with v0 = `startVelocities`, the same A and b = h·f(x1, v1) − m·(v1 − v0) (contacts: their
/// force only); the exact δ by the dense solve (the step's velocities are v1 + δ), and b.
std::vector<glm::dvec3> implicitNewtonChangeDense(const ImplicitParams& params,
                                                  const std::vector<model::FlatSpring>& springs,
                                                  const model::Csr& nodeSprings, const NodeState& state,
                                                  const std::vector<glm::dvec3>& startVelocities,
                                                  const ImplicitContactSet* contacts = nullptr);
std::vector<glm::dvec3> implicitNewtonRightHandSide(const ImplicitParams& params,
                                                    const std::vector<model::FlatSpring>& springs,
                                                    const model::Csr& nodeSprings, const NodeState& state,
                                                    const std::vector<glm::dvec3>& startVelocities,
                                                    const ImplicitContactSet* contacts = nullptr);

/// The right-hand side b of the system, per node (0 for pinned nodes), as the twin assembles it.
std::vector<glm::dvec3> implicitRightHandSide(const ImplicitParams& params,
                                              const std::vector<model::FlatSpring>& springs,
                                              const model::Csr& nodeSprings, const NodeState& state,
                                              const ImplicitContactSet* contacts = nullptr);

/// A·x, the matrix-free product the twin's PCG uses (pinned entries of x are ignored, pinned rows of
/// the result are 0). With implicitRightHandSide a test evaluates the true residual b − A·Δv of any
/// Δv, e.g. the GPU's, in double.
std::vector<glm::dvec3> implicitSystemProduct(const ImplicitParams& params,
                                              const std::vector<model::FlatSpring>& springs,
                                              const model::Csr& nodeSprings, const NodeState& state,
                                              const std::vector<glm::dvec3>& x,
                                              const ImplicitContactSet* contacts = nullptr);

/// ‖b‖₂ of the system (for the error bound ‖Δv − Δv*‖ ≤ tol·‖b‖ / min mass of the tests).
double implicitRightHandSideNorm(const ImplicitParams& params, const std::vector<model::FlatSpring>& springs,
                                 const model::Csr& nodeSprings, const NodeState& state,
                                 const ImplicitContactSet* contacts = nullptr);

} // namespace glcollide::cpu
