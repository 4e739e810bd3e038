// Friction between bodies (collision.friction, docs/collisions.md "Friction between bodies")
// through the Engine against the analytic block on an incline. The incline is one large pinned
// triangle in the plane y = 0 and gravity is tilted by θ instead (the same physics in the
// incline's frame, and the face's distances are exact in float); the block is three free nodes of
// mass m (a triangle without springs: three particles on the incline, each with one vertex-face
// contact against a pinned face, so W = Σ a_i² w_i = 1/m and the per-node count is 1).
//
// The law per substep h (symplectic Euler, the contact force from the velocities at the start of
// the substep): the penalty contact starts at its equilibrium depth m g cos θ / k, so f_n = m g cos θ
// (damped; it stays there). Friction is min(μ f_n, m |v_t| / h) against v_t. Then:
// - tan θ > μ: after the first substep (v = 0: no friction) the cap binds, so v_k = h g sin θ +
//   (k − 1) h a with a = g (sin θ − μ cos θ), and x after N substeps (T = N h) is
//   h² (N g sin θ + a N (N − 1) / 2) = a T²/2 + T h (g sin θ − a/2): within T h g of a T²/2.
// - tan θ < μ: the stop term binds (m g sin θ < μ m g cos θ), so each substep cancels the velocity
//   it starts with and gravity adds h g sin θ: the block creeps at h g sin θ, x = T h g sin θ
//   (the cost of explicit friction: one substep of the other forces is not stopped).
// - μ = 0: a = g sin θ.
// Implicit Euler and continuous detection give the response the velocities after this substep's
// gravity: no creep, x = h² a N (N + 1)/2 (their own test below). Last, the issue's cloth on a sphere, small:
// it stays at μ = 0.5 and slides off at μ = 0.

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace glcollide {
namespace {

constexpr double kG = 9.81;
constexpr double kNodeMass = 0.01;          // kg per block node
constexpr double kContactStiffness = 100.0; // N/m: ω = √(k/m) = 100/s, ω h = 0.08 at h = 1/1200 s
constexpr double kThickness = 0.01;         // m
constexpr int kSubsteps = 20;               // per frame of 1/60 s: h = 1/1200 s
constexpr int kFrames = 60;                 // T = 1 s

Scene blockOnIncline(double thetaDeg, double mu, ContactResponse response, Integrator integrator,
                     Detection detection) {
    const double theta = thetaDeg * std::numbers::pi / 180.0;
    Scene s;
    s.name = "block on incline";
    s.effects = {Effect::Gravity, Effect::Collisions};
    s.gravity = kG * glm::dvec3(std::sin(theta), -std::cos(theta), 0.0); // downhill: +x
    s.time.dt = 1.0 / 60.0;
    s.time.integrator = integrator;
    s.collision.detection = detection;
    s.time.substeps = kSubsteps;
    s.collision.thickness = kThickness;
    s.collision.stiffness = kContactStiffness;
    s.collision.damping = 0.5; // N·s/m, a quarter of critical 2√(k m): rounding does not ring
    s.collision.friction = mu;
    s.collision.response = response;
    Body incline;
    incline.name = "incline";
    // Counter-clockwise seen from +y (normal +y); the block stays far inside it.
    incline.positions = {{-5, 0, -5}, {-5, 0, 10}, {10, 0, -5}};
    incline.velocities.assign(3, glm::dvec3(0.0));
    incline.masses.assign(3, 1.0);
    incline.pinned.assign(3, 1);
    incline.faces = {{0, 1, 2}};
    // The block at the contact's equilibrium depth: k (h − y) = m g cos θ. Under implicit Euler or
    // with continuous detection the response sees the normal speed −h g cos θ after this substep's
    // gravity, whose damping c h g cos θ takes its share.
    const double h = s.time.dt / kSubsteps, damping = s.collision.damping;
    const bool seesGravity = integrator == Integrator::ImplicitEuler || detection == Detection::Continuous;
    const double solvedNormalSpeed = seesGravity ? h * kG * std::cos(theta) : 0.0;
    const double y =
        kThickness - (kNodeMass * kG * std::cos(theta) - damping * solvedNormalSpeed) / kContactStiffness;
    Body block;
    block.name = "block";
    block.positions = {{0, y, 0}, {0, y, 0.05}, {0.05, y, 0}};
    block.velocities.assign(3, glm::dvec3(0.0));
    block.masses.assign(3, kNodeMass);
    block.pinned.assign(3, 0);
    block.faces = {{0, 1, 2}};
    s.bodies = {incline, block};
    return s;
}

struct Slide {
    double distance = 0.0; // m, mean x displacement of the block's nodes
    double speed = 0.0;    // m/s, mean x velocity
    double lift = 0.0;     // m, largest |y − y0| of a block node
};

Slide simulate(double thetaDeg, double mu, ContactResponse response = ContactResponse::Penalty,
               Integrator integrator = Integrator::SymplecticEuler,
               Detection detection = Detection::Discrete) {
    const Scene scene = blockOnIncline(thetaDeg, mu, response, integrator, detection);
    Engine engine(scene);
    EXPECT_TRUE(engine.warnings().empty()) << engine.warnings().front();
    for (int f = 0; f < kFrames; ++f) engine.step();
    EXPECT_GT(engine.lastStep().collision.contacts, 0u);
    const std::vector<glm::dvec3> x = engine.readPositions(), v = engine.readVelocities();
    const std::uint32_t first = engine.bodyFirstNodes()[1];
    Slide s;
    for (std::uint32_t i = 0; i < 3; ++i) {
        s.distance += (x[first + i].x - scene.bodies[1].positions[i].x) / 3.0;
        s.speed += v[first + i].x / 3.0;
        s.lift = std::max(s.lift, std::abs(x[first + i].y - scene.bodies[1].positions[i].y));
    }
    std::printf("%s, %s, theta %.0f deg, mu %.2f: %.6f m in %.2f s, %.6f m/s, normal excursion %.2e m\n",
                detection == Detection::Continuous ? "continuous" : integratorName(integrator),
                response == ContactResponse::Bridson ? "bridson" : "penalty", thetaDeg, mu, s.distance,
                kFrames / 60.0, s.speed, s.lift);
    return s;
}

constexpr double kT = kFrames / 60.0;
constexpr double kH = 1.0 / (60.0 * kSubsteps);
// Float: each substep rounds x (≤ 2.9 m here: half an ulp ≤ 2^-23 m) and v (≤ 5.7 m/s: ≤ 2^-22
// m/s): over the 1200 substeps at most 1.5e-4 m and 3e-4 m/s (measured: 5e-5 m, 9e-5 m/s);
// allowed 1e-3 (m, m/s): a third of the gap to the continuous solution a T²/2 at 25°.
constexpr double kFloatSlack = 1e-3;

double sinDeg(double deg) {
    return std::sin(deg * std::numbers::pi / 180.0);
}
double cosDeg(double deg) {
    return std::cos(deg * std::numbers::pi / 180.0);
}

// tan θ > μ: slides with a = g (sin θ − μ cos θ). Distance and speed after N substeps against
// the discrete solution of the top, h² (N g sin θ + a N (N − 1)/2) and h g sin θ + (N − 1) h a
// (they differ from a T²/2 and a T by T h (g sin θ − a/2) and h μ g cos θ: 3 mm and 3 mm/s at
// 25°, which a wrong friction force of 1 % of μ m g cos θ would exceed), within the float slack.
// μ = 0 is the frictionless a = g sin θ. Bridson's response gives the same (at rest in the contact
// its normal force is the penalty k·depth: the limit, depth/τ·m/h, is far above it).
struct Incline {
    double thetaDeg, mu;
    ContactResponse response;
};

TEST(FrictionGl, ABlockSlidesDownASteepInclineAtTheCoulombAcceleration) {
    constexpr ContactResponse kPenalty = ContactResponse::Penalty;
    for (const auto& [thetaDeg, mu, response] :
         {Incline{25.0, 0.4, kPenalty}, Incline{35.0, 0.4, kPenalty}, Incline{20.0, 0.0, kPenalty},
          Incline{35.0, 0.0, kPenalty}, Incline{25.0, 0.4, ContactResponse::Bridson}}) {
        const double gs = kG * sinDeg(thetaDeg), a = gs - mu * kG * cosDeg(thetaDeg);
        ASSERT_GT(a, 0.0);
        const Slide s = simulate(thetaDeg, mu, response);
        const double n = kFrames * kSubsteps;
        const double distance = kH * kH * (n * gs + a * n * (n - 1.0) / 2.0),
                     speed = kH * gs + (n - 1.0) * kH * a;
        std::printf("  predicted %.6f m, %.6f m/s (a T^2/2 = %.6f m)\n", distance, speed, 0.5 * a * kT * kT);
        EXPECT_NEAR(s.distance, distance, kFloatSlack) << "theta " << thetaDeg << ", mu " << mu;
        EXPECT_NEAR(s.speed, speed, kFloatSlack) << "theta " << thetaDeg << ", mu " << mu;
        // The normal contact held its depth: within 1e-5 m, k·1e-5 = 1 mN, 1 % of f_n = m g cos θ
        // (measured ≤ 2e-8 m), so the friction cap was μ m g cos θ.
        EXPECT_LT(s.lift, 1e-5);
    }
}

// tan θ < μ: stays, creeping at one substep's worth of gravity, h g sin θ: T h g sin θ in all
// (within 1 % + float); the frictionless block would slide g sin θ T²/2, ~500 times further.
TEST(FrictionGl, ABlockStaysOnAShallowIncline) {
    for (const auto& [thetaDeg, mu, response] :
         {Incline{15.0, 0.4, ContactResponse::Penalty}, Incline{20.0, 0.4, ContactResponse::Penalty},
          Incline{20.0, 0.4, ContactResponse::Bridson}}) {
        ASSERT_LT(std::tan(thetaDeg * std::numbers::pi / 180.0), mu);
        const Slide s = simulate(thetaDeg, mu, response);
        const double creep = kT * kH * kG * sinDeg(thetaDeg);
        EXPECT_GE(s.distance, 0.0) << "theta " << thetaDeg;
        EXPECT_LE(s.distance, 1.01 * creep + 1e-5) << "theta " << thetaDeg;
        EXPECT_LE(std::abs(s.speed), 1.01 * kH * kG * sinDeg(thetaDeg) + 1e-5) << "theta " << thetaDeg;
        EXPECT_LT(s.lift, 1e-5);
    }
}

// Implicit Euler (the same h) runs ContactResponse on the velocities after the solve, and
// continuous detection on NodePredict's: both already hold this substep's gravity
// (docs/integration.md, docs/ccd.md): the friction sees v_k + h g sin θ and stops all of it. So a
// block with tan θ < μ does not creep at all, and a sliding one follows v_k = k h a,
// x = h² a N (N + 1)/2 (within the float slack). The normal force is the penalty plus the damping
// of the normal speed −h g cos θ; the block starts where their sum is m g cos θ.
TEST(FrictionGl, WhenTheResponseSeesTheSubstepsGravityABlockSticksWithoutCreep) {
    const double n = kFrames * kSubsteps;
    for (const auto& [integrator, detection] : {std::pair{Integrator::ImplicitEuler, Detection::Discrete},
                                                {Integrator::SymplecticEuler, Detection::Continuous}}) {
        // Slides at 25° (μ = 0.4; the prediction of the first test would be 3 mm further).
        const double a = kG * (sinDeg(25.0) - 0.4 * cosDeg(25.0));
        const Slide slides = simulate(25.0, 0.4, ContactResponse::Penalty, integrator, detection);
        const double distance = kH * kH * a * n * (n + 1.0) / 2.0, speed = n * kH * a;
        std::printf("  predicted %.6f m, %.6f m/s\n", distance, speed);
        EXPECT_NEAR(slides.distance, distance, kFloatSlack);
        EXPECT_NEAR(slides.speed, speed, kFloatSlack);
        EXPECT_LT(slides.lift, 1e-5); // as in the first test: f_n within 1 % of m g cos θ
        // Sticks at 20°: only rounding moves it (measured 0 m; the first test's creep is 2.8 mm).
        const Slide sticks = simulate(20.0, 0.4, ContactResponse::Penalty, integrator, detection);
        EXPECT_LT(std::abs(sticks.distance), 1e-6);
        EXPECT_LT(std::abs(sticks.speed), 1e-6);
        EXPECT_LT(sticks.lift, 1e-5);
    }
}

// The intersection-free response at the step a user chooses: implicit Euler at ONE substep per
// frame (h = 1/60 s, 20× the tests above). Its velocity filter runs before the solve (decision
// 0024, "Velocity filters before the solve"): friction bounded by μ times the penalty k·depth the
// solve applies, against the tangential velocity after the solve's gravity. In steady contact
// (depth k d = m g cos θ; the transient of the first substeps, which have no contact list yet, is
// over by frame 30) every substep is then exactly v ← v − h μ g cos θ, v ← v + h g sin θ while
// sliding, and v = 0 while sticking: from frame 30 to 120 the speed grows by 90 h a with
// a = g (sin θ − μ cos θ) (within the float slack), and a sticking block moves by rounding only
// (the creep of the tests above would be 90 h · h g sin θ = 8.5 mm here).
Slide slideFromFrame30(double thetaDeg, double mu, Slide& at30) {
    Scene scene = blockOnIncline(thetaDeg, mu, ContactResponse::IntersectionFree, Integrator::ImplicitEuler,
                                 Detection::Continuous);
    scene.time.substeps = 1;
    const double theta = thetaDeg * std::numbers::pi / 180.0;
    for (glm::dvec3& x : scene.bodies[1].positions)
        x.y = kThickness - kNodeMass * kG * std::cos(theta) / kContactStiffness; // no damping in the solve
    Engine engine(scene);
    const std::uint32_t first = engine.bodyFirstNodes()[1];
    const auto measure = [&] {
        const std::vector<glm::dvec3> x = engine.readPositions(), v = engine.readVelocities();
        Slide s;
        for (std::uint32_t i = 0; i < 3; ++i) {
            s.distance += x[first + i].x / 3.0;
            s.speed += v[first + i].x / 3.0;
            s.lift = std::max(s.lift, x[first + i].y);
        }
        return s;
    };
    for (int f = 0; f < 30; ++f) engine.step();
    at30 = measure();
    std::uint32_t guardActed = 0;
    double lowest = 1.0, highest = 0.0;
    for (int f = 30; f < 120; ++f) {
        engine.step();
        guardActed += engine.lastStep().collision.energyGuardSubsteps;
        const Slide now = measure();
        lowest = std::min(lowest, now.lift);
        highest = std::max(highest, now.lift);
        EXPECT_EQ(engine.lastStep().collision.maxIntersectingPairs, 0u);
    }
    Slide end = measure();
    std::printf("intersection_free, implicit, 1 substep/frame, theta %.0f, mu %.2f: frame 30 x %.6f v %.6f; "
                "frame 120 x %.6f v %.6f; block height %.6f..%.6f m; guard acted %u\n",
                thetaDeg, mu, at30.distance, at30.speed, end.distance, end.speed, lowest, highest,
                guardActed);
    EXPECT_EQ(guardActed, 0u) << "sliding and sticking only lose energy";
    end.lift = highest - lowest;
    return end;
}

TEST(FrictionGl, AtOneSubstepPerFrameTheIntersectionFreeBlockSticksOrSlidesByTheAngle) {
    constexpr double h = 1.0 / 60.0, n = 90.0;
    for (const auto& [thetaDeg, mu] : {std::pair{25.0, 0.4}, {30.0, 0.4}, {10.0, 0.0}}) {
        Slide at30;
        const Slide end = slideFromFrame30(thetaDeg, mu, at30);
        const double a = kG * (sinDeg(thetaDeg) - mu * cosDeg(thetaDeg));
        EXPECT_NEAR(end.speed - at30.speed, n * h * a, kFloatSlack) << "theta " << thetaDeg << ", mu " << mu;
        // x grows by h Σ v_k, v_k = v30 + k h a: n h v30 + h² a n (n + 1)/2.
        EXPECT_NEAR(end.distance - at30.distance, n * h * at30.speed + h * h * a * n * (n + 1.0) / 2.0,
                    kFloatSlack)
            << "theta " << thetaDeg << ", mu " << mu;
        EXPECT_LT(end.lift, 1e-5) << "the normal contact held its depth";
    }
    for (const auto& [thetaDeg, mu] : {std::pair{15.0, 0.4}, {20.0, 0.4}}) {
        Slide at30;
        const Slide end = slideFromFrame30(thetaDeg, mu, at30);
        EXPECT_LT(std::abs(end.distance - at30.distance), 1e-5) << "theta " << thetaDeg << ": it creeps";
        EXPECT_LT(std::abs(end.speed), 1e-5) << "theta " << thetaDeg;
    }
}

// The issue's cloth on a sphere, small: a 0.5 m cloth (12 × 12 nodes, 50 g) dropped 2 cm above a
// pinned sphere of radius 0.3 centred at the origin, off centre by 4 cm so that more of it hangs on
// one side; no ground. Bridson's response (the cloth scenes' choice, decision 0019) at the
// automatic substeps, or (`implicitIntersectionFree`) the intersection-free response under implicit
// Euler at 2 substeps per frame (decision 0024: friction in the filter before the solve), there
// also with approaching pairs in the solve (`contactMargin` thicknesses; decision 0024,
// "Approaching pairs in the solve": the margin must neither hold a frictionless cloth back nor keep
// a cloth with friction from landing in the thickness, where its friction acts).
Scene clothOnSphere(double mu, bool implicitIntersectionFree = false, int contactMargin = 0) {
    const std::string time =
        implicitIntersectionFree
            ? R"("integrator": "implicit_euler", "substeps": 2, "solver": {"contact_margin": )" +
                  std::to_string(contactMargin) + "}"
            : R"("substeps": "auto")";
    const std::string response = implicitIntersectionFree ? "intersection_free" : "bridson";
    const std::string json = R"({"format_version": 1, "name": "cloth on sphere",
      "effects": ["gravity", "springs", "damping", "collisions"],
      "time": {"dt": 0.016666666666666666, )" +
                             time + R"(},
      "damping": 0.05,
      "collision": {"broad_phase": "bvh", "response": ")" +
                             response + R"(", "thickness": 0.02, "stiffness": 100,
                    "friction": )" +
                             std::to_string(mu) + R"(},
      "objects": [
        {"name": "sphere", "generator": {"type": "sphere", "radius": 0.3, "subdivisions": 2}, "mass": 1.0,
         "springs": {"stiffness": 100}, "pinned": {"inside": {"min": [-1, -1, -1], "max": [1, 1, 1]}}},
        {"name": "cloth", "generator": {"type": "cloth", "size": [0.5, 0.5], "resolution": [12, 12]},
         "transform": {"translate": [0.04, 0.34, 0], "rotate_deg": [90, 0, 0]}, "mass": 0.05,
         "springs": {"stiffness": 20, "damping": 0.001, "shear_stiffness": 10, "bend_stiffness": 0.2}}]})";
    return parseScene(json, ".", "cloth on sphere");
}

