// Physics checks of the GPU pipeline against analytic answers: oscillator period, free fall,
// energy of an undamped cloth, a damped cloth coming to rest, a very stiff scene.

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace glcollide {
namespace {

/// A body of two nodes joined by one spring; node 0 pinned at the origin.
Scene springMassScene(double mass, double stiffness, double restLength, double stretch) {
    Scene scene;
    scene.name = "spring-mass";
    scene.effects = {Effect::Springs};
    Body body;
    body.name = "oscillator";
    body.positions = {{0.0, 0.0, 0.0}, {0.0, -(restLength + stretch), 0.0}};
    body.velocities = {glm::dvec3(0.0), glm::dvec3(0.0)};
    body.masses = {mass, mass};
    body.pinned = {1, 0};
    body.springs = {{0, 1, restLength, stiffness, 0.0, SpringKind::Edge}};
    scene.bodies.push_back(body);
    return scene;
}

TEST(PhysicsGl, SpringMassPeriodMatchesTwoPiSqrtMOverK) {
    const double m = 0.5, k = 200.0; // T = 2π√(m/k) = 0.3142 s
    const double expected = 2.0 * std::numbers::pi * std::sqrt(m / k);
    Scene scene = springMassScene(m, k, 1.0, 0.05);
    scene.time.dt = 1e-3;
    scene.time.substeps = 4; // ωh = 0.005: symplectic Euler's period error (ωh)²/24 ≈ 1e-6
    Engine engine(scene);
    double previous = engine.readPositions()[1].y + 1.0; // displacement from rest, starts < 0
    std::vector<double> upCrossings;                     // times where the displacement crosses zero going up
    for (int frame = 1; frame <= 2000; ++frame) {
        engine.step();
        const double current = engine.readPositions()[1].y + 1.0;
        if (previous < 0.0 && current >= 0.0) {
            const double t = (frame - 1 + previous / (previous - current)) * scene.time.dt;
            upCrossings.push_back(t);
        }
        previous = current;
    }
    ASSERT_GE(upCrossings.size(), 5u);
    const double measured =
        (upCrossings.back() - upCrossings.front()) / static_cast<double>(upCrossings.size() - 1);
    // Tolerance, derived: symplectic Euler's discrete frequency satisfies cos(w_h h) = 1 - (wh)^2/2,
    // so its period is short by (wh)^2/24 relative (1e-6 at wh = 0.005); the positions, about -1 m,
    // are floats (spacing 2^-23 m) and the node crosses rest at A w = 0.05 m x 20/s = 1 m/s, so
    // each crossing time is known to 2^-23 s, the period to 2 x 2^-23 s / (crossings - 1); linear
    // interpolation at a crossing errs only at third order (a sine's curvature is 0 there). Ten
    // times their sum: 1.2e-5 relative (measured on llvmpipe: 1.6e-7).
    const double h = scene.time.dt / scene.time.substeps, wh = std::sqrt(k / m) * h;
    const double bound =
        expected * wh * wh / 24.0 + 2.0 * 0x1p-23 / static_cast<double>(upCrossings.size() - 1);
    EXPECT_NEAR(measured, expected, 10.0 * bound) << "period " << measured << " s, expected " << expected;
}

TEST(PhysicsGl, FreeFallMatchesHalfGTSquared) {
    Scene scene;
    scene.effects = {Effect::Gravity};
    Body body;
    body.positions = {{0.0, 10.0, 0.0}};
    body.velocities = {glm::dvec3(0.0)};
    body.masses = {2.0};
    body.pinned = {0};
    scene.bodies.push_back(body);
    scene.time.dt = 0.01;
    scene.time.substeps = 10; // h = 1 ms
    Engine engine(scene);
    const double g = 9.81, h = 1e-3;
    for (int frame = 1; frame <= 100; ++frame) {
        engine.step();
        const double t = frame * scene.time.dt;
        const double n = t / h;
        const double y = engine.readPositions()[0].y;
        // Symplectic Euler gives y_n = y0 - g h² n(n+1)/2 exactly; float adds ~1e-6 m at 10 m.
        EXPECT_NEAR(y, 10.0 - g * h * h * n * (n + 1.0) / 2.0, 1e-4) << "t = " << t;
        // Against the analytic ½gt² the method's own error is g·h·t/2 (≤ 4.9 mm at t = 1 s).
        EXPECT_NEAR(y, 10.0 - 0.5 * g * t * t, 0.5 * g * h * t + 1e-4) << "t = " << t;
    }
}

Scene clothScene(const std::string& effects, double damping, int frames) {
    const std::string json = R"({
      "format_version": 1, "name": "cloth test", "effects": )" +
                             effects + R"(,
      "time": {"dt": 0.005, "substeps": "auto", "frames": )" +
                             std::to_string(frames) + R"(},
      )" + (damping > 0 ? "\"damping\": " + std::to_string(damping) + "," : std::string()) +
                             R"(
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [12, 12]},
                   "transform": {"translate": [0, 1, 0], "rotate_deg": [90, 0, 0]}, "mass": 0.2,
                   "springs": {"stiffness": 300, "damping": 0.0, "bend_stiffness": 10},
                   "pinned": {"inside": {"min": [-0.6, 0.9, 0.45], "max": [0.6, 1.1, 0.6]}}}]})";
    return parseScene(json, ".", "cloth test");
}

