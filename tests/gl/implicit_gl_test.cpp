// The implicit Euler solver on the GPU (shaders/passes/implicit_*.comp) against independent
// answers: an exact dense solve of the same linear system (cpu::implicitVelocityChangeDense), the
// double-precision twin of the same PCG (cpu::implicitVelocityUpdate) where the dense solve is too
// large, and the system itself (the true residual). Backward Euler's closed form on one spring is
// in physics_gl_test.cpp.
//
// What is checked. The solver stops when its recursively updated float residual r satisfies
// ‖r‖ ≤ tol·‖b‖. The tests check the answer itself against the system: the true residual
// ‖b − A·Δv‖ of the GPU's Δv, evaluated in double with the twin's right-hand side and matrix-free
// product (cpu::implicitRightHandSide, cpu::implicitSystemProduct) on the same float inputs, must
// be at most (tol + c·u)·‖b‖ (u = 2^-24). c covers the float evaluation that makes the true residual
// differ from the recursive one (b assembled in float, the product, and v += α·p rounded every
// iteration: Greenbaum, "Iterative methods for solving linear systems", 1997, ch. 7.3); a
// worst-case bound through κ(A) is useless here (4.9·10⁶ m/s on the star), so c is measured:
// true minus reported ‖r‖/‖b‖ was at most 7 u (the star; 3 u on the one-node system, −0.5 … 0.2 u
// on the networks; llvmpipe). c = 64 leaves a margin of 9 for another device's rounding (fused
// multiply-adds, other summation orders). A wrong operator shows at once: dropping 18 % of the
// hub's springs from the product gives 0.16, scaling the spring blocks by 0.95 gives 0.05
// (tests/mutants/dyn-implicit-*.patch).
// Then agreement with an independent answer (the dense Cholesky solve, or the twin's PCG
// converged to 1e-12): Δv − Δv_ref = A⁻¹(r − r_ref) and A ⪰ M(1 + h·c_air), so
// ‖Δv − Δv_ref‖ ≤ (‖r‖ + ‖r_ref‖)/(m_min(1 + h·c_air)) with the residuals just measured.

#include "cpu/implicit_twin.hpp"
#include "passes/dynamics_passes.hpp"
#include "passes/implicit_solver.hpp"
#include "passes/row_layout.hpp"
#include "support/random_dynamics_model.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <numbers>

