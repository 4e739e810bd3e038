#include "engine/pipeline_plan.hpp"

#include "engine/response_model.hpp"
#include "passes/broad_phase/create_broad_phase.hpp"

#include <glcollide/error.hpp>

#include <algorithm>

namespace glcollide::engine {

std::vector<Stage> PipelinePlan::stages() const {
    if (frameStep) return {Stage::FrameStep};
    if (collisions) return responseModel(collision.response).stages(*this);
    return forceResponseStages();
}

/// Integration with (or without) a response that acts as forces or impulses on the pairs found.
std::vector<Stage> PipelinePlan::forceResponseStages() const {
    std::vector<Stage> s;
    if (nodeForce) s.push_back(Stage::NodeForce);
    if (springUpdate) s.push_back(Stage::SpringUpdate);
    // Discrete detection: contacts are found at the start of the substep.
    if (collisions && !continuous) s.push_back(Stage::CollisionDetection);
    // Implicit Euler: the springs' solve comes before the contact response, which then acts on
    // the solved velocities (and NodeUpdate adds it: Bridson et al. 2002's order).
    if (implicitSolve) s.push_back(Stage::ImplicitSolve);
    // Continuous detection: the velocities the integrator gives and the end positions x1 they
    // lead to, then the collision stages over [x0, x1].
    if (continuous) {
        s.push_back(Stage::NodePredict);
        s.push_back(Stage::CollisionDetection);
    }
    if (collisions) s.push_back(Stage::ContactResponse);
    if (nodeUpdate) s.push_back(Stage::NodeUpdate);
    return s;
}

/// The intersection-free response's substep (decision 0024): the forces and the solve give v and
/// NodePredict the step x1 they lead to; the contact response, iterated, acts on the pairs the last
/// substep's swept detection found (they include every pair within the thickness at x0, whose
/// boxes lie inside the last substep's swept boxes) and ContactApply moves v and x1 after each
/// iteration; the detection runs over [x0, x1] with CCD; SafeStep cuts; the energy guard takes a
/// rise of the total energy back out; the checked x1 becomes the positions.
std::vector<Stage> PipelinePlan::safeStepStages() const {
    std::vector<Stage> s;
    if (nodeForce) s.push_back(Stage::NodeForce);
    if (springUpdate) s.push_back(Stage::SpringUpdate);
    // Under implicit Euler the velocity filters (the contacts' inelastic impulses and friction, the
    // ground's response) act on the start velocity, before the solve: a velocity changed after the
    // solve no longer solves its system, and doing so put energy into resting bodies (decision
    // 0024, "Velocity filters before the solve"). Under symplectic Euler they follow the step.
    if (implicitSolve) s.push_back(Stage::ContactIterations);
    if (implicitSolve) s.push_back(Stage::ImplicitSolve);
    // Each further Newton step: the last step's end x1 is detected (the contacts it brings into the
    // thickness join the feature-pair lists), then the system is solved again at x1. The engine
    // skips a step's four stages once the steps have converged (ImplicitParams::newtonMoveTolerance)
    // or the substep recovers from an intersecting start.
    for (int k = 1; implicitSolve && implicitContacts && k < implicitParams.newtonSteps; ++k) {
        s.insert(s.end(), {Stage::NewtonPredict, Stage::NewtonDetection, Stage::ImplicitNewton});
        if (lineSearch) s.push_back(Stage::NewtonLineSearch);
    }
    s.push_back(Stage::NodePredict);
    // Recovery from an intersecting start pushes after the step, as under symplectic Euler (the
    // solve's penalty, with sides from x0, does not separate a tangled start).
    s.push_back(implicitSolve ? Stage::RecoveryIterations : Stage::ContactIterations);
    s.insert(s.end(), {Stage::CollisionDetection, Stage::SafeStep});
    if (energyGuard) s.push_back(Stage::EnergyGuard);
    // Intersections deeper than the thickness: no contact reaches them, and the CCD leaves their
    // pairs out; the pairs that intersect at x0 push x1 apart, after the guard (which would take the
    // push back out as a rise of the springs' energy) and unchecked by the CCD, like every tangled node.
    s.push_back(Stage::Untangle);
    s.push_back(Stage::Commit);
    return s;
}

std::vector<passes::PassId> PipelinePlan::passIds() const {
    using passes::PassId;
    std::vector<PassId> p;
    for (Stage stage : stages()) {
        switch (stage) {
        case Stage::NodeForce:
            p.push_back(PassId::NodeForce);
            break;
        case Stage::SpringUpdate:
            p.push_back(PassId::SpringUpdate);
            break;
        case Stage::NodePredict:
        case Stage::NewtonPredict:
            p.push_back(PassId::NodePredict);
            break;
        case Stage::CollisionDetection:
        case Stage::NewtonDetection:
            // The broad phase's passes come from its factory entry; TriTri tests its candidates;
            // FeaturePairs expands them into the feature pairs ContactResponse reads. Radial
            // culling, when the scene asks for it, runs first (decision 0025).
            if (collision.culling == Culling::Radial) p.push_back(PassId::RadialCulling);
            for (PassId id : passes::broadPhasePasses(collision.broadPhase)) p.push_back(id);
            p.push_back(PassId::TriTri);
            p.push_back(PassId::FeaturePairs);
            if (continuous) p.push_back(PassId::Ccd);
            break;
        case Stage::ImplicitSolve:
            p.push_back(PassId::ImplicitSolve);
            break;
        case Stage::ImplicitNewton:
            break; // ImplicitSolve's pass again, timed as its
        case Stage::NewtonLineSearch:
            p.push_back(PassId::NewtonLineSearch);
            break;
        case Stage::ContactResponse:
            p.push_back(PassId::ContactResponse);
            break;
        case Stage::SafeStep:
            p.push_back(PassId::SafeStep);
            break;
        case Stage::EnergyGuard:
            p.push_back(PassId::EnergyGuard);
            break;
        case Stage::Untangle:
            p.push_back(PassId::Untangle);
            break;
        case Stage::Commit:
            break; // a buffer copy: no pass of its own
        case Stage::ContactIterations:
        case Stage::RecoveryIterations:
            p.push_back(PassId::ContactResponse);
            p.push_back(PassId::ContactApply);
            break;
        case Stage::NodeUpdate:
            p.push_back(PassId::NodeUpdate);
            break;
        case Stage::FrameStep:
            p.push_back(PassId::FrameStep);
            break;
        }
    }
    // A pass that runs twice in a substep (NodePredict of a Newton step) is listed once.
    std::vector<PassId> unique;
    for (PassId id : p)
        if (std::find(unique.begin(), unique.end(), id) == unique.end()) unique.push_back(id);
    return unique;
}

std::vector<std::string> PipelinePlan::passes() const {
    std::vector<std::string> names;
    for (passes::PassId id : passIds()) names.emplace_back(passes::passName(id));
    return names;
}

std::vector<passes::BufferId> PipelinePlan::bufferIds() const {
    using passes::BufferId;
    std::vector<BufferId> b;
    // Without NodeUpdate nothing moves: a scene of static bodies needs no buffer of its own.
    if (!nodeUpdate) return b;
    b = {BufferId::Positions, BufferId::Velocities, BufferId::Faces};
    if (nodeForce || springUpdate) b.push_back(BufferId::Forces); // FrameStep: the same as theirs
    if (springs) b.push_back(BufferId::Springs);
    // Without springs the solver still reads the (empty) row lengths.
    if (springs || implicitSolve) b.push_back(BufferId::NodeSpringOffsets);
    if (springs) b.push_back(BufferId::NodeSpringList);
    if (springs || implicitSolve) b.push_back(BufferId::HeavyNodes);
    // NodeForce, SpringUpdate, FrameStep or ImplicitSetup gathers the faces' wind drag.
    if (nodeForceParams.wind) {
        b.push_back(BufferId::NodeFaceOffsets);
        b.push_back(BufferId::NodeFaceList);
    }
    if (collisions) b.push_back(BufferId::ContactForces);
    if (nodeUpdateParams.checkFinite) b.push_back(BufferId::Health);
    if (continuous) b.push_back(BufferId::PredictedPositions);
    return b;
}

std::vector<std::string> PipelinePlan::buffers() const {
    std::vector<std::string> labels;
    for (passes::BufferId id : bufferIds()) labels.emplace_back(passes::bufferLabel(id));
    return labels;
}

int automaticResponseIterations(Integrator integrator) {
    // Under symplectic Euler the iterations are the contacts' only support: 4 let a pile of tet
    // balls sink until the safe step froze it in mid-air (decision 0024, "Response iterations");
    // before an implicit solve they only stop approaches, and the solve holds the contacts.
    return integrator == Integrator::ImplicitEuler ? 4 : 8;
}

/// The intersection-free response's plan (decision 0024): the safe step, contacts and the ground in
/// the implicit solve, the energy guard.
void planSafeStep(const Scene& scene, PipelinePlan& plan) {
    plan.safeStep = plan.continuous;
    if (!plan.safeStep) return; // the scene validation refuses discrete detection with it
    plan.implicitContacts = plan.implicitSolve;
    plan.responseIterations = scene.collision.responseIterations > 0
                                  ? scene.collision.responseIterations
                                  : automaticResponseIterations(scene.time.integrator);
    // Automatic Newton steps with the contacts in the solve: 2, so that the contacts the first
    // step brings into the thickness act in the solve (decision 0024, "Newton steps").
    if (plan.implicitSolve && scene.time.solver.newtonSteps == 0) plan.implicitParams.newtonSteps = 2;
    // Steps after the second only while the last one moved a node by a part of the thickness.
    plan.implicitParams.newtonMoveTolerance = scene.time.solver.newtonTolerance * plan.contact.thickness;
    // Approaching pairs within the margin beyond the thickness enter the solve with stiffness and
    // no force (decision 0024, "Approaching pairs in the solve").
    plan.contact.solveMargin =
        plan.implicitSolve ? scene.time.solver.contactMargin * plan.contact.thickness : 0.0;
    const NodeForceParams& nf = plan.nodeForceParams;
    const NodeUpdateParams& nu = plan.nodeUpdateParams;
    // x1 is the whole step with the ground (SafeStep then commits it; there is no NodeUpdate):
    // NodePredict applies the forces, ContactApply each response iteration's contact forces.
    NodeUpdateParams& np = plan.nodePredictParams;
    np.ground = nu.ground;
    np.groundHeight = nu.groundHeight;
    np.restitution = nu.restitution;
    np.friction = nu.friction;
    np.groundBand = nu.ground ? plan.contact.thickness : 0.0; // SafeStep cuts ground crossings
    // Under implicit Euler the ground's and the contacts' velocity responses run before the solve
    // (ContactIterations on the start velocity), inelastic only: the penalties are in the matrix.
    np.bandResponse = !plan.implicitSolve;
    if (plan.implicitSolve) plan.contact.repulsion = false;
    // Their friction stops the velocity the solve will leave, predicted from the forces at the start
    // (no creep while sticking): the explicit force stage runs for it, before the filter.
    if (plan.implicitSolve) {
        const NodeForceParams& f = plan.nodeForceParams;
        const bool external = f.gravity || f.damping || f.wind;
        plan.springUpdate = plan.springs;
        plan.nodeForce = external && !plan.springUpdate;
        plan.contact.predictedForces = plan.springUpdate || plan.nodeForce;
    }
    // The ground's friction predicts gravity alone (node_update.comp has no room for the forces).
    const glm::dvec3 predicted =
        plan.implicitSolve && plan.nodeForceParams.gravity ? scene.gravity : glm::dvec3(0.0);
    if (plan.implicitSolve && nu.ground) {
        // The ground in the solve's matrix, as stiff as a contact (decision 0024).
        ImplicitParams& ip = plan.implicitParams;
        ip.groundStiffness = plan.contact.stiffness;
        ip.groundHeight = nu.groundHeight;
        ip.groundBand = np.groundBand;
    }
    // The energy guard sums what the substep's forces derive from: gravity, the springs, the
    // contacts' and the ground's penalties (a closed scene: the scene refuses it with wind).
    plan.energyGuard = scene.collision.energyGuard && !nf.wind;
    passes::EnergyGuardParams& eg = plan.energyGuardParams;
    eg.gravity = nf.gravity ? scene.gravity : glm::dvec3(0.0);
    eg.springs = plan.springs;
    eg.contacts = true;
    eg.thickness = plan.contact.thickness;
    eg.stiffness = plan.contact.stiffness;
    eg.groundStiffness = plan.implicitParams.groundStiffness;
    eg.groundLevel = plan.implicitParams.groundHeight + plan.implicitParams.groundBand;
    // The line search's Φ: the same potentials plus inertia and the dampers' dissipation (a
    // potential only without wind; with wind the whole Newton step is taken).
    plan.lineSearch =
        plan.implicitSolve && plan.implicitParams.newtonSteps > 1 && scene.time.solver.lineSearch && !nf.wind;
    plan.lineSearchParams.potentials = eg;
    plan.lineSearchParams.airDamping = plan.implicitParams.airDamping;
    NodeUpdateParams& ca = plan.contactApplyParams;
    ca = np;
    ca.forces = false;
    ca.contacts = true;
    ca.bandResponse = true;
    ca.groundStiffness = plan.implicitParams.groundStiffness; // 0 under symplectic Euler
    ca.predictedAcceleration = predicted;
    ca.contactForceScale = nu.contactForceScale;
}

PipelinePlan planPipeline(const Scene& scene) {
    const EffectSet& fx = scene.effects;
    PipelinePlan plan;
    NodeForceParams& nf = plan.nodeForceParams;
    nf.gravity = fx.has(Effect::Gravity);
    nf.damping = fx.has(Effect::Damping);
    nf.wind = fx.has(Effect::Wind);
    nf.gravityAcceleration = scene.gravity;
    nf.dampingCoefficient = scene.damping;
    nf.windVelocity = scene.wind.velocity;
    nf.windDrag = scene.wind.drag;

    std::size_t nodes = 0;
    for (const Body& b : scene.bodies) nodes += b.positions.size();
    plan.nodeUpdate = nodes > 0;
    std::size_t faces = 0;
    for (const Body& b : scene.bodies) faces += b.faces.size();
    plan.betweenObjects = fx.has(Effect::Collisions);
    plan.selfCollisions = fx.has(Effect::SelfCollisions);
    plan.collisions = plan.nodeUpdate && faces > 0 && (plan.betweenObjects || plan.selfCollisions);
    plan.collision = scene.collision;
    plan.contact = contactParams(scene.collision);
    const bool external = nf.gravity || nf.damping || nf.wind;
    plan.springs = plan.nodeUpdate && fx.has(Effect::Springs);
    plan.springUpdate = plan.springs;
    // With springs, SpringUpdate adds the external force in its own dispatch (one fewer per substep).
    plan.nodeForce = plan.nodeUpdate && external && !plan.springUpdate;
    plan.springUpdateParams.external = nf;

    NodeUpdateParams& nu = plan.nodeUpdateParams;
    nu.forces = plan.nodeForce || plan.springUpdate;
    nu.contacts = plan.collisions;
    if (scene.time.integrator == Integrator::ImplicitEuler && plan.nodeUpdate) {
        plan.implicitSolve = true;
        ImplicitParams& ip = plan.implicitParams;
        ip.springs = plan.springs;
        ip.external = nf; // the setup dispatch adds the external force: no NodeForce pass
        ip.airDamping = nf.damping ? nf.dampingCoefficient : 0.0;
        ip.tolerance = scene.time.solver.tolerance;
        ip.maxIterations = scene.time.solver.maxIterations;
        // Above 1 only with intersection_free (validated); automatic: 1 here, planSafeStep raises it.
        ip.newtonSteps = std::max(1, scene.time.solver.newtonSteps);
        plan.springUpdate = false; // the solver gathers the springs itself
        plan.nodeForce = false;
        nu.forces = false; // v is the solve's; NodeUpdate adds the contact forces (if any) and moves x
    }
    plan.continuous = plan.collisions && scene.collision.detection == Detection::Continuous;
    if (plan.continuous) {
        // NodePredict applies the forces (v += h·M⁻¹f; nothing under implicit Euler, whose solve
        // set v) and NodeUpdate only adds the contact forces and moves x.
        plan.nodePredictParams = nu;
        plan.nodePredictParams.contacts = false; // NodeUpdate adds them after the response
        nu.forces = false;
    }
    nu.contactForceScale = plan.contact.forceScale;
    nu.ground = fx.has(Effect::Ground);
    nu.groundHeight = scene.ground.height;
    nu.restitution = scene.ground.restitution;
    nu.friction = scene.ground.friction;
    if (plan.collisions) responseModel(scene.collision.response).plan(scene, plan);
    return plan;
}

} // namespace glcollide::engine