TEST(PhysicsGl, UndampedClothConservesEnergyOver10000Steps) {
    Scene scene = clothScene(R"(["gravity", "springs"])", 0.0, 1);
    scene.time.substeps = 1;
    scene.time.dt = 5e-4; // below the stability limit (checked below): one substep per step
    Engine engine(scene);
    ASSERT_GE(engine.substepInfo().stableSubsteps, 1);
    ASSERT_EQ(engine.substepInfo().stableSubsteps, 1) << "dt must be stable for this test";
    const double e0 = engine.energy().total();
    double maxKinetic = 0.0, maxDeviation = 0.0;
    for (int step = 1; step <= 10000; ++step) {
        engine.step();
        if (step % 50 == 0) {
            const EnergyReport e = engine.energy();
            maxKinetic = std::max(maxKinetic, e.kinetic);
            maxDeviation = std::max(maxDeviation, std::abs(e.total() - e0));
        }
    }
    ASSERT_GT(maxKinetic, 0.05) << "the cloth should swing";
    // Symplectic Euler conserves a modified energy E~ = E - (h/2) F.v + O(h^2) and does not drift,
    // so, starting at rest, |E - E0| <= (h/2) max|F.v| = (h/2) max|dKE/dt|, and a motion of angular
    // frequency w has |dKE/dt| <= w KE_max. Allowed: w up to 80 /s, twenty times the swing's
    // sqrt(g / 0.6 m) = 4 /s, for the faster stretch and bend modes the release excites:
    // (h/2) 80/s KE_max = 2 % of KE_max at h = 0.5 ms (measured on llvmpipe: 0.38 %).
    const double h = scene.time.dt, omega = 80.0;
    EXPECT_LT(maxDeviation, 0.5 * h * omega * maxKinetic)
        << "max |E - E0| = " << maxDeviation << " J, max KE = " << maxKinetic << " J";
}

TEST(PhysicsGl, DampedHangingClothComesToRest) {
    Scene scene = clothScene(R"(["gravity", "springs", "damping"])", 2.0, 1);
    Engine engine(scene);
    double peakKinetic = 0.0;
    for (int frame = 1; frame <= 2000; ++frame) { // 10 s of simulated time
        engine.step();
        if (frame % 20 == 0) peakKinetic = std::max(peakKinetic, engine.energy().kinetic);
    }
    ASSERT_GT(peakKinetic, 1e-3) << "the cloth should swing down first";
    const double finalKinetic = engine.energy().kinetic;
    // Damping of 2/s takes energy down by e^-2 per second in every mode. The decay stops at a
    // float floor: rounding of the spring forces at |x| ~ 1 m (u·k·|x| ~ 2e-5 N per spring)
    // keeps ~1e-8 J of jitter (measured on llvmpipe: 8e-9 J at t = 10 s, peak 7e-3 J).
    EXPECT_LT(finalKinetic, 1e-5 * peakKinetic)
        << "KE " << finalKinetic << " J, peak " << peakKinetic << " J";
    for (const glm::dvec3& v : engine.readVelocities()) ASSERT_LT(glm::length(v), 5e-3);
}