namespace glcollide {
namespace {

using namespace testing_support;

/// The smallest eigenvalue bound of A: A ⪰ M(1 + h·c_air) (the spring blocks are positive
/// semidefinite), so λ_min(A) ≥ the smallest free mass times 1 + h·c_air.
double smallestEigenvalueBound(const ImplicitParams& p, const RandomModel& m) {
    double w = 0.0;
    for (double x : m.state.inverseMasses) w = std::max(w, x);
    return w > 0.0 ? (1.0 + p.h * p.airDamping) / w : 1.0;
}

double norm(const std::vector<glm::dvec3>& v) {
    double s = 0.0;
    for (const glm::dvec3& x : v) s += glm::dot(x, x);
    return std::sqrt(s);
}

/// ‖b − A·Δv‖ and ‖b‖ of the system of `m` (whose state holds the external forces the GPU's setup
/// adds, and the velocities before the solve), for the velocities `after` = v + Δv, in double with
/// the twin's right-hand side and matrix-free product: the residual of the answer itself, not the
/// recursively updated one the solver stops on.
struct TrueResidual {
    double residual = 0.0, rhs = 0.0;
};
TrueResidual trueResidual(const ImplicitParams& p, const RandomModel& m,
                          const std::vector<glm::dvec3>& after) {
    std::vector<glm::dvec3> dv(after.size());
    for (std::size_t i = 0; i < after.size(); ++i) dv[i] = after[i] - m.state.velocities[i]; // exact: floats
    const std::vector<glm::dvec3> b = cpu::implicitRightHandSide(p, m.springs, m.nodeSprings, m.state);
    const std::vector<glm::dvec3> product =
        cpu::implicitSystemProduct(p, m.springs, m.nodeSprings, m.state, dv);
    std::vector<glm::dvec3> r(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) r[i] = b[i] - product[i];
    return {norm(r), norm(b)};
}

ImplicitParams solverParams() {
    ImplicitParams p;
    p.h = 1.0 / 60.0;
    p.airDamping = 0.3;
    p.springs = true;
    p.external.gravity = p.external.damping = true; // added by the setup dispatch
    p.external.gravityAcceleration = {0.3, -9.81, 0.7};
    p.external.dampingCoefficient = p.airDamping;
    p.tolerance = 1.0e-5;
    p.maxIterations = 400;
    return p;
}

/// Runs the GPU solve on `m` and returns the velocities and the solver's statistics.
std::vector<glm::dvec3> solveOnGpu(const ImplicitParams& p, const RandomModel& m,
                                   passes::ImplicitSolverCounts* counts = nullptr) {
    passes::DeviceBuffers b = uploadModel(m);
    const std::vector<std::uint32_t> heavy = passes::heavyRowNodes(m.nodeSprings.offsets);
    passes::ImplicitSolverPass pass(p, b.nodeCount, static_cast<std::uint32_t>(heavy.size()));
    pass.dispatch(b, p);
    if (counts) *counts = pass.readStatistics();
    const std::vector<glm::dvec4> v = download(b.velocities, b.nodeCount);
    return {v.begin(), v.end()};
}

/// c of the residual check (see the top): 9 × the largest measured gap of 7 u.
constexpr double kResidualRoundoffUnits = 64.0;

/// The GPU's answer (velocities `gpu` after the solve) against its system and against a reference
/// answer (the dense solve, or the twin's PCG converged far beyond the GPU's tolerance).
void expectSolvesTheSystem(const ImplicitParams& p, const RandomModel& m, const std::vector<glm::dvec3>& gpu,
                           const std::vector<glm::dvec3>& reference, double reported,
                           const std::string& what) {
    const TrueResidual g = trueResidual(p, m, gpu), ref = trueResidual(p, m, reference);
    std::printf("%s: true ‖b − AΔv‖/‖b‖ = %.4g, reported %.4g, gap %.3g u (reference %.3g), ‖b‖ = %.3g\n",
                what.c_str(), g.rhs > 0 ? g.residual / g.rhs : 0.0, reported,
                g.rhs > 0 ? (g.residual / g.rhs - reported) / kUnitRoundoff : 0.0,
                ref.rhs > 0 ? ref.residual / ref.rhs : 0.0, g.rhs);
    EXPECT_LE(g.residual, (p.tolerance + kResidualRoundoffUnits * kUnitRoundoff) * g.rhs) << what;
    double error2 = 0.0;
    for (std::size_t i = 0; i < gpu.size(); ++i) {
        const glm::dvec3 d = gpu[i] - reference[i];
        error2 += glm::dot(d, d);
    }
    // Δv − Δv_ref = A⁻¹(r − r_ref), and ‖A⁻¹‖ ≤ 1/λ_min(A); 1e-9 relative for the double
    // evaluation of the residuals (about 1e-16 of ‖|A||Δv|‖ each).
    const double bound = (g.residual + ref.residual) / smallestEigenvalueBound(p, m) * (1.0 + 1e-9);
    EXPECT_LE(std::sqrt(error2), bound) << what << ": GPU velocities vs the reference";
}

const std::uint32_t kSizes[] = {1, GLC_WORKGROUP_SIZE - 1, GLC_WORKGROUP_SIZE + 1, 2003};

class ImplicitGl : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(ImplicitGl, SolveMatchesExactSolution) {
    const std::uint32_t n = GetParam();
    RandomModel m = makeRandomModel(n, 4000 + n);
    // Stiff springs: h²k up to 28 N/m·s² against masses of 0.5–2 kg.
    for (model::FlatSpring& s : m.springs) s.stiffness = toFloat(s.stiffness * 100.0);
    const ImplicitParams p = solverParams();
    passes::ImplicitSolverCounts counts;
    const std::vector<glm::dvec3> gpu = solveOnGpu(p, m, &counts);
    EXPECT_EQ(counts.unconvergedSubsteps, 0u);
    EXPECT_LE(counts.maxRelativeResidual, p.tolerance);
    cpu::nodeForce(p.external, m.faceIndices, m.nodeFaces, m.state); // the twin's f: the same terms

