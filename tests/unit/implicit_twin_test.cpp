// The implicit Euler twin (src/cpu/implicit_twin.cpp) against analytic answers: backward Euler on
// one spring has a closed form (energy shrinks by exactly 1/(1 + h²ω²) per step, the phase advances
// by atan(hω)), and its PCG agrees with a dense Cholesky solve of the same system.

#include "cpu/implicit_twin.hpp"
#include "model/flat_model.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <random>

namespace glcollide {
namespace {

/// Node 0 pinned at the origin, node 1 of mass m on the x axis at rest length + stretch.
struct OneSpring {
    cpu::NodeState state;
    std::vector<model::FlatSpring> springs;
    model::Csr rows;
};

OneSpring oneSpring(double mass, double stiffness, double restLength, double stretch) {
    OneSpring s;
    s.state.positions = {glm::dvec3(0.0), glm::dvec3(restLength + stretch, 0.0, 0.0)};
    s.state.velocities = {glm::dvec3(0.0), glm::dvec3(0.0)};
    s.state.forces = {glm::dvec3(0.0), glm::dvec3(0.0)};
    s.state.inverseMasses = {0.0, 1.0 / mass};
    s.springs = {{0, 1, restLength, stiffness, 0.0}};
    s.rows = model::buildSpringAdjacency(2, s.springs);
    return s;
}

ImplicitParams params(double h) {
    ImplicitParams p;
    p.h = h;
    p.springs = true;
    p.tolerance = 1e-14;
    p.maxIterations = 50;
    return p;
}

TEST(ImplicitTwin, OneSpringFollowsTheBackwardEulerClosedForm) {
    const double m = 0.2, k = 5000.0, L = 0.5, h = 0.01; // hω = 1.58: far beyond explicit's limit 2
    const double omega = std::sqrt(k / m);
    OneSpring s = oneSpring(m, k, L, 0.1);
    const ImplicitParams p = params(h);
    double y = 0.1, v = 0.0; // the closed-form recurrence of backward Euler on y'' = -ω² y
    const double energy0 = 0.5 * k * y * y;
    for (int n = 1; n <= 200; ++n) {
        cpu::implicitVelocityUpdate(p, s.springs, s.rows, s.state);
        s.state.positions[1] += h * s.state.velocities[1];
        const double v1 = (v - h * omega * omega * y) / (1.0 + h * h * omega * omega);
        y += h * v1;
        v = v1;
        const double simY = s.state.positions[1].x - L;
        ASSERT_NEAR(simY, y, 1e-12) << "step " << n;
        ASSERT_NEAR(s.state.velocities[1].x, v, 1e-10) << "step " << n;
        // The map is a rotation by atan(hω) scaled by 1/sqrt(1 + h²ω²) in the energy norm.
        const double energy = 0.5 * m * v * v + 0.5 * k * y * y;
        ASSERT_NEAR(energy / energy0, std::pow(1.0 + h * h * omega * omega, -n), 1e-9) << "step " << n;
        EXPECT_EQ(s.state.positions[1].y, 0.0);
    }
}

TEST(ImplicitTwin, CompressedSpringKeepsTheSystemPositiveDefinite) {
    // A spring compressed to a tenth of its rest length has transverse stiffness k(1 - L/l) = -9k:
    // unclamped, h²K would make A indefinite for h²k > m/9. The clamp keeps A ⪰ M: Cholesky works.
    OneSpring s = oneSpring(0.01, 1.0e4, 1.0, -0.9);
    s.state.velocities[1] = glm::dvec3(0.0, 3.0, 0.0);
    const ImplicitParams p = params(1.0 / 60.0);
    const std::vector<glm::dvec3> dv = cpu::implicitVelocityChangeDense(p, s.springs, s.rows, s.state);
    for (const glm::dvec3& d : dv)
        EXPECT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z));
    // Transverse: no stiffness after the clamp, so the y velocity is untouched.
    EXPECT_NEAR(dv[1].y, 0.0, 1e-12);
    cpu::NodeState twin = s.state;
    const cpu::ImplicitSolveStats stats = cpu::implicitVelocityUpdate(p, s.springs, s.rows, twin);
    EXPECT_TRUE(stats.converged);
    EXPECT_NEAR(twin.velocities[1].x, s.state.velocities[1].x + dv[1].x, 1e-9);
}

TEST(ImplicitTwin, PcgMatchesTheDenseSolveOnARandomNetwork) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), zeroOne(0.0, 1.0);
    const std::uint32_t n = 60;
    cpu::NodeState state;
    for (std::uint32_t i = 0; i < n; ++i) {
        state.positions.emplace_back(unit(rng), unit(rng), unit(rng));
        state.velocities.emplace_back(unit(rng), unit(rng), unit(rng));
        state.forces.emplace_back(unit(rng), unit(rng), unit(rng));
        state.inverseMasses.push_back(i % 17 == 0 ? 0.0 : 1.0 / (0.01 + zeroOne(rng)));
    }
    std::vector<model::FlatSpring> springs;
    for (std::uint32_t s = 0; s < 4 * n; ++s) {
        const std::uint32_t a = s % n, b = (a + 1 + static_cast<std::uint32_t>(zeroOne(rng) * (n - 1))) % n;
        const double l = glm::length(state.positions[b] - state.positions[a]);
        springs.push_back({a, b, l * (0.5 + zeroOne(rng)), 1.0e4 * zeroOne(rng), 0.1 * zeroOne(rng)});
    }
    const model::Csr rows = model::buildSpringAdjacency(n, springs);
    ImplicitParams p = params(1.0 / 30.0);
    p.airDamping = 0.5;
    p.tolerance = 1e-10;
    p.maxIterations = 1000;
    const std::vector<glm::dvec3> dense = cpu::implicitVelocityChangeDense(p, springs, rows, state);
    cpu::NodeState twin = state;
    const cpu::ImplicitSolveStats stats = cpu::implicitVelocityUpdate(p, springs, rows, twin);
    ASSERT_TRUE(stats.converged);
    EXPECT_LE(stats.relativeResidual, p.tolerance);
    // ‖Δv − Δv*‖ ≤ ‖A⁻¹‖·‖r‖ ≤ tol·‖b‖ / m_min  (A ⪰ m_min·I); m_min ≥ 0.01 kg here.
    const double bound = p.tolerance * cpu::implicitRightHandSideNorm(p, springs, rows, state) / 0.01;
    double error2 = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 d = twin.velocities[i] - (state.velocities[i] + dense[i]);
        error2 += glm::dot(d, d);
        if (state.inverseMasses[i] == 0.0) {
            EXPECT_EQ(twin.velocities[i], state.velocities[i]);
        }
    }
    EXPECT_LE(std::sqrt(error2), bound);
}

} // namespace
} // namespace glcollide