TEST(PhysicsGl, VeryStiffSceneStaysFiniteAndBoundedFor10000Steps) {
    const std::string json = R"({
      "format_version": 1, "name": "stiff", "effects": ["gravity", "springs", "ground"],
      "time": {"dt": 0.01, "substeps": "auto", "frames": 1},
      "ground": {"height": 0, "restitution": 0, "friction": 0.5},
      "objects": [{"name": "box", "generator": {"type": "tet_box", "size": [0.2, 0.2, 0.2], "resolution": [2, 2, 2]},
                   "transform": {"translate": [0, 0.3, 0], "rotate_deg": [20, 0, 30]}, "mass": 0.01,
                   "springs": {"stiffness": 1e6, "damping": 0.0}}]})";
    Scene scene = parseScene(json, ".", "stiff test");
    Engine engine(scene);
    const SubstepInfo& info = engine.substepInfo();
    ASSERT_GT(info.substeps, 10) << "1e6 N/m on ~0.4 g nodes must need many substeps";
    const double e0 = engine.energy().total();
    const int frames = (10000 + info.substeps - 1) / info.substeps;
    for (int frame = 0; frame < frames; ++frame) engine.step();
    double lowest = 1e9;
    for (const glm::dvec3& x : engine.readPositions()) {
        ASSERT_TRUE(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z));
        lowest = std::min(lowest, x.y);
    }
    EXPECT_GE(lowest, 0.0);
    // Nothing adds energy (the box falls ~2 cm in these 0.07 s and ground contact only removes
    // energy), but float rounding does: every substep rounds each position, |x| < 0.5 m, to within
    // half a float spacing, s = 2^-26 m, a random displacement the 10^6 N/m springs turn into
    // vibration. Uncorrelated, these kicks add up like a random walk: after n substeps a spring's
    // stretch is ~sqrt(n) s, its energy ~(1/2) k n s^2. Allowance: that for every spring, 1.2e-4 J
    // for these 98 springs, 4e-3 of E0 (measured on llvmpipe: 2.6e-5 J, 8.7e-4 of E0; the earlier
    // allowance of 1e-3 of E0 had no derivation and sat 15 % above that).
    const double e1 = engine.energy().total();
    const double substeps = static_cast<double>(frames) * info.substeps, s = 0x1p-26, k = 1e6;
    const double allowance = engine.springCount() * 0.5 * k * substeps * s * s;
    std::printf("stiff box: E0 %.6g J, E %.6g J after %.0f substeps; allowance %.3g J (%u springs)\n", e0, e1,
                substeps, allowance, engine.springCount());
    EXPECT_LE(e1, e0 + allowance) << "E0 " << e0 << " J, E " << e1 << " J after " << substeps << " substeps";
}

} // namespace
} // namespace glcollide

