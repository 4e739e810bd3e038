#pragma once
// NewtonLineSearch — a backtracking line search for implicit Euler's further Newton steps
// (decision 0024, "Line search"). After ImplicitSolverPass::dispatchNewton moved the velocities
// from v1 to v1 + δ, the incremental potential Φ(v) = Σ ½m|v − v0|² + U(x0 + h·v) + h·D(v)
// (newton_line_search.comp) is summed on the GPU for v1 and for v1 + α·δ, α = 1, ½, ¼; the first
// candidate whose Φ is not above Φ(v1) by more than the sums' resolution is kept, else v1. The
// penalty is not smooth at the band's edge, so a full Newton step can climb: a pair the first step
// pushed out of the band has no force at x1, and the next step pulls it back deeper.
// Each evaluation is three dispatches and one 8-byte read-back (the host decides).

#include "passes/contact_response.hpp"
#include "passes/device_buffers.hpp"
#include "passes/energy_guard.hpp"
#include "passes/pass_id.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>

namespace glcollide::passes {

/// What Φ sums besides inertia: the energy guard's potentials (the scene's, the contacts' and the
/// ground's penalties, sides of open faces from x0 here) and the dampers' dissipation.
struct LineSearchParams {
    EnergyGuardParams potentials;
    double airDamping = 0.0; ///< 1/s: the air's c (force −c·m·v); 0 when off
};

/// What the line search did over the frame (cleared when a frame starts).
struct LineSearchCounts {
    std::uint32_t steps = 0;     ///< Newton steps searched
    std::uint32_t shortened = 0; ///< of those, steps that kept a fraction α < 1 of δ
    std::uint32_t rejected = 0;  ///< of those, steps that kept none of δ (back to v1)
};

/// What one line-searched Newton step kept.
struct LineSearchStep {
    float fraction = 1.0f; ///< α: the fraction of δ kept (0: none; the step's start v1 stays)
    /// m: the largest distance the kept step moved a free node's end x1 = x0 + h·v, α·h·max|δ|
    /// (δ's largest entry is exact: an order-independent maximum on the GPU).
    double largestMove = 0.0;
};

/// One evaluation of Φ: the GPU's float total and the magnitude scale of its terms.
struct PotentialSum {
    double total = 0.0;     ///< J
    double magnitude = 0.0; ///< J: the rounding's scale (EnergyGuardPass::resolutionFactor)
};

class NewtonLineSearchPass {
  public:
    static constexpr PassId kId = PassId::NewtonLineSearch;
    static constexpr const char* kName = passName(kId);
    /// The fractions of δ tried, in order; none accepted keeps v1.
    static constexpr std::array<float, 3> kFractions = {1.0f, 0.5f, 0.25f};

    NewtonLineSearchPass(const LineSearchParams& params, std::uint32_t nodeCount, std::uint32_t springCount);

    /// After a Newton step's solve: `startVelocities` v0 (the substep's start), `stepStart` v1
    /// (the Newton step's start), the buffers' velocities v1 + δ. Leaves the velocities at the
    /// kept candidate and predictedPositions at x0 + h·v; returns the fraction of δ kept and how far
    /// it moved x1. `contacts`: the Newton step's detection lists (nullptr without collision effects).
    LineSearchStep dispatch(const DeviceBuffers& buffers, const ContactInputs* contacts,
                            const gl::Buffer& startVelocities, const gl::Buffer& stepStart, double h) const;

    /// Φ at v = v1 + alpha·δ, with the velocity sets of the last dispatch (tests compare it with the
    /// twin's); leaves that candidate in the buffers.
    [[nodiscard]] PotentialSum evaluate(const DeviceBuffers& buffers, const ContactInputs* contacts,
                                        float alpha, double h) const;
    /// The relative resolution of the last evaluation's sum (over the nodes, the springs and the
    /// lists' capacities): two sums differ beyond rounding when they differ by more than this
    /// times the sum of their magnitudes.
    [[nodiscard]] double resolution() const { return EnergyGuardPass::resolutionFactor(m_terms); }

    [[nodiscard]] LineSearchCounts frameCounts() const { return m_counts; }
    void clearFrameCounts() const { m_counts = {}; }

  private:
    void bindState(const DeviceBuffers& buffers, const ContactInputs* contacts) const;
    void copyVelocities(const DeviceBuffers& buffers, const gl::Buffer& startVelocities,
                        const gl::Buffer& stepStart) const;
    void writeCandidate(const DeviceBuffers& buffers, float alpha, double h) const;
    [[nodiscard]] PotentialSum sum(double h) const;

    LineSearchParams m_params;
    std::uint32_t m_nodeCount;
    std::uint32_t m_springCount;
    mutable gl::Buffer m_state;      ///< GpuLineSearch
    mutable gl::Buffer m_velocities; ///< vec4[3·nodes]: v0, v1, v1 + δ
    mutable LineSearchCounts m_counts;
    mutable std::uint64_t m_terms = 0;    ///< terms of the last evaluation's sum
    mutable float m_largestChange = 0.0f; ///< m/s: max |δ| over the free nodes, read with the last sum
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
