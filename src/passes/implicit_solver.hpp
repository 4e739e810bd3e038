#pragma once
// The implicit Euler velocity update (docs/integration.md): ImplicitSetup assembles A·Δv = b and
// starts block-Jacobi preconditioned conjugate gradients; each iteration is two dispatches
// (ImplicitCgDirection: new direction and A·p; ImplicitCgUpdate: v += alpha·p, r, z), and a last
// ImplicitCgDirection only checks the residual. The passes agree on every scalar by summing the
// same per-group partials in the same order, so no reduce pass, no read-back and no float atomics.
// NodeUpdate (without forces) then moves the positions and applies the ground.
//
// The pass owns the solver's vectors: r, z, two p, q (vec4 each) and P⁻¹ (6 floats), 104 bytes per
// node, plus 12 bytes per work group of partial sums and 32 bytes of state.
//
// Contacts in the solve (docs/integration.md, "Contacts in the implicit solve"). A pass built with
// `contacts` and dispatched with an ImplicitContacts adds the penalty contacts of the collision
// detection's feature-pair lists to the system. Every pair the penalty response counts as a
// contact at the positions x of the start of the substep (the same geometry, ownership and side
// rules: common/contact_pair.glsl) is active, with nodes n, signed weights a, unit normal u and
// depth δ (h_c − d, or the penalty's depth on the wrong side). It contributes
//   force  f_i = a_i·k·δ·u            (to b: h·f_i)
//   K      ∂f_i/∂x_j = −k·a_i a_j u uᵀ (to b: h²·Σ_j ∂f_i/∂x_j v_j; to A: +h²k·a_i a_j u uᵀ, PSD)
// and its diagonal blocks h²k·a_i²·u uᵀ to the block-Jacobi preconditioner. Linearised at x: the
// normal's rotation and the weights' change with x (the geometric stiffness, of order k·δ/ℓ, not
// of order k), the activation of pairs that enter the thickness during the substep, damping and
// the force cap of the penalty response are not in the system. Deterministic: the contacts reach
// each row through a node → contact incidence list built per substep on the GPU (count with
// integer atomics, prefix sum, scatter, sort each row by the pair's key), summed in row order.
// Cost: kContactDispatches per substep to build the list (the find, indirect over both lists with
// their arguments, the scan, the scatter over the records, the sort) and one read-back of the
// contact count; per CG iteration 4 velocity-sized reads per incidence in ImplicitCgDirection.
// Memory: 68 bytes per contact (record 48, its list slot 4, its incidences 16) for the contacts
// found (at least one per node; grown, never dropped), 8 per node — not per feature pair: layered
// cloth has ~10³ times more swept feature pairs than contacts.

#include "core/contact_params.hpp"
#include "core/dynamics_params.hpp"
#include "core/gpu_layout.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "passes/contact_response.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"
#include "passes/row_layout.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::passes {

/// The solver statistics of the substeps since the last resetStatistics().
struct ImplicitSolverCounts {
    std::uint32_t maxIterations = 0;       ///< most CG iterations of one substep
    double maxRelativeResidual = 0.0;      ///< largest final ‖r‖/‖b‖ of one substep
    std::uint32_t totalIterations = 0;     ///< summed over the substeps
    std::uint32_t unconvergedSubsteps = 0; ///< substeps that hit the cap above the tolerance
};

/// The contacts of one implicit solve: the collision detection's feature-pair lists (vertex-face
/// and edge-edge, declared) with the face info and objects, as the penalty response reads them,
/// and its parameters: thickness (m), stiffness k (N/m) and substep (s; the open-surface side rule
/// reads x − substep·v, as the penalty response; 0: the side at x). Damping, force cap, force scale
/// and the Bridson settings are not used.
struct ImplicitContacts {
    ContactInputs inputs;
    ContactParams params;
};

class ImplicitSolverPass {
  public:
    static constexpr PassId kId = PassId::ImplicitSolve;
    static constexpr const char* kName = passName(kId);

    /// `heavyNodes`: the nodes with more than kHeavyRow springs, ascending (DeviceBuffers::heavyNodes
    /// holds the same list on the device).
    /// `contacts`: also build the contact term's kernels and buffers (dispatch with contacts).
    ImplicitSolverPass(const ImplicitParams& config, std::uint32_t nodeCount, std::uint32_t heavyCount,
                       bool contacts = false);

    /// One velocity update: setup, then iterations until converged or the cap (dispatches are issued
    /// for every iteration; after convergence they return at once). `contacts`: the contact term
    /// (the pass must be built with contacts; the records grow with the lists' capacities, nothing
    /// is read back); nullptr: the springs-only solve, the same kernels and bits as without contacts.
    void dispatch(const DeviceBuffers& buffers, const ImplicitParams& params,
                  const ImplicitContacts* contacts = nullptr) const;
    /// The second Newton step of the same substep (the pass built with contacts and
    /// ImplicitParams::newtonSteps > 1, after a dispatch with contacts): the system assembled at
    /// x1 = buffers.predictedPositions with the velocities v1 bound, the contacts of `contacts`'
    /// lists found at x1 (sides: x1 − params.substep·v1), right-hand side h·f(x1, v1) − m·(v1 − v0)
    /// with v0 the velocities the first dispatch started from; the velocities become v1 + δ.
    void dispatchNewton(const DeviceBuffers& buffers, const ImplicitParams& params,
                        const ImplicitContacts& contacts) const;

    void resetStatistics();
    [[nodiscard]] ImplicitSolverCounts readStatistics() const;