    std::vector<glm::dvec3> reference = m.state.velocities;
    if (n <= 200) {
        const std::vector<glm::dvec3> dv =
            cpu::implicitVelocityChangeDense(p, m.springs, m.nodeSprings, m.state);
        for (std::size_t i = 0; i < n; ++i) reference[i] += dv[i];
    } else { // the twin's PCG, converged much further than the GPU's tolerance
        cpu::NodeState twin = m.state;
        ImplicitParams tight = p;
        tight.tolerance = 1.0e-12;
        tight.maxIterations = 5000;
        const cpu::ImplicitSolveStats s = cpu::implicitVelocityUpdate(tight, m.springs, m.nodeSprings, twin);
        ASSERT_TRUE(s.converged);
        reference = twin.velocities;
    }
    expectSolvesTheSystem(p, m, gpu, reference, counts.maxRelativeResidual, "nodes " + std::to_string(n));
}

INSTANTIATE_TEST_SUITE_P(Sizes, ImplicitGl, ::testing::ValuesIn(kSizes));

// The host stops dispatching a solve once the GPU says it has converged (read back every 16
// iterations): the same bits as a solve that runs to its cap (whose later dispatches return at
// once), and the dispatches of the iterations it needed, not of the cap. Cap 1024 against the
// same solve at a cap just above its own iteration count.
TEST(ImplicitGl, StopsDispatchingOnceConvergedWithTheSameBits) {
    RandomModel m = makeRandomModel(GLC_WORKGROUP_SIZE + 1, 4321);
    for (model::FlatSpring& s : m.springs) s.stiffness = toFloat(s.stiffness * 100.0);
    ImplicitParams p = solverParams();
    p.maxIterations = 1024;
    passes::ImplicitSolverCounts counts;
    const std::uint64_t before = gl::dispatchCount();
    const std::vector<glm::dvec3> early = solveOnGpu(p, m, &counts);
    const std::uint64_t dispatches = gl::dispatchCount() - before;
    ASSERT_EQ(counts.unconvergedSubsteps, 0u);
    const std::uint32_t needed = counts.maxIterations;
    ASSERT_GT(needed, 16u) << "a solve that needs several checks";
    ASSERT_LT(needed + 16u, 1024u);
    // Setup, then two dispatches per iteration up to the check after the converged one.
    EXPECT_LE(dispatches, 2u + 2u * (needed + 16u));
    EXPECT_LT(dispatches, 2u * 1024u);
    p.maxIterations = static_cast<int>(needed) + 1; // no check reaches past it: every dispatch runs
    passes::ImplicitSolverCounts capped;
    const std::vector<glm::dvec3> full = solveOnGpu(p, m, &capped);
    EXPECT_EQ(capped.maxIterations, needed);
    for (std::size_t i = 0; i < early.size(); ++i) {
        EXPECT_EQ(early[i].x, full[i].x) << i;
        EXPECT_EQ(early[i].y, full[i].y) << i;
        EXPECT_EQ(early[i].z, full[i].z) << i;
    }
}

/// A hub node joined to 10,000 leaves on a sphere around it (rest lengths 0.8–1.2 of the distance:
/// some springs compressed), the leaves joined in a ring, every tenth leaf pinned.
RandomModel star(std::uint32_t leaves) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> zeroOne(0.0, 1.0);
    RandomModel m;
    auto add = [&](glm::dvec3 x, double w) {
        m.state.positions.push_back(glm::dvec3(glm::vec3(x)));
        m.state.velocities.push_back(
            glm::dvec3(glm::vec3(zeroOne(rng) - 0.5, zeroOne(rng) - 0.5, zeroOne(rng) - 0.5)));
        m.state.forces.push_back(glm::dvec3(0.0));
        m.state.inverseMasses.push_back(w);
    };
    add(glm::dvec3(0.0), toFloat(1.0 / 0.05));
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (std::uint32_t i = 0; i < leaves; ++i) { // Fibonacci sphere
        const double y = 1.0 - 2.0 * (i + 0.5) / leaves, r = std::sqrt(1.0 - y * y);
        add(glm::dvec3(r * std::cos(golden * i), y, r * std::sin(golden * i)),
            i % 10 == 0 ? 0.0 : toFloat(1.0 / 0.001));
    }
    for (std::uint32_t i = 1; i <= leaves; ++i) {
        const std::uint32_t next = i % leaves + 1;
        const double hubLength = glm::length(m.state.positions[i]);
        const double ringLength = glm::length(m.state.positions[next] - m.state.positions[i]);
        m.springs.push_back({0, i, toFloat(hubLength * (0.8 + 0.4 * zeroOne(rng))), 1000.0, 0.01});
        m.springs.push_back({i, next, toFloat(ringLength), 100.0, 0.0});
    }
    const auto n = static_cast<std::uint32_t>(m.state.positions.size());
    m.nodeSprings = model::buildSpringAdjacency(n, m.springs);
    m.nodeFaces = model::buildAdjacency(n, m.faceIndices, 3);
    return m;
}

TEST(ImplicitGl, NodeOfValence10000IsGatheredByAWorkGroupAndMatchesTheTwin) {
    RandomModel m = star(10000);
    ASSERT_EQ(passes::heavyRowNodes(m.nodeSprings.offsets), std::vector<std::uint32_t>{0u});
    const auto n = static_cast<std::uint32_t>(m.state.positions.size());

    // SpringUpdate: the hub's force is a sum of 10,000 spring forces.
    {
        passes::DeviceBuffers b = uploadModel(m);
        const SpringUpdateParams p;
        passes::SpringUpdatePass(p).dispatch(b, p);
        const std::vector<glm::dvec4> gpu = download(b.forces, n);
        cpu::NodeState twin = m.state;
        twin.forces.assign(n, glm::dvec3(0.0));
        cpu::springUpdate(m.springs, m.nodeSprings, twin);
        for (std::uint32_t i = 0; i < n; ++i) {
            double magnitudes = 0.0; // Σ |term| over the row
            for (std::uint32_t k = m.nodeSprings.offsets[i]; k < m.nodeSprings.offsets[i + 1]; ++k) {
                const model::FlatSpring& s = m.springs[m.nodeSprings.items[k]];
                const double length = glm::length(m.state.positions[s.b] - m.state.positions[s.a]);
                magnitudes += s.stiffness * (length + s.restLength + 2.0) + s.damping * 2.0;
            }
            // Each term carries ~16u relative (the per-spring bound of DynamicsGl), and the sum adds
            // at most row/128 + log2(128) + 1 roundings of u·Σ|term| (strided, then the tree).
            const double row = m.nodeSprings.offsets[i + 1] - m.nodeSprings.offsets[i];
            const double tolerance = (16.0 + row / 128.0 + 8.0) * kUnitRoundoff * magnitudes;
            ASSERT_LE(glm::length(glm::dvec3(gpu[i]) - twin.forces[i]), tolerance) << "node " << i;
        }
    }
    // The implicit solve, with the hub's row gathered cooperatively in the setup and every product.
    {
        ImplicitParams p = solverParams();
        passes::ImplicitSolverCounts counts;
        const std::vector<glm::dvec3> gpu = solveOnGpu(p, m, &counts);
        EXPECT_EQ(counts.unconvergedSubsteps, 0u);
        EXPECT_LE(counts.maxRelativeResidual, p.tolerance);
        cpu::nodeForce(p.external, m.faceIndices, m.nodeFaces, m.state);
        cpu::NodeState twin = m.state;
        ImplicitParams tight = p;
        tight.tolerance = 1.0e-12;
        tight.maxIterations = 5000;
        ASSERT_TRUE(cpu::implicitVelocityUpdate(tight, m.springs, m.nodeSprings, twin).converged);
        expectSolvesTheSystem(p, m, gpu, twin.velocities, counts.maxRelativeResidual, "star");
    }
}

} // namespace
} // namespace glcollide
