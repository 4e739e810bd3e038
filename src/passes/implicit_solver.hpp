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

#include "core/dynamics_params.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"
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

class ImplicitSolverPass {
  public:
    static constexpr PassId kId = PassId::ImplicitSolve;
    static constexpr const char* kName = passName(kId);

    /// `heavyNodes`: the nodes with more than kHeavyRow springs, ascending (DeviceBuffers::heavyNodes
    /// holds the same list on the device).
    ImplicitSolverPass(const ImplicitParams& config, std::uint32_t nodeCount, std::uint32_t heavyCount);

    /// One velocity update: setup, then iterations until converged or the cap (dispatches are issued
    /// for every iteration; after convergence they return at once).
    void dispatch(const DeviceBuffers& buffers, const ImplicitParams& params) const;

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

    /// Dispatches of one velocity update: 1 + 2·maxIterations + 1.
    [[nodiscard]] std::uint32_t dispatchesPerSubstep() const;

  private:
    /// The row layout's bindings and uniforms plus the partial sums and the state.
    void bindLayout(const gl::ComputeProgram& program, const DeviceBuffers& b) const;

    ImplicitParams m_config;
    std::uint32_t m_nodeCount = 0;
    RowLayout m_layout;
    gl::ComputeProgram m_setup;
    gl::ComputeProgram m_direction;
    gl::ComputeProgram m_update;
    gl::Buffer m_residual, m_preconditioned, m_direction0, m_direction1, m_product, m_blockInverse;
    gl::Buffer m_partialsR, m_partialsPq, m_state;
};

} // namespace glcollide::passes
