// GL-free checks of the engine's composition rule, the stability rule, the flattening of scenes
// and the mapping of driver compile logs to real file names.

#include "cpu/dynamics_twin.hpp"
#include "cpu/stability.hpp"
#include "engine/pipeline_plan.hpp"
#include "engine/response_model.hpp"
#include "gl/program.hpp"
#include "model/flat_model.hpp"

#include <glcollide/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace glcollide {
namespace {

Scene twoNodeScene(double k, double c, double m) {
    Scene scene;
    Body body;
    body.positions = {{0, 0, 0}, {0, -1, 0}};
    body.velocities = {glm::dvec3(0), glm::dvec3(0)};
    body.masses = {m, m};
    body.pinned = {1, 0};
    body.springs = {{0, 1, 1.0, k, c, SpringKind::Edge}};
    scene.bodies.push_back(body);
    return scene;
}

TEST(PipelinePlan, PassesFollowEffects) {
    Scene scene = twoNodeScene(10, 0, 1);
    EXPECT_EQ(engine::planPipeline(scene).passes(), std::vector<std::string>{"NodeUpdate"});
    scene.effects = {Effect::Gravity, Effect::Springs};
    auto plan = engine::planPipeline(scene);
    // SpringUpdate adds gravity in its own dispatch: no NodeForce pass.
    EXPECT_EQ(plan.passes(), (std::vector<std::string>{"SpringUpdate", "NodeUpdate"}));
    EXPECT_TRUE(plan.springUpdateParams.external.gravity);
    scene.effects = {Effect::Gravity};
    plan = engine::planPipeline(scene);
    EXPECT_EQ(plan.passes(), (std::vector<std::string>{"NodeForce", "NodeUpdate"}));
    scene.effects = {Effect::Springs};
    plan = engine::planPipeline(scene);
    EXPECT_FALSE(plan.springUpdateParams.external.gravity);
    EXPECT_TRUE(plan.nodeUpdateParams.forces);
    scene.effects = {Effect::Ground};
    plan = engine::planPipeline(scene);
    EXPECT_FALSE(plan.nodeUpdateParams.forces);
    EXPECT_TRUE(plan.nodeUpdateParams.ground);
    EXPECT_EQ(plan.buffers(), (std::vector<std::string>{"positions", "velocities", "faces"}));
    plan.nodeUpdateParams.checkFinite = true; // EngineOptions::checkFinite: NodeUpdate records health
    EXPECT_EQ(plan.buffers(), (std::vector<std::string>{"positions", "velocities", "faces", "health"}));
}

/// The penalty response with discrete detection: the AABB-octree paper's pipeline (not the
/// default, which is intersection_free with continuous detection; decision 0024, "The default").
void usePenalty(Scene& scene) {
    scene.collision.response = ContactResponse::Penalty;
    scene.collision.detection = Detection::Discrete;
}

TEST(PipelinePlan, StagesStateTheSubstepOrderOnce) {
    using engine::Stage;
    Scene scene = defaultScene();
    scene.effects = {Effect::Gravity, Effect::Springs, Effect::Collisions};
    usePenalty(scene);
    engine::PipelinePlan plan = engine::planPipeline(scene);
    EXPECT_EQ(plan.stages(), (std::vector<Stage>{Stage::SpringUpdate, Stage::CollisionDetection,
                                                 Stage::ContactResponse, Stage::NodeUpdate}));
    scene.time.integrator = Integrator::ImplicitEuler;
    plan = engine::planPipeline(scene);
    // The springs' solve comes after detection and before the response, which acts on its velocities.
    EXPECT_EQ(plan.stages(), (std::vector<Stage>{Stage::CollisionDetection, Stage::ImplicitSolve,
                                                 Stage::ContactResponse, Stage::NodeUpdate}));
    plan.frameStep = true; // FrameStep replaces the whole substep
    EXPECT_EQ(plan.stages(), std::vector<Stage>{Stage::FrameStep});
    EXPECT_EQ(plan.passes(), std::vector<std::string>{"FrameStep"});
}

// Continuous detection: the integrator's velocities and the predicted end positions come first,
// the collision stages then run over the substep and NodeUpdate only adds the contact forces.
TEST(PipelinePlan, ContinuousDetectionPredictsBeforeItDetects) {
    using engine::Stage;
    Scene scene = twoNodeScene(10, 0, 1);
    scene.bodies[0].faces = {{0, 1, 0}};
    scene.effects = {Effect::Gravity, Effect::Springs, Effect::Collisions};
    scene.collision.response = ContactResponse::Penalty;
    scene.collision.detection = Detection::Continuous;
    engine::PipelinePlan plan = engine::planPipeline(scene);
    EXPECT_TRUE(plan.continuous);
    EXPECT_EQ(plan.stages(),
              (std::vector<Stage>{Stage::SpringUpdate, Stage::NodePredict, Stage::CollisionDetection,
                                  Stage::ContactResponse, Stage::NodeUpdate}));
    EXPECT_EQ(plan.passes(),
              (std::vector<std::string>{"SpringUpdate", "NodePredict", "BBUpdate", "BBCollision", "TriTri",
                                        "FeaturePairs", "Ccd", "ContactResponse", "NodeUpdate"}));
    EXPECT_TRUE(plan.nodePredictParams.forces); // v += h·M⁻¹f happens once, in NodePredict
    EXPECT_FALSE(plan.nodeUpdateParams.forces);
    EXPECT_TRUE(plan.nodeUpdateParams.contacts);
    const std::vector<std::string> buffers = plan.buffers();
    EXPECT_EQ(buffers.back(), "predictedPositions");
    scene.time.integrator = Integrator::ImplicitEuler;
    plan = engine::planPipeline(scene);
    EXPECT_EQ(plan.stages(),
              (std::vector<Stage>{Stage::ImplicitSolve, Stage::NodePredict, Stage::CollisionDetection,
                                  Stage::ContactResponse, Stage::NodeUpdate}));
    EXPECT_FALSE(plan.nodePredictParams.forces); // the solve set v
    // Without a collision effect there is nothing to detect: discrete or continuous, the same plan.
    scene.effects = {Effect::Gravity, Effect::Springs};
    plan = engine::planPipeline(scene);
    EXPECT_FALSE(plan.continuous);
    EXPECT_EQ(plan.stages(), (std::vector<Stage>{Stage::ImplicitSolve, Stage::NodeUpdate}));
}

// The intersection-free response (decision 0024): the forces and the solve give v, NodePredict the
// whole step, the response iterations move v and x1, the detection checks [x0, x1], SafeStep cuts,
// the energy guard takes a rise out and x1 is committed; there is no NodeUpdate.
TEST(PipelinePlan, IntersectionFreeResponseCommitsTheCheckedStep) {
    using engine::Stage;
    Scene scene = twoNodeScene(10, 0, 1);
    scene.bodies[0].faces = {{0, 1, 0}};
    scene.effects = {Effect::Gravity, Effect::Springs, Effect::Collisions, Effect::Ground};
    scene.collision.detection = Detection::Continuous;
    scene.collision.response = ContactResponse::IntersectionFree;
    engine::PipelinePlan plan = engine::planPipeline(scene);
    EXPECT_TRUE(plan.safeStep);
    EXPECT_EQ(plan.stages(),
              (std::vector<Stage>{Stage::SpringUpdate, Stage::NodePredict, Stage::ContactIterations,
                                  Stage::CollisionDetection, Stage::SafeStep, Stage::EnergyGuard,
                                  Stage::Untangle, Stage::Commit}));
    EXPECT_EQ(plan.passes(),
              (std::vector<std::string>{"SpringUpdate", "NodePredict", "ContactResponse", "ContactApply",
                                        "BBUpdate", "BBCollision", "TriTri", "FeaturePairs", "Ccd",
                                        "SafeStep", "EnergyGuard", "Untangle"}));
    // The guard sums what the forces derive from: gravity, springs, contacts, no ground penalty
    // under symplectic Euler (the ground is a velocity response there).
    EXPECT_TRUE(plan.energyGuard);
    EXPECT_EQ(plan.energyGuardParams.gravity, scene.gravity);
    EXPECT_TRUE(plan.energyGuardParams.springs);
    EXPECT_TRUE(plan.energyGuardParams.contacts);
    EXPECT_EQ(plan.energyGuardParams.groundStiffness, 0.0);
    // x1 is the whole step: forces and ground in NodePredict, contacts and ground in ContactApply.
    EXPECT_TRUE(plan.nodePredictParams.forces);
    EXPECT_FALSE(plan.nodePredictParams.contacts);
    EXPECT_TRUE(plan.nodePredictParams.ground);
    EXPECT_FALSE(plan.contactApplyParams.forces);
    EXPECT_TRUE(plan.contactApplyParams.contacts);
    EXPECT_TRUE(plan.contactApplyParams.ground);
    // Sides of open surfaces from x itself: it is intersection-free at the start of every substep.
    EXPECT_FALSE(plan.contact.sidesFromPrevious);
    EXPECT_TRUE(plan.contact.velocityResponse);
    EXPECT_TRUE(plan.contact.repulsion);
    scene.time.solver.contactMargin = 1.0;
    EXPECT_EQ(engine::planPipeline(scene).contact.solveMargin, 0.0) << "no solve, no margin";
    scene.time.solver.contactMargin = 0.0;
    EXPECT_TRUE(plan.nodePredictParams.bandResponse);
    // The velocity response's iterations: automatic (8 under symplectic Euler, where they are the
    // contacts' only support), or the scene's.
    EXPECT_EQ(plan.responseIterations, 8);
    EXPECT_EQ(plan.responseIterations, engine::automaticResponseIterations(Integrator::SymplecticEuler));
    scene.collision.responseIterations = 3;
    EXPECT_EQ(engine::planPipeline(scene).responseIterations, 3);
    scene.collision.responseIterations = 0;
    // Under implicit Euler the velocity filters (inelastic impulses, friction, the ground's
    // response) act on the start velocity before the solve, and nothing changes v after it: the
    // penalties are in the matrix, so the iterations do not push (no repulsion).
    scene.time.integrator = Integrator::ImplicitEuler;
    scene.time.solver.newtonSteps = 1;
    plan = engine::planPipeline(scene);
    // (RecoveryIterations push after the step only while the last start intersected.) The forces at
    // the start (SpringUpdate) predict what the solve adds, for the filter's friction.
    EXPECT_EQ(plan.stages(),
              (std::vector<Stage>{Stage::SpringUpdate, Stage::ContactIterations, Stage::ImplicitSolve,
                                  Stage::NodePredict, Stage::RecoveryIterations, Stage::CollisionDetection,
                                  Stage::SafeStep, Stage::EnergyGuard, Stage::Untangle, Stage::Commit}));
    EXPECT_FALSE(plan.contact.repulsion);
    EXPECT_EQ(plan.responseIterations, 4) << "before the solve, which holds the contacts";
    EXPECT_TRUE(plan.contact.predictedForces);
    EXPECT_FALSE(plan.nodePredictParams.bandResponse);
    EXPECT_TRUE(plan.contactApplyParams.bandResponse);
    // The band's friction is bounded by the solve's ground penalty too (a resting node has some).
    EXPECT_EQ(plan.contactApplyParams.groundStiffness, plan.implicitParams.groundStiffness);
    // Automatic Newton steps with the contacts in the solve: 2. The second detects the first's end
    // and solves again there, and the line search keeps the part of it that lowers Φ; each pass is
    // listed once.
    scene.time.solver.newtonSteps = 0;
    plan = engine::planPipeline(scene);
    EXPECT_EQ(plan.implicitParams.newtonSteps, 2);
    EXPECT_TRUE(plan.lineSearch);
    EXPECT_EQ(plan.stages(),
              (std::vector<Stage>{Stage::SpringUpdate, Stage::ContactIterations, Stage::ImplicitSolve,
                                  Stage::NewtonPredict, Stage::NewtonDetection, Stage::ImplicitNewton,
                                  Stage::NewtonLineSearch, Stage::NodePredict, Stage::RecoveryIterations,
                                  Stage::CollisionDetection, Stage::SafeStep, Stage::EnergyGuard,
                                  Stage::Untangle, Stage::Commit}));
    EXPECT_EQ(plan.passes(),
              (std::vector<std::string>{"SpringUpdate", "ContactResponse", "ContactApply", "ImplicitSolve",
                                        "NodePredict", "BBUpdate", "BBCollision", "TriTri", "FeaturePairs",
                                        "Ccd", "NewtonLineSearch", "SafeStep", "EnergyGuard", "Untangle"}));
    // Φ sums what the guard sums, from the same levels, plus inertia and dissipation.
    EXPECT_EQ(plan.lineSearchParams.potentials.groundStiffness, plan.energyGuardParams.groundStiffness);
    EXPECT_EQ(plan.lineSearchParams.potentials.groundLevel, plan.energyGuardParams.groundLevel);
    EXPECT_EQ(plan.lineSearchParams.potentials.gravity, plan.energyGuardParams.gravity);
    // Steps after the second stop once the last moved no node by a quarter of the thickness.
    EXPECT_DOUBLE_EQ(plan.implicitParams.newtonMoveTolerance, 0.25 * plan.contact.thickness);
    scene.time.solver.newtonTolerance = 0.0;
    EXPECT_EQ(engine::planPipeline(scene).implicitParams.newtonMoveTolerance, 0.0);
    scene.time.solver.newtonTolerance = 0.25;
    // Approaching pairs within contact_margin thicknesses beyond it enter the solve (default 0).
    EXPECT_EQ(plan.contact.solveMargin, 0.0);
    scene.time.solver.contactMargin = 1.5;
    EXPECT_DOUBLE_EQ(engine::planPipeline(scene).contact.solveMargin, 1.5 * plan.contact.thickness);
    scene.time.solver.contactMargin = 0.0;
    scene.time.solver.newtonSteps = 3;
    EXPECT_EQ(engine::planPipeline(scene).stages().size(), plan.stages().size() + 4);
    // Switched off, each Newton step is taken whole.
    scene.time.solver.lineSearch = false;
    EXPECT_FALSE(engine::planPipeline(scene).lineSearch);
    EXPECT_EQ(engine::planPipeline(scene).stages().size(), plan.stages().size() + 3 - 1);
    scene.time.solver.lineSearch = true;
    EXPECT_FALSE(plan.nodePredictParams.forces); // the solve set v
    // The solve's ground penalty has a potential: the guard counts it, from the same level.
    EXPECT_EQ(plan.energyGuardParams.groundStiffness, plan.implicitParams.groundStiffness);
    EXPECT_EQ(plan.energyGuardParams.groundLevel,
              plan.implicitParams.groundHeight + plan.implicitParams.groundBand);
    EXPECT_GT(plan.energyGuardParams.groundStiffness, 0.0);
    // Switched off, it is not in the substep; x1 is still committed.
    scene.collision.energyGuard = false;
    plan = engine::planPipeline(scene);
    EXPECT_FALSE(plan.energyGuard);
    EXPECT_EQ(plan.stages().back(), Stage::Commit);
    EXPECT_EQ(plan.stages()[plan.stages().size() - 2], Stage::Untangle);
    EXPECT_EQ(plan.stages()[plan.stages().size() - 3], Stage::SafeStep);
}

// The responses as types (issue 23, item 6): the factory maps every setting to its class, each
// states what it needs, and the plan's substep is the one its class gives.
TEST(ResponseModel, TheFactoryMapsEverySettingToItsClass) {
    using engine::Stage;
    for (const char* name : {"penalty", "bridson", "intersection_free"}) {
        const std::optional<ContactResponse> kind = responseFromName(name);
        ASSERT_TRUE(kind) << name;
        const engine::ResponseModel& model = engine::responseModel(*kind);
        EXPECT_EQ(model.kind(), *kind) << name;
        const bool safe = *kind == ContactResponse::IntersectionFree;
        EXPECT_EQ(model.requiredDetection(),
                  safe ? std::optional<Detection>(Detection::Continuous) : std::nullopt);
        EXPECT_EQ(model.explicitUnderImplicitEuler(), *kind == ContactResponse::Penalty) << name;
        Scene scene = twoNodeScene(10, 0, 1);
        scene.bodies[0].faces = {{0, 1, 0}};
        scene.effects = {Effect::Gravity, Effect::Springs, Effect::Collisions};
        scene.collision.response = *kind;
        scene.collision.detection = Detection::Continuous;
        const engine::PipelinePlan plan = engine::planPipeline(scene);
        EXPECT_EQ(plan.safeStep, safe) << name;
        EXPECT_EQ(plan.stages(), model.stages(plan)) << name;
        EXPECT_EQ(plan.stages(), safe ? plan.safeStepStages() : plan.forceResponseStages()) << name;
    }
    EXPECT_FALSE(responseFromName("impulse"));
}

TEST(PipelinePlan, EmptySceneRunsNothing) {
    Scene scene;
    scene.effects = {Effect::Gravity};
    EXPECT_TRUE(engine::planPipeline(scene).passes().empty());
    EXPECT_TRUE(engine::planPipeline(scene).buffers().empty());
}

TEST(PipelinePlan, CollisionEffectsAddTheBroadPhaseNarrowPhaseAndResponse) {
    Scene scene = twoNodeScene(10, 0, 1);
    scene.bodies[0].faces = {{0, 1, 0}};
    scene.effects = {Effect::Gravity, Effect::Collisions};
    usePenalty(scene);
    engine::PipelinePlan plan = engine::planPipeline(scene);
    EXPECT_TRUE(plan.betweenObjects);
    EXPECT_FALSE(plan.selfCollisions);
    EXPECT_EQ(plan.passes(), (std::vector<std::string>{"NodeForce", "BBUpdate", "BBCollision", "TriTri",
                                                       "FeaturePairs", "ContactResponse", "NodeUpdate"}));
    EXPECT_EQ(plan.buffers(),
              (std::vector<std::string>{"positions", "velocities", "faces", "forces", "contactForces"}));
    EXPECT_TRUE(plan.nodeUpdateParams.contacts);
    scene.effects = {Effect::SelfCollisions};
    scene.collision.broadPhase = BroadPhase::AllPairs;
    plan = engine::planPipeline(scene);
    EXPECT_TRUE(plan.selfCollisions);
    // All pairs: one broad-phase stage (every face pair's boxes), timed as BBCollision.
    EXPECT_EQ(plan.passes(), (std::vector<std::string>{"BBCollision", "TriTri", "FeaturePairs",
                                                       "ContactResponse", "NodeUpdate"}));
    scene.bodies[0].faces.clear(); // nothing to collide: no collision passes
    EXPECT_EQ(engine::planPipeline(scene).passes(), std::vector<std::string>{"NodeUpdate"});
}

TEST(PipelinePlan, ContactForceScaleLeavesHeadroomAndIsAPowerOfTwo) {
    CollisionSettings s;
    s.stiffness = 1.0e4;
    s.thickness = 0.01;
    const ContactParams p = contactParams(s);
    EXPECT_EQ(p.forceCap, 4.0 * 1.0e4 * 0.01);
    EXPECT_LE(p.forceScale * p.forceCap * kContactsPerNodeHeadroom, 2147483647.0);
    EXPECT_GT(2.0 * p.forceScale * p.forceCap * kContactsPerNodeHeadroom, 2147483647.0);
    EXPECT_EQ(std::exp2(std::round(std::log2(p.forceScale))), p.forceScale);
}

TEST(Stability, ContactsStiffenEveryFreeNode) {
    const model::FlatModel model = model::flatten(twoNodeScene(400, 0, 0.25));
    CollisionSettings s;
    s.stiffness = 1000;
    const ContactParams contacts = contactParams(s);
    const cpu::StabilityLimit with = cpu::stableSubstep(model, true, {}, 1.0, &contacts);
    const double expected = 2.0 * (1.0 / 0.25) * (400 + cpu::kContactsPerNodeForStability * 1000);
    EXPECT_DOUBLE_EQ(with.omega * with.omega, expected);
}

TEST(Stability, SingleSpringLimitIsTheBoundOnTwoOverOmega) {
    // One free node on one spring: ω² = k/m exactly; the Gershgorin bound used is 2k/m, so the
    // rule gives h = safety · 2/√(2k/m).
    const double k = 400, m = 0.25;
    const model::FlatModel model = model::flatten(twoNodeScene(k, 0, m));
    const cpu::StabilityLimit limit = cpu::stableSubstep(model, true, {}, 1.0);
    EXPECT_DOUBLE_EQ(limit.maxSubstep, 2.0 / std::sqrt(2.0 * k / m));
    EXPECT_EQ(limit.node, 1u);
    EXPECT_LE(limit.maxSubstep, 2.0 / std::sqrt(k / m)) << "never looser than the exact limit";
}

TEST(Stability, DampingShrinksTheStepToTheJuryBound) {
    const double k = 400, c = 3, m = 0.25;
    const model::FlatModel model = model::flatten(twoNodeScene(k, c, m));
    const cpu::StabilityLimit limit = cpu::stableSubstep(model, true, {}, 1.0);
    const double h = limit.maxSubstep, w2 = limit.omega * limit.omega, g = limit.gamma;
    EXPECT_NEAR(h * h * w2 + 2 * h * g, 4.0, 1e-12) << "h solves h²ω² + 2hγ = 4";
    EXPECT_LT(h, 2.0 / limit.omega);
}

TEST(Stability, ExplicitEulerOnTheTwinIsStableAtTheLimitAndUnstableAboveTheExactOne) {
    // The CPU twin integrates one spring: at the rule's step it stays bounded; at 1.05× the exact
    // limit 2/ω it grows, showing the rule is not vacuous.
    const double k = 400, m = 0.25;
    const model::FlatModel model = model::flatten(twoNodeScene(k, 0, m));
    auto run = [&](double h) {
        cpu::NodeState s{model.positions, model.velocities, {}, model.inverseMasses};
        s.positions[1].y -= 0.1;
        double amplitude = 0;
        for (int i = 0; i < 2000; ++i) {
            s.forces.assign(s.positions.size(), glm::dvec3(0.0));
            cpu::springUpdate(model.springs, model.nodeSprings, s);
            cpu::nodeUpdate({h, true}, s);
            amplitude = std::max(amplitude, std::abs(s.positions[1].y + 1.0));
        }
        return amplitude;
    };
    EXPECT_LT(run(cpu::stableSubstep(model, true, {}).maxSubstep), 0.2);
    EXPECT_GT(run(1.05 * 2.0 / std::sqrt(k / m)), 1e3);
}

TEST(Stability, SubstepCount) {
    cpu::StabilityLimit limit;
    limit.maxSubstep = std::numeric_limits<double>::infinity();
    EXPECT_EQ(cpu::substepsFor(0.01, limit), 1);
    limit.maxSubstep = 0.003;
    EXPECT_EQ(cpu::substepsFor(0.01, limit), 4);
    limit.maxSubstep = 1e-12;
    EXPECT_GT(cpu::substepsFor(0.01, limit), cpu::kMaxSubsteps);
}

TEST(FlatModel, ConcatenatesBodiesAndSortsAdjacency) {
    Scene scene = twoNodeScene(10, 0, 1);
    scene.bodies.push_back(scene.bodies[0]);
    scene.bodies[1].faces = {{0, 1, 1}};
    const model::FlatModel m = model::flatten(scene);
    ASSERT_EQ(m.nodeCount(), 4u);
    EXPECT_EQ(m.springs[1].a, 2u);
    EXPECT_EQ(m.springs[1].b, 3u);
    EXPECT_EQ(m.inverseMasses[0], 0.0) << "pinned";
    EXPECT_EQ(m.inverseMasses[1], 1.0);
    EXPECT_EQ(m.faceIndices, (std::vector<std::uint32_t>{2, 3, 3}));
    EXPECT_EQ(m.nodeSprings.offsets, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
    EXPECT_EQ(m.nodeFaces.offsets, (std::vector<std::uint32_t>{0, 0, 0, 1, 3}));
    for (std::size_t i = 0; i < m.nodeCount(); ++i)
        for (std::uint32_t k = m.nodeSprings.offsets[i] + 1; k < m.nodeSprings.offsets[i + 1]; ++k)
            EXPECT_LT(m.nodeSprings.items[k - 1], m.nodeSprings.items[k]);
}

TEST(ShaderLog, MesaAndNvidiaLocationsNameTheFile) {
    // node_force.comp includes common/layout.glsl as GLSL source string 1.
    const std::string mesa = gl::mapShaderLog("1:12(3): error: boom\n0:40(1): error: bang", "node_force");
    EXPECT_NE(mesa.find("shaders/common/layout.glsl:12: error: boom"), std::string::npos) << mesa;
    EXPECT_NE(mesa.find("shaders/passes/node_force.comp:40: error: bang"), std::string::npos) << mesa;
    const std::string nvidia = gl::mapShaderLog("0(7) : error C0000: syntax error", "node_force");
    EXPECT_NE(nvidia.find("shaders/passes/node_force.comp:7 : error C0000"), std::string::npos) << nvidia;
}

TEST(ShaderLog, DefinesAreInsertedAfterVersionWithoutShiftingLines) {
    const std::string source = gl::shaderSource("node_update", {"GLC_GROUND"});
    EXPECT_EQ(source.rfind("#version 430 core\n#define GLC_GROUND\n#line 2 0\n", 0), 0u)
        << source.substr(0, 80);
    EXPECT_THROW(gl::shaderSource("node_update", {"1BAD"}), Error);
    EXPECT_THROW(gl::shaderSource("no_such_shader"), Error);
}

} // namespace
} // namespace glcollide