glm::dvec3 clothCentreAfter(Engine& engine, int frames) {
    for (int f = 0; f < frames; ++f) {
        engine.step();
        EXPECT_EQ(engine.lastStep().collision.maxIntersectingPairs, 0u) << "frame " << f;
    }
    const std::vector<glm::dvec3> x = engine.readPositions();
    const std::uint32_t first = engine.bodyFirstNodes()[1];
    const std::size_t nodes = engine.scene().bodies[1].positions.size();
    glm::dvec3 c(0.0);
    for (std::size_t i = 0; i < nodes; ++i) c += x[first + i] / static_cast<double>(nodes);
    return c;
}

// After 60 frames (1 s): at μ = 0.5 the cloth is held, its centre above the sphere's centre (a
// cloth that hangs on the sphere; measured 0.244 m) and, from frame 30 to 60, within 1 cm of
// where it landed in x (measured 0.3 mm: the creep of docs/collisions.md's limits); at μ = 0 it
// has slid off, its centre below the sphere's bottom −0.3 m (measured −1.28 m: falling freely).
// Implicit, intersection-free (llvmpipe, session 25): μ = 0.5 moved 1.6 mm, μ = 0 reached −1.17 m;
// with a contact margin of 1 (its pairs in the first solve only) 1.2 mm and −0.42 m — slower: the
// first solve still holds a node sliding past an edge — where session 24's margin, in the Newton
// steps too, failed both (0.18 m; 0.03 m).
TEST(FrictionGl, ClothStaysOnASphereWithFrictionAndSlidesOffWithout) {
    for (const auto& [implicitIntersectionFree, margin] : {std::pair{false, 0}, {true, 0}, {true, 1}}) {
        SCOPED_TRACE(implicitIntersectionFree
                         ? "intersection_free, implicit Euler, 2 substeps per frame, contact "
                           "margin " +
                               std::to_string(margin)
                         : "bridson");
        Engine held(clothOnSphere(0.5, implicitIntersectionFree, margin));
        const glm::dvec3 landed = clothCentreAfter(held, 30), stays = clothCentreAfter(held, 30);
        std::printf("mu 0.5: cloth centre (%.4f, %.4f) at 0.5 s, (%.4f, %.4f) at 1 s, contacts %u\n",
                    landed.x, landed.y, stays.x, stays.y, held.lastStep().collision.contacts);
        EXPECT_GT(stays.y, 0.0);
        EXPECT_NEAR(stays.x, landed.x, 0.01);
        EXPECT_GT(held.lastStep().collision.contacts, 0u);
        Engine slides(clothOnSphere(0.0, implicitIntersectionFree, margin));
        const glm::dvec3 off = clothCentreAfter(slides, 60);
        std::printf("mu 0: cloth centre (%.4f, %.4f) at 1 s\n", off.x, off.y);
        EXPECT_LT(off.y, -0.3);
    }
}
} // namespace
} // namespace glcollide