namespace glcollide {
namespace {

TEST(PhysicsGl, ImplicitEulerSpringMassFollowsTheBackwardEulerClosedForm) {
    // Backward Euler on y'' = -ω²y: v' = (v − hω²y)/(1 + h²ω²), y' = y + h·v'. Per step the state
    // turns by atan(hω) and the energy shrinks by exactly 1/(1 + h²ω²) (docs/integration.md).
    const double m = 0.5, k = 200.0, omega = std::sqrt(k / m); // ω = 20 /s
    Scene scene = springMassScene(m, k, 1.0, 0.05);
    scene.time.integrator = Integrator::ImplicitEuler;
    scene.time.dt = 0.15; // hω = 3: symplectic Euler would need 2 substeps per frame
    scene.time.substeps = 1;
    scene.time.solver.tolerance = 1e-6;
    Engine engine(scene);
    EXPECT_GE(engine.substepInfo().stableSubsteps, 2);
    const double h = scene.time.dt;
    double y = -0.05, v = 0.0; // displacement along −y from the rest position at −1 m
    for (int n = 1; n <= 12; ++n) {
        engine.step();
        const double v1 = (v - h * omega * omega * y) / (1.0 + h * h * omega * omega);
        y += h * v1;
        v = v1;
        // One node, so block Jacobi is exact and one CG iteration solves it; what is left is float:
        // positions near 1 m carry 2^-24 m rounding per step (n steps, 4x margin).
        const double measured = engine.readPositions()[1].y + 1.0;
        EXPECT_NEAR(measured, y, 4.0 * n * 0x1p-24) << "step " << n;
        EXPECT_LE(engine.lastStep().solver.maxIterations, 1u);
    }
    // The amplitude after 12 steps: (1 + 9)^-6 of the start, so the oscillation is nearly gone —
    // the numerical damping the integration benchmark measures.
    EXPECT_LT(std::abs(y), 0.05 * 1e-5);
}

// The cloth starts horizontal, pinned at two corners, and swings down at one implicit substep per
// frame (symplectic Euler would need 815). The solves must converge: the 64-iteration default cap
// stopped every substep at ‖r‖/‖b‖ up to 4.4·10⁻² (issue 21), so this scene raises the cap to the
// format's largest, 1024 (measured: 139–721 iterations per substep over the first second).
TEST(PhysicsGl, ImplicitHangingClothWithStiffness1e5IsStableAtOneSubstepPerFrame) {
    const std::string json = R"({
      "format_version": 1, "name": "stiff hanging cloth", "effects": ["gravity", "springs", "damping"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1, "frames": 1,
               "solver": {"tolerance": 1e-4, "max_iterations": 1024}},
      "damping": 0.1,
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [32, 32]},
                   "transform": {"translate": [0, 1.5, 0], "rotate_deg": [90, 0, 0]}, "mass": 0.3,
                   "springs": {"stiffness": 1e5, "damping": 0.002, "shear_stiffness": 200, "bend_stiffness": 20},
                   "pinned": [0, 31]}]})";
    Scene scene = parseScene(json, ".", "stiff hanging cloth");
    Engine engine(scene);
    ASSERT_GT(engine.substepInfo().stableSubsteps, 500) << "symplectic Euler would need hundreds";
    const double e0 = engine.energy().total();
    constexpr int kFrames = 60; // 1 s: the swing down, the energy's peak and its fall below the start
    std::vector<double> energy{e0};
    for (int frame = 1; frame <= kFrames; ++frame) {
        engine.step();
        ASSERT_FALSE(engine.lastStep().nonFinite.found) << "frame " << frame;
        const SolverStats& solver = engine.lastStep().solver;
        ASSERT_EQ(solver.unconvergedSubsteps, 0u) << "frame " << frame << ": stopped at the cap";
        ASSERT_LE(solver.maxRelativeResidual, scene.time.solver.tolerance) << "frame " << frame;
        energy.push_back(engine.energy().total());
    }
    const double highest = *std::max_element(energy.begin(), energy.end());
    std::printf("energy: start %.4f J, highest %.4f J (%+.1f %%), after 0.5 s %.4f J, after 1 s %.4f J\n", e0,
                highest, 100.0 * (highest / e0 - 1.0), energy[kFrames / 2], energy[kFrames]);
    // One linearised step of backward Euler dissipates energy for the linear system, not for the
    // rotating stiff springs of a swinging cloth: the step moves their ends along the linearised
    // (tangential) direction, which stretches them, and at 10⁵ N/m a small stretch holds much
    // energy. So the total energy rises while the cloth swings down; measured on llvmpipe with
    // these converged solves: +36.7 % at frame 5 (+14.6 % when every solve stopped at 64
    // iterations: a capped solve damps more). The bound is that measurement plus 13 % of the start
    // for another device's rounding (a converged answer is fixed by the system to within the
    // tolerance, 10⁻⁴ relative); a step that amplifies leaves it within frames.
    EXPECT_LT(highest, 1.5 * e0);
    // Independent of that number, it is not growing: below the start at the end (measured 3.04 J
    // against 4.41 J on llvmpipe, 3.05 J on an H200), and the second half never reaches the first
    // half's peak (an amplifying step would). Not "never above the energy after 0.5 s": that
    // depends on the swing's phase, which rounding moves (H200 at bd8506c: 4.27 J after 0.5 s,
    // 4.50 J later, against llvmpipe's 4.40 J falling).
    EXPECT_LT(energy[kFrames], e0);
    const double firstHalfPeak = *std::max_element(energy.begin(), energy.begin() + kFrames / 2 + 1);
    EXPECT_LT(*std::max_element(energy.begin() + kFrames / 2 + 1, energy.end()), firstHalfPeak);
    double lowest = 10.0;
    for (const glm::dvec3& x : engine.readPositions()) lowest = std::min(lowest, x.y);
    // Stiff structural springs: the 1 m cloth hangs from y = 1.5 m and stretches little (measured
    // lowest node after 1 s: 0.548 m, still swinging).
    EXPECT_GT(lowest, 1.5 - 1.1);
    EXPECT_LT(lowest, 1.5 - 0.9);
}

} // namespace
} // namespace glcollide