    [[nodiscard]] std::vector<std::string> allocatedLabels() const;
    [[nodiscard]] std::size_t allocatedBytes() const;
    /// The solver's vectors after the last dispatch (tests compare them with the twin).
    [[nodiscard]] const gl::Buffer& residual() const { return m_residual; }
    [[nodiscard]] const gl::Buffer& preconditioned() const { return m_preconditioned; }
    [[nodiscard]] const gl::Buffer& blockInverse() const { return m_blockInverse; }
    [[nodiscard]] const gl::Buffer& product() const { return m_product; }
    [[nodiscard]] const gl::Buffer& direction(int parity) const {
        return parity ? m_direction1 : m_direction0;
    }

    /// Contacts in the last dispatch with contacts (its records; no download: the host read the
    /// count to size them).
    [[nodiscard]] std::uint32_t contactCount() const { return m_records; }

    /// The contact term after the last dispatch with contacts (tests compare them with the twin;
    /// each a download): the records, one per contact in the order the GPU appended them, each
    /// record's list slot (vertex-face slots first, then contactEdgeEdgeBase() + the edge-edge
    /// slot), and the node → contact incidence list (row offsets: nodes + 1; entries 4·record +
    /// corner).
    [[nodiscard]] std::vector<gpu::GpuImplicitContact> downloadContactRecords() const;
    [[nodiscard]] std::vector<std::uint32_t> downloadContactRecordSlots() const;
    [[nodiscard]] std::vector<std::uint32_t> downloadNodeContactOffsets() const;
    [[nodiscard]] std::vector<std::uint32_t> downloadNodeContactList() const;
    [[nodiscard]] std::uint32_t contactEdgeEdgeBase() const { return m_contactEdgeEdgeBase; }
    /// The Newton steps' velocities (built with newtonSteps > 1): v0, the substep's start, and v1,
    /// the last Newton step's start (NewtonLineSearchPass reads both).
    [[nodiscard]] const gl::Buffer& startVelocities() const { return m_startVelocities; }
    [[nodiscard]] const gl::Buffer& newtonStart() const { return m_newtonStart; }

    /// Dispatches of one velocity update at most (the cap reached): 1 + 2·maxIterations + 1; a
    /// solve that converges stops within 16 iterations of it (kConvergenceCheckInterval).
    [[nodiscard]] std::uint32_t dispatchesPerSubstep() const;
    /// Dispatches a velocity update with contacts adds: find (over both lists, with their
    /// indirect-argument dispatches: 4), scan, scatter and sort; a find that outgrows the records
    /// runs again once the records have grown.
    static constexpr std::uint32_t kContactDispatches = 7;

  private:
    /// Whether the current solve's direction pass has set doneAt (read back from the GPU).
    [[nodiscard]] bool converged() const;
    /// One solve: setup (`setup`, the positions bound at GLC_BIND_NODE_POSITIONS: `positions`) and
    /// the conjugate-gradient iterations.
    void solve(const DeviceBuffers& b, const ImplicitParams& params, const ImplicitContacts* contacts,
               const gl::Buffer& positions, const gl::ComputeProgram& setup) const;
    /// The row layout's bindings and uniforms plus the partial sums and the state.
    void bindLayout(const gl::ComputeProgram& program, const DeviceBuffers& b) const;
    /// Builds the records and the sorted node → contact incidence list of this substep.
    void buildContactRows(const DeviceBuffers& b, const ImplicitContacts& contacts) const;
    /// Sizes the records and the incidence list for `records` contacts (they only grow).
    void reserveContacts(std::uint64_t records) const;
    /// Sets the word offsets of m_contactData's parts (u_contactCount, u_contactEntries, …).
    void setContactWords(const gl::ComputeProgram& program) const;
    /// Find over both lists: the contacts' records and the rows' counts; returns the contacts.
    [[nodiscard]] std::uint32_t findContacts(const AppendLists& lists) const;

    ImplicitParams m_config;
    std::uint32_t m_nodeCount = 0;
    RowLayout m_layout;
    gl::ComputeProgram m_setup;
    gl::ComputeProgram m_direction;
    gl::ComputeProgram m_update;
    gl::Buffer m_residual, m_preconditioned, m_direction0, m_direction1, m_product, m_blockInverse;
    gl::Buffer m_partialsR, m_partialsPq, m_state;
    // The contact term (built with contacts): the springs-only kernels above stay as they are; these
    // are their contact variants and the incidence list's builders.
    bool m_contacts = false;
    gl::ComputeProgram m_setupContacts, m_directionContacts;
    // The Newton step (ImplicitParams::newtonSteps > 1): its setup, the start velocities v0
    // (copied into m_residual for its setup) and the last Newton step's start v1.
    bool m_newton = false;
    gl::ComputeProgram m_setupNewton;
    gl::Buffer m_startVelocities, m_newtonStart;
    gl::ComputeProgram m_contactFind, m_contactScan, m_contactScatter, m_contactSort;
    mutable gl::Buffer m_nodeContactCounts; // cleared by every dispatch with contacts
    // Row offsets, the record count, incidence entries, the records' list slots and the records
    // (common/implicit_contact.glsl, GLC_BIND_IMPLICIT_CONTACTS), sized for the contacts found:
    // grown when a find counts more than it holds, hence mutable.
    mutable gl::Buffer m_contactData;
    mutable std::uint32_t m_contactEdgeEdgeBase = 0, m_recordCapacity = 0, m_records = 0;
    /// Word offsets of the parts of m_contactData.
    [[nodiscard]] std::uint32_t contactCountWord() const { return m_nodeCount + 1; }
    [[nodiscard]] std::uint32_t contactEntriesWord() const { return m_nodeCount + 2; }
    [[nodiscard]] std::size_t contactSlotsWord() const {
        return contactEntriesWord() + std::size_t{4} * m_recordCapacity;
    }
    [[nodiscard]] std::size_t contactRecordsWord() const { return contactSlotsWord() + m_recordCapacity; }
};

} // namespace glcollide::passes
