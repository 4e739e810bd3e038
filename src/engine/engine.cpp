#include <glcollide/engine.hpp>

#include "core/gpu_layout.hpp"
#include "cpu/contact_twin.hpp"
#include "cpu/dynamics_twin.hpp"
#include "cpu/stability.hpp"
#include "engine/node_pull.hpp"
#include "engine/pipeline_plan.hpp"
#include "engine/response_model.hpp"
#include "engine/robust_self_check.hpp"
#include "gl/debug_output.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/host_state.hpp"
#include "gl/program.hpp"
#include "gl/setup_stats_sink.hpp"
#include "model/flat_model.hpp"
#include "passes/collision_detection.hpp"
#include "passes/contact_response.hpp"
#include "passes/dynamics_passes.hpp"
#include "passes/implicit_solver.hpp"
#include "passes/row_layout.hpp"
#include "passes/energy_guard.hpp"
#include "passes/contact_impact.hpp"
#include "passes/ground_impact.hpp"
#include "passes/start_velocities.hpp"
#include "passes/safe_step.hpp"
#include "passes/untangle.hpp"

#include <glcollide/error.hpp>
#include <glcollide/gl_info.hpp>

#include <epoxy/gl.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace glcollide {
namespace {

std::vector<glm::vec4> packNodes(const std::vector<glm::dvec3>& xyz, const std::vector<double>* w) {
    std::vector<glm::vec4> out(xyz.size());
    for (std::size_t i = 0; i < xyz.size(); ++i)
        out[i] = glm::vec4(glm::vec3(xyz[i]), w ? static_cast<float>((*w)[i]) : 0.0f);
    return out;
}

std::vector<glm::dvec3> unpackNodes(const gl::Buffer& buffer, std::uint32_t count) {
    std::vector<glm::vec4> raw(count);
    buffer.download(0, raw.size() * sizeof(glm::vec4), raw.data());
    std::vector<glm::dvec3> out(count);
    for (std::size_t i = 0; i < count; ++i) out[i] = glm::dvec3(glm::vec3(raw[i]));
    return out;
}

} // namespace

struct Engine::Impl {
    // First member, so it is destroyed last: deleting the GL objects still reports to it.
    std::unique_ptr<gl::DebugOutputScope> debug;
    gl::HostStateGuard::Features glFeatures;
    Scene scene;
    EngineOptions options;
    model::FlatModel model;
    engine::PipelinePlan plan;
    SubstepInfo substeps;
    std::vector<std::string> warnings;
    passes::DeviceBuffers buffers;
    std::optional<passes::NodeForcePass> nodeForce;
    std::optional<passes::SpringUpdatePass> springUpdate;
    std::optional<passes::NodeUpdatePass> nodeUpdate;
    std::optional<passes::NodePredictPass> nodePredict;
    std::optional<passes::SafeStepPass> safeStep;
    // With SafeStep, when the ground has a restitution (decision 0024, "Restitution at any step").
    std::optional<passes::GroundImpactPass> groundImpact;
    // With SafeStep, when contacts between bodies have a restitution (decision 0024, "Restitution
    // between bodies").
    std::optional<passes::ContactImpactPass> contactImpact;
    // The velocities at the start of the substep, for either impact pass.
    std::optional<passes::StartVelocities> startVelocities;
    std::optional<passes::EnergyGuardPass> energyGuard;
    std::optional<passes::UntanglePass> untangle;
    std::optional<passes::NewtonLineSearchPass> lineSearch;
    std::uint64_t tangledSubsteps = 0;    ///< CollisionStats::substepsUntilIntersectionFree
    bool reachedIntersectionFree = false; ///< CollisionStats::reachedIntersectionFree
    bool radialPremise = false; ///< radial culling: this substep starts intersection-free (decision 0025)
    bool startChecked = false;  ///< checkStartFree() has run
    std::optional<passes::ContactApplyPass> contactApply;
    std::optional<passes::ImplicitSolverPass> implicitSolve;
    std::optional<passes::FrameStepPass> frameStep;
    FrameStepParams frameStepParams;
    std::optional<passes::CollisionDetection> collision;
    std::optional<passes::ContactResponsePass> contact;
    std::vector<engine::Stage> stages;   ///< what a substep runs, in order (PipelinePlan::stages)
    std::vector<passes::PassId> passIds; ///< the substep's passes in order; stats.passes follows it
    std::vector<std::string> passNames;
    gl::GpuTimer timer{passes::kPassCount}; // one section per pass: passes::passIndex(id)
    StepStats stats;
    SetupStats setup;
    std::vector<std::uint32_t> heavyNodes; ///< nodes with more than kHeavyRow springs
    gl::Buffer frameStamp;                 ///< checkFrameCompleted's word (made on first use)

    // The host's pull (Engine::setPull); its pass is built at the first call.
    std::optional<NodePull> pull;
    std::optional<engine::NodePullPass> pullPass;

    void chooseSubsteps();
    gl::Buffer makeBuffer(passes::BufferId id);
    void allocate();
    void makePass(engine::Stage stage);
    /// This substep takes no further Newton step: its start intersects (recovery, decision 0024)...
    bool newtonRecovering = false;
    /// ... or the last step converged: it moved no node by more than
    /// ImplicitParams::newtonMoveTolerance, or kept none of its change.
    bool newtonConverged = false;
    [[nodiscard]] bool newtonDone() const { return newtonRecovering || newtonConverged; }
    std::uint32_t newtonStepsSkipped = 0; ///< further Newton steps not taken this frame (converged)
    /// The last detection found intersecting pairs at its start (recovery): the contact iterations
    /// push (ContactParams::repulsion) even where the plan has them inelastic only.
    bool lastStartIntersected = false;
    void substep(int index, bool lastOfFrame);
    // Frame bookkeeping, shared by step() and stepSubstep().
    std::uint64_t frameDispatchesBefore = 0;
    double frameWallMilliseconds = 0.0; ///< summed over the frame's calls
    void beginFrame();
    void checkHostMoves();
    void checkStartFree();
    void runSubstep(int s, int calls, bool readLastCounts);
    void endFrame();
    void checkFrameCompleted();
    void readHealth();
    void readSolverStats();
    void readEnergyGuard();
    void readContacts();
    [[nodiscard]] passes::ContactInputs contactInputs() const;
    struct ContactEnergy {
        double energy = 0.0, magnitude = 0.0;
        double ambiguity = 0.0; ///< cpu::ambiguousContactEnergy of the same pairs
    };
    [[nodiscard]] ContactEnergy contactEnergy() const;
    /// The response's contact rules (the CPU twin) on `pairs` at positions x, velocities v, sides from x.
    [[nodiscard]] std::vector<cpu::ContactGeometry> contactsAt(const std::vector<glm::dvec3>& x,
                                                               const std::vector<glm::dvec3>& v,
                                                               const cpu::FeaturePairList& pairs) const;
    /// cpu::ambiguousContactEnergy of `pairs` under the same rules as contactsAt.
    [[nodiscard]] double contactAmbiguityAt(const std::vector<glm::dvec3>& x,
                                            const std::vector<glm::dvec3>& v,
                                            const cpu::FeaturePairList& pairs) const;
    /// Calls use(params, input) with contactsAt's rules and input.
    template <typename F>
    auto withContactInput(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v, F&& use) const;
    void requireCollisions(const char* call) const;
    struct BoxTree;
    [[nodiscard]] BoxTree readBoxTree(const char* call) const;
    template <typename Pass, typename... Args> decltype(auto) run(const Pass& pass, Args&&... args);
};

void Engine::Impl::chooseSubsteps() {
    const double dt = scene.time.dt;
    const cpu::StabilityLimit limit = cpu::stableSubstep(model, plan.springs, plan.nodeForceParams, 0.9,
                                                         plan.collisions ? &plan.contact : nullptr);
    const int stable = cpu::substepsFor(dt, limit);
    substeps.stableSubsteps = stable;
    substeps.maxStableSubstep = limit.maxSubstep;
    substeps.limitingNode = limit.node;
    substeps.automatic = scene.time.substeps == 0;
    if (plan.implicitSolve) {
        // Backward Euler is stable for any step of the linear spring system it solves: the count
        // is the user's (auto: one substep per frame), never a stability requirement.
        substeps.substeps = substeps.automatic ? 1 : scene.time.substeps;
        if (plan.collisions && engine::responseModel(scene.collision.response).explicitUnderImplicitEuler()) {
            // Penalty contact forces enter the implicit step explicitly (docs/integration.md), so
            // they keep the explicit limit of a contact spring.
            const cpu::StabilityLimit contactLimit =
                cpu::stableSubstep(model, false, NodeForceParams{}, 0.9, &plan.contact);
            const int contactSubsteps = cpu::substepsFor(dt, contactLimit);
            if (substeps.substeps < contactSubsteps)
                warnings.push_back(
                    "/time/substeps " + std::to_string(substeps.substeps) +
                    " with implicit_euler: the penalty contact response is explicit and needs " +
                    std::to_string(contactSubsteps) +
                    " substeps per frame to stay stable; use \"response\": \"bridson\" "
                    "(velocity-level, stable at any step) or more substeps");
        }
    } else if (substeps.automatic) {
        if (stable > cpu::kMaxSubsteps) {
            std::ostringstream msg;
            msg << scene.sourcePath.string() << ": scene too stiff: explicit integration needs "
                << "substeps of at most " << limit.maxSubstep << " s (node " << limit.node << ": omega "
                << limit.omega << " 1/s), more than " << cpu::kMaxSubsteps << " per frame of " << dt
                << " s; lower the stiffness, raise the masses or "
                << "lower /time/dt";
            throw Error(msg.str());
        }
        substeps.substeps = stable;
    } else {
        substeps.substeps = scene.time.substeps;
        if (substeps.substeps < stable)
            warnings.push_back("/time/substeps " + std::to_string(substeps.substeps) +
                               " is below the stability limit of " + std::to_string(stable) +
                               " substeps per frame: the simulation may blow up");
    }
    substeps.substepLength = dt / substeps.substeps;
    plan.nodeUpdateParams.h = substeps.substepLength;
    plan.nodePredictParams.h = substeps.substepLength;
    plan.contactApplyParams.h = substeps.substepLength;
    // The intersection-free response's ground: an approach slower than what gravity adds in two
    // substeps is resting contact (no restitution; NodeUpdateParams::restingSpeed).
    const double restingSpeed =
        scene.effects.has(Effect::Gravity) ? 2.0 * glm::length(scene.gravity) * substeps.substepLength : 0.0;
    plan.nodePredictParams.restingSpeed = restingSpeed;
    plan.contactApplyParams.restingSpeed = restingSpeed;
    plan.implicitParams.h = substeps.substepLength;
    plan.contact.substep = substeps.substepLength;
    // Restitution between bodies: a bounce leaves the solve's contacts (ContactParams::leavingStep).
    if (plan.implicitContacts && scene.collision.restitution > 0.0) {
        plan.contact.leavingStep = substeps.substepLength;
        plan.contact.leavingSpeed = restingSpeed;
    }
}

/// The initial contents of the engine's buffer `id` (PipelinePlan::bufferIds decides which exist).
gl::Buffer Engine::Impl::makeBuffer(passes::BufferId id) {
    using passes::BufferId;
    const model::FlatModel& m = model;
    const char* label = passes::bufferLabel(id);
    // Without springs every row is empty (the implicit solver still reads the row lengths).
    const auto springRowOffsets = [&] {
        return plan.springs ? m.nodeSprings.offsets : std::vector<std::uint32_t>(m.nodeCount() + 1, 0u);
    };
    switch (id) {
    case BufferId::Positions:
    case BufferId::PredictedPositions: // x1 = x0 until the first NodePredict
        return gl::makeBuffer(label, packNodes(m.positions, &m.inverseMasses));
    case BufferId::Velocities:
        return gl::makeBuffer(label, packNodes(m.velocities, nullptr));
    case BufferId::Faces:
        return gl::makeBuffer(label, m.faceIndices);
    case BufferId::Forces:
        return gl::Buffer(label, m.nodeCount() * sizeof(glm::vec4));
    case BufferId::Springs: {
        std::vector<gpu::GpuSpring> springs;
        springs.reserve(m.springs.size());
        for (const model::FlatSpring& s : m.springs)
            springs.push_back({s.a, s.b, static_cast<float>(s.restLength), static_cast<float>(s.stiffness),
                               static_cast<float>(s.damping), 0u, 0u, 0u});
        for (std::size_t o = 0; o < m.objects.size(); ++o)
            for (std::uint32_t k = 0; k < m.objects[o].springCount; ++k)
                springs[m.objects[o].firstSpring + k].object = static_cast<std::uint32_t>(o);
        return gl::makeBuffer(label, springs);
    }
    case BufferId::NodeSpringOffsets:
        return gl::makeBuffer(label, springRowOffsets());
    case BufferId::NodeSpringList:
        return gl::makeBuffer(label, m.nodeSprings.items);
    case BufferId::HeavyNodes:
        heavyNodes = passes::heavyRowNodes(springRowOffsets());
        return gl::makeBuffer(label, heavyNodes);
    case BufferId::NodeFaceOffsets:
        return gl::makeBuffer(label, m.nodeFaces.offsets);
    case BufferId::NodeFaceList:
        return gl::makeBuffer(label, m.nodeFaces.items);
    case BufferId::ContactForces:
        return gl::makeBuffer(label, std::vector<glm::ivec4>(m.nodeCount(), glm::ivec4(0)));
    case BufferId::Health: {
        const gpu::GpuHealth none{GLC_HEALTH_NONE, GLC_HEALTH_NONE, 0u, 0u};
        return gl::Buffer(label, sizeof none, &none);
    }
    }
    throw Error("engine: no initial contents for buffer " + std::string(label));
}

void Engine::Impl::allocate() {
    buffers.nodeCount = static_cast<std::uint32_t>(model.nodeCount());
    buffers.faceCount = static_cast<std::uint32_t>(model.faceCount());
    buffers.springCount = static_cast<std::uint32_t>(model.springs.size());
    for (passes::BufferId id : plan.bufferIds()) buffers[id] = makeBuffer(id);
}

template <typename Pass, typename... Args>
decltype(auto) Engine::Impl::run(const Pass& pass, Args&&... args) {
    const gl::TimedSection section(options.gpuTiming ? &timer : nullptr, passes::passIndex(Pass::kId),
                                   Pass::kName);
    return pass.dispatch(buffers, std::forward<Args>(args)...);
}

Engine::Engine(const Scene& scene, const EngineOptions& options) {
    validateScene(scene);
    requireGl43();
    const gl::HostStateGuard::Features features = gl::HostStateGuard::probe();
    // Declared before `impl`: if construction throws, the objects made so far are deleted first,
    // then the host's bindings are restored.
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Compute, features);
    auto impl = std::make_unique<Impl>();
    Impl& d = *impl;
    d.glFeatures = features;
    // Every program the passes build from here on reports its cost to this engine alone.
    const gl::SetupStatsScope setupSink(&d.setup);
    if (options.debugCallback)
        d.debug = std::make_unique<gl::DebugOutputScope>(
            [callback = options.debugCallback](const gl::DebugMessage& m) {
                callback(GlDebugMessage{m.source, m.type, m.id, m.severity, m.text});
            },
            gl::DebugOutputScope::kEnableOutput | gl::DebugOutputScope::kSynchronous);
    const gl::DebugGroup group("glcollide::Engine::Engine");
    d.scene = scene;
    d.options = options;
    d.plan = engine::planPipeline(scene);
    d.model = model::flatten(scene);
    d.plan.nodeUpdateParams.checkFinite = options.checkFinite;
    // With the safe step there is no NodeUpdate: NodePredict checks the new state.
    if (d.plan.safeStep) d.plan.nodePredictParams.checkFinite = options.checkFinite;
    d.chooseSubsteps();
    d.allocate();
    d.plan.frameStep = options.frameStep && d.plan.nodeUpdate && !d.plan.implicitSolve &&
                       !d.plan.collisions && (d.plan.nodeForce || d.plan.springUpdate) &&
                       d.buffers.nodeCount <= kFrameStepMaxNodes && d.heavyNodes.empty();
    d.stages = d.plan.stages();
    // A stage that runs twice in a substep (the Newton step's NodePredict and CollisionDetection)
    // has one pass object.
    std::vector<engine::Stage> made;
    for (engine::Stage stage : d.stages)
        if (std::find(made.begin(), made.end(), stage) == made.end()) {
            d.makePass(stage);
            made.push_back(stage);
        }
    d.passIds = d.plan.passIds();
    for (passes::PassId id : d.passIds) d.passNames.emplace_back(passes::passName(id));
    d.stats.substeps = d.substeps.substeps;
    d.stats.collisions = d.plan.collisions;
    d.stats.continuous = d.plan.continuous;
    d.stats.safeStep = d.plan.safeStep;
    for (const std::string& name : d.passNames) d.stats.passes.push_back({name, 0.0});
    m_impl = std::move(impl);
}

/// Builds the pass object that runs `stage` (its programs; the collision detection's tables and
/// lists, and the robust self-check where robust precision is used).
void Engine::Impl::makePass(engine::Stage stage) {
    using engine::Stage;
    switch (stage) {
    case Stage::NodeForce:
        nodeForce.emplace(plan.nodeForceParams);
        break;
    case Stage::SpringUpdate:
        springUpdate.emplace(plan.springUpdateParams);
        break;
    case Stage::ImplicitSolve:
        implicitSolve.emplace(plan.implicitParams, buffers.nodeCount,
                              static_cast<std::uint32_t>(heavyNodes.size()), plan.implicitContacts);
        break;
    case Stage::ContactResponse:
        contact.emplace(plan.contact);
        break;
    case Stage::NodeUpdate:
        nodeUpdate.emplace(plan.nodeUpdateParams);
        break;
    case Stage::NodePredict:
        nodePredict.emplace(plan.nodePredictParams);
        break;
    case Stage::ContactIterations:
    case Stage::RecoveryIterations:
        contact.emplace(plan.contact);
        contactApply.emplace(plan.contactApplyParams);
        break;
    case Stage::SafeStep:
        safeStep.emplace(passes::SafeStepSettings{}, static_cast<std::uint32_t>(model.objects.size()),
                         plan.nodeUpdateParams.ground, plan.nodeUpdateParams.groundHeight);
        // The ground's restitution at any step (decision 0024): impacts within the substep.
        if (plan.nodePredictParams.ground && plan.nodePredictParams.restitution > 0.0) {
            const NodeUpdateParams& np = plan.nodePredictParams;
            GroundImpactParams gi;
            gi.bandTop = np.groundHeight + np.groundBand;
            gi.gravityY = scene.effects.has(Effect::Gravity) ? scene.gravity.y : 0.0;
            gi.restitution = np.restitution;
            gi.friction = np.friction;
            gi.restingSpeed = np.restingSpeed;
            groundImpact.emplace(buffers.nodeCount, gi);
        }
        if (scene.collision.restitution > 0.0) {
            ContactImpactParams ci;
            ci.restitution = scene.collision.restitution;
            ci.restingSpeed = plan.contactApplyParams.restingSpeed;
            ci.gravity = scene.effects.has(Effect::Gravity) ? glm::dvec3(scene.gravity) : glm::dvec3(0.0);
            ci.iterations = scene.collision.restitutionIterations;
            contactImpact.emplace(buffers.nodeCount, ci, plan.contact);
        }
        if (groundImpact || contactImpact) startVelocities.emplace(buffers.nodeCount);
        break;
    case Stage::EnergyGuard:
        energyGuard.emplace(plan.energyGuardParams, buffers.springCount);
        break;
    case Stage::NewtonLineSearch:
        lineSearch.emplace(plan.lineSearchParams, buffers.nodeCount, buffers.springCount);
        break;
    case Stage::Untangle:
        untangle.emplace(buffers.nodeCount, passes::kUntangleStepPerThickness * plan.contact.thickness);
        break;
    case Stage::Commit:
        break; // SafeStepPass::commit: a copy
    case Stage::NewtonPredict:
    case Stage::NewtonDetection:
    case Stage::ImplicitNewton:
        break; // the NodePredict, CollisionDetection and ImplicitSolve stages' passes
    case Stage::FrameStep: {
        FrameStepParams& f = frameStepParams;
        f.external = plan.nodeForceParams;
        f.springs = plan.springUpdate;
        f.update = plan.nodeUpdateParams;
        f.substeps = static_cast<std::uint32_t>(substeps.substeps);
        f.substepsPerDispatch =
            passes::frameStepSubstepsPerDispatch(buffers.nodeCount, f.springs ? &model.nodeSprings : nullptr,
                                                 f.external.wind ? &model.nodeFaces : nullptr);
        frameStep.emplace(f);
        break;
    }
    case Stage::CollisionDetection: {
        passes::CollisionConfig config;
        config.betweenObjects = plan.betweenObjects;
        config.selfCollisions = plan.selfCollisions;
        config.settings = plan.collision;
        config.substepsPerFrame = static_cast<std::uint32_t>(substeps.substeps);
        if (plan.collision.culling == Culling::Radial) {
            passes::RadialObserverSettings observers{plan.collision.ghostMaxPerimeter,
                                                     plan.collision.observers,
                                                     plan.collision.clusterMaxAngle,
                                                     plan.collision.clusterMaxFaces,
                                                     {}};
            for (const Body& body : scene.bodies) {
                observers.objectObservers.push_back(body.observer);
                observers.objectObserverEnds.push_back(body.observerEnd);
                observers.objectSkeletons.push_back(body.skeleton);
            }
            config.radial = passes::radialCullingConfig(model, observers);
        }
        collision.emplace(config, model);
        // Robust precision promises the oracle's answers; check that this device delivers them
        // before relying on it (once per device, driver and shader; docs/narrow-phase.md).
        if (plan.collision.precision == TriTriPrecision::Robust) {
            setup.robustSelfCheck =
                engine::runRobustSelfCheck(engine::effectiveSelfCheckMode(options.robustSelfCheck));
            if (!setup.robustSelfCheck.message.empty()) warnings.push_back(setup.robustSelfCheck.message);
        }
        break;
    }
    }
}

Engine::~Engine() {
    if (!m_impl) return; // moved from: no GL call, so no context needed
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Teardown, m_impl->glFeatures);
    m_impl.reset();
}

Engine::Engine(Engine&&) noexcept = default;

Engine& Engine::operator=(Engine&& other) noexcept {
    if (this != &other) {
        if (m_impl) {
            const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Teardown, m_impl->glFeatures);
            m_impl.reset();
        }
        m_impl = std::move(other.m_impl);
    }
    return *this;
}

namespace {
/// Folds one substep's collision counts into the frame's statistics: most are the last
/// substep's, the maximum, growths and rebuilds accumulate (the frame resets them).
void addSubstepCounts(const passes::CollisionCounts& counts, CollisionStats& c) {
    c.boxPairs = counts.boxPairs;
    c.candidatePairs = counts.candidates;
    c.intersectingPairs = counts.intersections;
    c.maxIntersectingPairs = std::max(c.maxIntersectingPairs, counts.intersections);
    c.undecidedPairs = counts.undecided;
    c.exactFallbacks = counts.exactFallbacks;
    c.listGrowths += counts.reruns;
    c.vertexFacePairs = counts.vertexFacePairs;
    c.edgeEdgePairs = counts.edgeEdgePairs;
    c.vertexFacePairsWithoutOwnership = counts.vertexFacePairsWithoutOwnership;
    c.edgeEdgePairsWithoutOwnership = counts.edgeEdgePairsWithoutOwnership;
    c.bvhNodeVisits = counts.bvhNodeVisits;
    c.bvhRebuilds += counts.bvhRebuilt ? 1u : 0u;
    c.bvhRounds = counts.bvhRounds;
    c.ccdVertexFaceHits = counts.ccdVertexFaceHits;
    c.ccdEdgeEdgeHits = counts.ccdEdgeEdgeHits;
    c.ccdCapped = counts.ccdCapped;
    c.ccdBoxes = counts.ccdBoxes;
    c.ccdEarliestToi = std::min(c.ccdEarliestToi, counts.ccdEarliestToi);
    c.ccdCappedInFrame += counts.ccdCapped;
    c.substepsWithIntersections += counts.intersections > 0 ? 1u : 0u;
    c.ccdTangledPairs = counts.ccdTangled;
    c.radialObservedFaces = counts.radialObserved;
    c.radialGhostFaces = counts.radialGhostFaces;
    if (counts.radialOn) {
        c.radialSubsteps += 1;
        c.radialNonPositiveFaces = counts.radialNonPositive;
        c.radialFreeFaces = counts.radialFree;
        c.radialViolatedSurfaces = counts.radialViolated;
        c.radialSubstepsViolated += counts.radialViolated > 0 ? 1u : 0u;
        c.radialCulledTriTri = counts.radialCulledTriTri;
        c.radialCulledCcd = counts.radialCulledCcd;
        c.radialCulledTriTriInFrame += counts.radialCulledTriTri;
        c.radialCulledCcdInFrame += counts.radialCulledCcd;
    }
}

/// Recovery from intersecting input: counts the substeps that began with intersecting pairs until
/// the first that began without (kept across frames in `c`'s engine-wide fields).
void addRecoveryCounts(const passes::CollisionCounts& counts, std::uint64_t& tangledSubsteps, bool& reached) {
    if (reached) return;
    if (counts.intersections == 0)
        reached = true;
    else
        ++tangledSubsteps;
}

/// Folds one substep's safe step into the frame's statistics.
void addSafeStepCounts(const passes::SafeStepCounts& counts, CollisionStats& c) {
    c.safeStepSubsteps += counts.rounds > 0 ? 1u : 0u;
    c.safeStepCuts += counts.cuts;
    c.safeStepMaxRounds = std::max(c.safeStepMaxRounds, counts.rounds);
    c.safeStepFrozeAll += counts.frozeAll ? 1u : 0u;
    c.safeStepGroundCrossings += counts.groundCrossings;
}
} // namespace

/// One substep: the plan's stages in the plan's order (PipelinePlan::stages states it).
void Engine::Impl::substep(int index, bool lastOfFrame) {
    using engine::Stage;
    if (startVelocities) startVelocities->record(buffers);
    for (Stage stage : stages) {
        switch (stage) {
        case Stage::NodeForce:
            run(*nodeForce, plan.nodeForceParams);
            break;
        case Stage::SpringUpdate:
            run(*springUpdate, plan.springUpdateParams);
            break;
        case Stage::CollisionDetection: {
            // Radial culling's premise: this substep starts intersection-free. Known when the
            // last detection found no intersecting pair at its start (its answers are exact,
            // culled or not) and the intersection-free response, which keeps a free start free,
            // made this start — not the host (checked at the frame's start, Engine::step).
            collision->setRadialCulling(radialPremise);
            const passes::CollisionCounts counts =
                collision->detect(buffers, options.gpuTiming ? &timer : nullptr);
            radialPremise = counts.intersections == 0;
            lastStartIntersected = counts.intersections > 0;
            addSubstepCounts(counts, stats.collision);
            addRecoveryCounts(counts, tangledSubsteps, reachedIntersectionFree);
            stats.collision.substepsUntilIntersectionFree = tangledSubsteps;
            stats.collision.reachedIntersectionFree = reachedIntersectionFree;
            break;
        }
        case Stage::ImplicitSolve:
            newtonRecovering = newtonConverged = false;
            if (plan.implicitContacts) {
                // The contacts of the last substep's feature pairs at x0 (decision 0024); the
                // first substep has none yet.
                ContactParams params = plan.contact;
                if (!params.sidesFromPrevious) params.substep = 0.0; // sides from x0 itself
                const passes::ImplicitContacts contacts{contactInputs(), params};
                run(*implicitSolve, plan.implicitParams, &contacts);
                // The frame's contact count is the solve's: the velocity filter before it counts
                // only the contacts it acts on (approaching, or with friction).
                if (lastOfFrame) stats.collision.contacts = implicitSolve->contactCount();
            } else {
                run(*implicitSolve, plan.implicitParams);
            }
            break;
        case Stage::NewtonPredict:
            if (newtonDone()) break;
            run(*nodePredict, plan.nodePredictParams, static_cast<std::uint32_t>(index));
            break;
        case Stage::NewtonDetection:
            if (newtonDone()) break;
            // The same detection over [x0, x1] for the Newton step's contacts; the substep's
            // counts (intersections at x0, CCD) are the final detection's.
            collision->setRadialCulling(radialPremise);
            // Not while the start intersects (recovery, decision 0024): the penalty's force ends at
            // the band's edge, so a Newton step from a first step that pushed a pair out of the band
            // sees no force and cancels the push (two overlapping boxes never came apart). The
            // start is the same for every Newton step of the substep, so none is taken.
            newtonRecovering =
                collision->detect(buffers, options.gpuTiming ? &timer : nullptr).intersections > 0;
            break;
        case Stage::ImplicitNewton: {
            if (newtonDone()) break;
            // The contacts of this substep's detection at x1; sides from x1 − h·v1 = x0.
            ContactParams params = plan.contact;
            params.substep = substeps.substepLength;
            // The margin's approaching pairs are the first solve's only (decision 0024, "Approaching
            // pairs in the solve"): held at x1 too, a landing body hovered in the margin, out of
            // its friction's reach, and a node sliding past an edge was held back for good.
            params.solveMargin = 0.0;
            const passes::ImplicitContacts contacts{contactInputs(), params};
            const gl::TimedSection section(options.gpuTiming ? &timer : nullptr,
                                           passes::passIndex(passes::ImplicitSolverPass::kId),
                                           passes::ImplicitSolverPass::kName);
            implicitSolve->dispatchNewton(buffers, plan.implicitParams, contacts);
            break;
        }
        case Stage::NewtonLineSearch: {
            if (newtonDone()) {
                newtonStepsSkipped += newtonConverged ? 1u : 0u; // once per step of the plan
                break;
            }
            const passes::ContactInputs inputs = contactInputs();
            const gl::TimedSection section(options.gpuTiming ? &timer : nullptr,
                                           passes::passIndex(passes::NewtonLineSearchPass::kId),
                                           passes::NewtonLineSearchPass::kName);
            const passes::LineSearchStep kept =
                lineSearch->dispatch(buffers, &inputs, implicitSolve->startVelocities(),
                                     implicitSolve->newtonStart(), plan.implicitParams.h);
            // Converged (decision 0024, "Newton steps until converged"): a step that moved no node
            // by more than the tolerance leaves the next step's contacts and system nearly this
            // one's; a step that kept none of its change would be solved again unchanged.
            newtonConverged =
                kept.fraction == 0.0f || kept.largestMove <= plan.implicitParams.newtonMoveTolerance;
            break;
        }
        case Stage::ContactResponse:
            run(*contact, contactInputs(), plan.contact);
            if (lastOfFrame) readContacts();
            break;
        case Stage::ContactIterations:
        case Stage::RecoveryIterations: {
            // Recovery (decision 0024): while the last detection found intersecting pairs, the
            // iterations after an implicit solve push (Bridson's repulsion) as under symplectic
            // Euler: the solve's penalty, with sides from x0, does not separate a tangled start.
            ContactParams params = plan.contact;
            if (stage == Stage::RecoveryIterations) {
                if (!lastStartIntersected) break;
                params.repulsion = true;
            }
            NodeUpdateParams apply = plan.contactApplyParams;
            for (int k = 0; k < plan.responseIterations; ++k) {
                // Before the solve the filter's friction (the contacts' and the ground's) acts in
                // the first iteration only: it has the whole substep's Coulomb budget, and the later
                // iterations, which still see every resting contact, would spend it again (four
                // held a block on a 35° incline at μ = 0.4).
                if (k == 1 && !params.repulsion) params.friction = apply.friction = 0.0;
                run(*contact, contactInputs(), params);
                // The contacts, not their iterations; with contacts in the solve, the solve's.
                if (lastOfFrame && k == 0 && !plan.implicitContacts) readContacts();
                run(*contactApply, apply, static_cast<std::uint32_t>(index));
            }
            break;
        }
        case Stage::NodePredict:
            run(*nodePredict, plan.nodePredictParams, static_cast<std::uint32_t>(index));
            break;
        case Stage::SafeStep: {
            const passes::CollisionCounts& found = collision->lastCounts();
            addSafeStepCounts(run(*safeStep, *collision, substeps.substepLength,
                                  found.ccdVertexFaceHits + found.ccdEdgeEdgeHits),
                              stats.collision);
            if (groundImpact) run(*groundImpact, startVelocities->buffer());
            if (contactImpact) run(*contactImpact, contactInputs(), startVelocities->buffer());
            break;
        }
        case Stage::EnergyGuard: {
            const passes::ContactInputs inputs = contactInputs();
            run(*energyGuard, &inputs, *collision);
            break;
        }
        case Stage::Untangle: {
            // Only while this substep's start intersects (the detection above found pairs at x0).
            if (!lastStartIntersected) break;
            const passes::UntangleCounts counts = run(*untangle, *collision);
            ++stats.collision.untangleSubsteps;
            stats.collision.untangledNodes += counts.movedNodes;
            stats.collision.untangleUnresolvedPairs += counts.unresolvedPairs;
            break;
        }
        case Stage::Commit:
            passes::SafeStepPass::commit(buffers);
            break;
        case Stage::NodeUpdate:
            run(*nodeUpdate, plan.nodeUpdateParams, static_cast<std::uint32_t>(index));
            break;
        case Stage::FrameStep:
            run(*frameStep, frameStepParams);
            break; // every substep of the frame
        }
    }
}

void Engine::Impl::readEnergyGuard() {
    const passes::EnergyGuardCounts g = energyGuard->frameCounts();
    CollisionStats& c = stats.collision;
    c.energyGuard = true;
    c.energyGuardSubsteps = g.acted;
    c.energyGuardPulledBack = g.pulledBack;
    c.energyGuardBackToStart = g.backToStart;
    c.energyGuardRemoved = g.removed;
    c.energyGuardUnremoved = g.unremoved;
    c.energyGuardLargestRise = g.largestExcess;
    c.energyGuardTotal = g.total;
    c.energyGuardKinetic = g.kinetic;
    c.energyGuardContact = g.contact;
}

/// The collision detection's buffers that the contact passes read.
passes::ContactInputs Engine::Impl::contactInputs() const {
    return passes::ContactInputs{&collision->lists(), &collision->faceInfo(), &collision->objects(),
                                 &collision->tangled()};
}

/// The contacts the response found in the last substep (its count in the counter block, which
/// detect() clears).
void Engine::Impl::readContacts() {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    collision->counters().download(offsetof(gpu::GpuCollisionCounters, stats) +
                                       GLC_STAT_CONTACTS * sizeof(std::uint32_t),
                                   sizeof stats.collision.contacts, &stats.collision.contacts);
}

void Engine::Impl::readSolverStats() {
    SolverStats& s = stats.solver;
    s.implicit = implicitSolve.has_value();
    if (!implicitSolve) return;
    const passes::ImplicitSolverCounts c = implicitSolve->readStatistics();
    s.maxIterations = c.maxIterations;
    s.maxRelativeResidual = c.maxRelativeResidual;
    s.totalIterations = c.totalIterations;
    s.unconvergedSubsteps = c.unconvergedSubsteps;
    s.lineSearch = lineSearch.has_value();
    if (!lineSearch) return;
    const passes::LineSearchCounts l = lineSearch->frameCounts();
    s.lineSearchSteps = l.steps;
    s.lineSearchShortened = l.shortened;
    s.lineSearchRejected = l.rejected;
    s.newtonStepsSkipped = newtonStepsSkipped;
}

void Engine::Impl::checkFrameCompleted() {
    // A lost context (a device reset, a memory fault) executes nothing and reads back nothing, so
    // its frames would look simulated: on an H200 at bd8506c a 473K-face run went on with every
    // pass timed at 0 ms and the state frozen, and `run` printed success. The GPU writes the
    // frame's number after the frame's commands; a word never written fails the frame. Part of
    // EngineOptions::checkFinite, whose read waits for the frame anyway: without it, no sync.
    if (!options.checkFinite) return;
    constexpr std::uint32_t kNeverWritten = 0xffffffffu;
    const std::uint32_t expected = static_cast<std::uint32_t>(stats.frame % kNeverWritten);
    if (!frameStamp) frameStamp = gl::Buffer("frameStamp", sizeof expected);
    frameStamp.fill32(expected);
    std::uint32_t seen = kNeverWritten;
    frameStamp.download(0, sizeof seen, &seen);
    if (seen == expected) return;
    const GLenum error = glGetError(); // only now: the host's error flag is its own
    std::ostringstream msg;
    msg << "engine: the GPU did not complete frame " << stats.frame << " (a word written after the frame's "
        << "commands read back as " << seen << ", not " << expected << "; glGetError: 0x" << std::hex << error
        << "): the context was lost or the device was reset, so the state is not the simulation's";
    throw Error(msg.str());
}

void Engine::Impl::readHealth() {
    if (!buffers.health || stats.nonFinite.found) return;
    gpu::GpuHealth health{};
    buffers.health.download(0, sizeof health, &health); // issues GL_BUFFER_UPDATE_BARRIER_BIT
    if (health.badSubstep == GLC_HEALTH_NONE) return;
    NonFiniteReport& r = stats.nonFinite;
    r.found = true;
    r.frame = stats.frame;
    r.substep = static_cast<int>(health.badSubstep);
    r.globalNode = health.firstBadNode;
    for (std::size_t o = 0; o < model.objects.size(); ++o) {
        const model::ObjectRange& range = model.objects[o];
        if (health.firstBadNode >= range.firstNode &&
            health.firstBadNode - range.firstNode < range.nodeCount) {
            r.object = static_cast<std::uint32_t>(o);
            r.node = health.firstBadNode - range.firstNode;
        }
    }
}

/// A frame's start (step(), or the stepSubstep() that begins a frame).
void Engine::Impl::beginFrame() {
    if (options.gpuTiming) timer.beginFrame();
    stats.collision = {};
    if (implicitSolve) implicitSolve->resetStatistics();
    if (lineSearch) lineSearch->clearFrameCounts();
    newtonStepsSkipped = 0;
    frameDispatchesBefore = gl::dispatchCount();
    frameWallMilliseconds = 0.0;
    // The energy guard's start: the host may have moved nodes since the last frame.
    if (energyGuard) {
        const passes::ContactInputs inputs = contactInputs();
        energyGuard->clearFrameCounts();
        energyGuard->record(buffers, &inputs);
    }
}

/// Radial culling's premise against the host: a read-only check, so running it before any
/// substep (stepSubstep) changes nothing when the host moved no node.
void Engine::Impl::checkHostMoves() {
    if (collision && collision->radialCulling() && radialPremise &&
        collision->radialCulling()->hostMovedNodes(buffers))
        radialPremise = false; // the host moved nodes: the start is not known to be free
}

/// Radial culling's premise for the very first substep (decision 0025, "Culling from the first
/// substep"): nothing has checked the initial state yet, so without this the first substep could
/// not cull — and a large scene's first detection without culling can outgrow the lists (a
/// 81,920-face cloth ball thrown at 6 m/s needs 16.8M candidate pairs at one substep per frame, more
/// than llvmpipe's 128 MiB storage block). One detection of the start standing still (x1 = x0:
/// boxes without motion) decides with the exact TriTri whether any face pair intersects at x0; none
/// is the premise. It changes nothing else: NodePredict writes x1 again before the first substep's
/// detection, whose counts are the substep's, and the check's lists are emptied. Once, before
/// the first substep.
void Engine::Impl::checkStartFree() {
    if (startChecked) return;
    startChecked = true;
    if (!collision || !collision->radialCulling() || radialPremise) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::copyBufferData(buffers.positions, buffers.predictedPositions, buffers.positions.bytes());
    collision->setRadialCulling(false);
    radialPremise = collision->detect(buffers, nullptr).intersections == 0;
    // The first substep's solve and filters read the last detection's pairs: without culling there
    // was none before it, and culling changes nothing but time.
    collision->forgetLists();
    stats.collision.radialStartChecked = true;
    stats.collision.radialStartFree = radialPremise;
}

/// Substep `s` of the frame (of `calls` dispatch rounds: 1 under FrameStep), the host's pull first.
void Engine::Impl::runSubstep(int s, int calls, bool readLastCounts) {
    // The host's pull (setPull): its own pass before each substep, only while it is set.
    const double pullStep = frameStep ? scene.time.dt : substeps.substepLength;
    if (pull) {
        pullPass->dispatch(buffers, *pull, pullStep);
        // The pull does work on the scene, as a host's moves do: the energy guard's start
        // is the state after its kick, not a rise to take back out.
        if (energyGuard) {
            const passes::ContactInputs inputs = contactInputs();
            energyGuard->record(buffers, &inputs);
        }
    }
    substep(s, readLastCounts || s + 1 == calls);
}

/// A frame's end (step(), or the stepSubstep() that ends a frame).
void Engine::Impl::endFrame() {
    if (energyGuard) readEnergyGuard();
    stats.dispatchesPerSubstep =
        static_cast<double>(gl::dispatchCount() - frameDispatchesBefore) / substeps.substeps;
    stats.frame += 1;
    stats.substepInFrame = 0;
    stats.time = static_cast<double>(stats.frame) * scene.time.dt;
    checkFrameCompleted();
    readHealth();
    readSolverStats();
    if (options.gpuTiming) {
        const std::vector<double> ms = timer.resolveMilliseconds();
        for (std::size_t p = 0; p < passIds.size(); ++p)
            stats.passes[p].gpuMilliseconds = ms[passes::passIndex(passIds[p])];
    }
}

void Engine::step() {
    Impl& d = *m_impl;
    const auto start = std::chrono::steady_clock::now();
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Compute, d.glFeatures);
    // Host shader writes to the position buffer since the last call become visible to the passes.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    {
        gl::DebugGroup frame("glcollide::Engine::step");
        // Mid-frame (stepSubstep): the frame in progress is finished, its start already done.
        if (d.stats.substepInFrame == 0) d.beginFrame();
        d.checkHostMoves();
        d.checkStartFree();
        // FrameStep runs the frame's substeps in its one dispatch.
        const int calls = d.frameStep ? 1 : d.substeps.substeps;
        for (int s = d.stats.substepInFrame; s < calls; ++s) d.runSubstep(s, calls, false);
    }
    // A host draws positions as vertices and faces as indices right after step().
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                    GL_SHADER_STORAGE_BARRIER_BIT);
    d.endFrame();
    d.frameWallMilliseconds +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    d.stats.wallMilliseconds = d.frameWallMilliseconds;
}

void Engine::stepSubstep() {
    Impl& d = *m_impl;
    if (d.frameStep)
        throw Error("engine: stepSubstep() needs the per-substep passes, and EngineOptions::frameStep "
                    "runs all substeps of a frame in one dispatch; construct the engine with frameStep "
                    "off to step substeps");
    const auto start = std::chrono::steady_clock::now();
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Compute, d.glFeatures);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); // as in step(): host shader writes are seen
    {
        gl::DebugGroup group("glcollide::Engine::stepSubstep");
        if (d.stats.substepInFrame == 0) d.beginFrame();
        d.checkHostMoves();
        d.checkStartFree();
        // The contact count is read for every substep (a read, no state): lastStep() describes it.
        d.runSubstep(d.stats.substepInFrame, d.substeps.substeps, true);
    }
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                    GL_SHADER_STORAGE_BARRIER_BIT);
    d.stats.substepInFrame += 1;
    if (d.stats.substepInFrame == d.substeps.substeps) {
        d.endFrame();
    } else {
        d.stats.time = static_cast<double>(d.stats.frame) * d.scene.time.dt +
                       d.stats.substepInFrame * d.substeps.substepLength;
    }
    d.frameWallMilliseconds +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    d.stats.wallMilliseconds = d.frameWallMilliseconds;
}

const SetupStats& Engine::setupStats() const {
    return m_impl->setup;
}

void Engine::setPull(std::optional<NodePull> pull) {
    Impl& d = *m_impl;
    if (pull) {
        engine::validatePull(*pull, d.buffers.nodeCount);
        if (!d.pullPass) {
            const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Compute, d.glFeatures);
            d.pullPass.emplace();
        }
    }
    d.pull = pull;
}

const std::optional<NodePull>& Engine::pull() const {
    return m_impl->pull;
}

const StepStats& Engine::lastStep() const {
    return m_impl->stats;
}
std::vector<std::string> Engine::pipeline() const {
    return m_impl->passNames;
}
std::vector<std::string> Engine::allocatedBuffers() const {
    std::vector<std::string> labels = m_impl->buffers.allocatedLabels();
    if (m_impl->implicitSolve)
        for (std::string& l : m_impl->implicitSolve->allocatedLabels()) labels.push_back(std::move(l));
    if (m_impl->collision)
        for (std::string& l : m_impl->collision->allocatedLabels()) labels.push_back(std::move(l));
    return labels;
}

std::size_t Engine::allocatedBytes() const {
    return m_impl->buffers.allocatedBytes() + solverBytes() +
           (m_impl->collision ? m_impl->collision->allocatedBytes() : 0);
}

std::size_t Engine::solverBytes() const {
    return m_impl->implicitSolve ? m_impl->implicitSolve->allocatedBytes() : 0;
}

std::vector<std::array<std::uint32_t, 2>> Engine::readIntersectingPairs() const {
    if (!m_impl->collision) return {};
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, m_impl->glFeatures);
    return m_impl->collision->readIntersections();
}

std::vector<std::array<std::uint32_t, 2>> Engine::readCandidatePairs() const {
    if (!m_impl->collision) return {};
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, m_impl->glFeatures);
    return m_impl->collision->readCandidates();
}

std::vector<float> Engine::readTimesOfImpact() const {
    if (!m_impl->collision || !m_impl->collision->continuous()) return {};
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, m_impl->glFeatures);
    std::vector<float> toi(nodeCount());
    m_impl->collision->nodeToi().download(0, toi.size() * sizeof(float), toi.data());
    return toi;
}

CollisionStats Engine::detectCollisions() {
    CollisionStats c;
    if (!m_impl->collision) return c;
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Compute, m_impl->glFeatures);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); // as in step(): host shader writes are seen
    const gl::DebugGroup group("glcollide::Engine::detectCollisions");
    addSubstepCounts(m_impl->collision->detect(m_impl->buffers, nullptr), c);
    return c;
}

void Engine::Impl::requireCollisions(const char* call) const {
    if (!collision)
        throw Error(std::string("engine: ") + call +
                    " needs a scene with the collisions or self_collisions effect (\"" + scene.name +
                    "\" has neither): there is no collision detection to read");
}

FeaturePairs Engine::readFeaturePairs() const {
    m_impl->requireCollisions("readFeaturePairs()");
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, m_impl->glFeatures);
    FeaturePairs out;
    out.vertexFace = m_impl->collision->readVertexFacePairs();
    out.edgeEdge = m_impl->collision->readEdgeEdgePairs();
    return out;
}

std::vector<FeatureContact> Engine::readContacts() const {
    const Impl& d = *m_impl;
    d.requireCollisions("readContacts()");
    const FeaturePairs pairs = readFeaturePairs();
    const std::vector<glm::dvec3> x = readPositions(), v = readVelocities();
    std::vector<FeatureContact> out;
    // One list at a time, so each contact knows its kind (contactsAt keeps list order).
    for (const bool edgeEdge : {false, true}) {
        cpu::FeaturePairList one;
        (edgeEdge ? one.edgeEdge : one.vertexFace) = edgeEdge ? pairs.edgeEdge : pairs.vertexFace;
        for (const cpu::ContactGeometry& c : d.contactsAt(x, v, one))
            out.push_back(FeatureContact{edgeEdge, c.nodes, c.weights, c.normal, c.depth});
    }
    return out;
}

namespace {
/// The BVH's node depths (root 0), from its links (layout.glsl: node n < faces − 1 is internal with
/// children links[n].xy; the others are leaves).
std::vector<int> bvhDepths(const std::vector<std::array<std::uint32_t, 4>>& links, std::uint32_t faces) {
    std::vector<int> depth(links.size(), -1);
    if (links.empty()) return depth;
    std::vector<std::uint32_t> stack{0};
    depth[0] = 0;
    while (!stack.empty()) {
        const std::uint32_t n = stack.back();
        stack.pop_back();
        if (n + 1 >= faces) continue; // a leaf
        for (const std::uint32_t child : {links[n][0], links[n][1]}) {
            if (child >= links.size())
                throw Error("engine: the BVH's links read back corrupt (a child out of range)");
            depth[child] = depth[n] + 1;
            stack.push_back(child);
        }
    }
    return depth;
}

std::vector<BroadPhaseBox> toBoxes(const std::vector<gpu::GpuBox>& boxes) {
    std::vector<BroadPhaseBox> out;
    out.reserve(boxes.size());
    for (const gpu::GpuBox& b : boxes) out.push_back({glm::dvec3(b.lo), glm::dvec3(b.hi)});
    return out;
}
} // namespace

struct Engine::Impl::BoxTree {
    bool bvh = false;
    std::vector<gpu::GpuBox> boxes; ///< BVH: every node; octree: every leaf
    std::vector<int> depth;         ///< BVH: per node
    int maxDepth = 0;
};

Engine::Impl::BoxTree Engine::Impl::readBoxTree(const char* call) const {
    requireCollisions(call);
    BoxTree t;
    const gl::Buffer& bvhBoxes = collision->broadPhaseBuffer("bvhBoxes");
    const gl::Buffer& leafBoxes = collision->boxes();
    if (bvhBoxes) {
        t.bvh = true;
        const std::size_t nodes = bvhBoxes.bytes() / sizeof(gpu::GpuBox);
        t.boxes.resize(nodes);
        bvhBoxes.download(0, nodes * sizeof(gpu::GpuBox), t.boxes.data());
        std::vector<std::array<std::uint32_t, 4>> links(nodes);
        collision->broadPhaseBuffer("bvhLinks").download(0, nodes * sizeof links[0], links.data());
        t.depth = bvhDepths(links, buffers.faceCount);
        for (const int d : t.depth) t.maxDepth = std::max(t.maxDepth, d);
    } else if (leafBoxes) {
        const std::size_t count = collision->layout().boxCount;
        t.boxes.resize(count);
        leafBoxes.download(0, count * sizeof(gpu::GpuBox), t.boxes.data());
        t.maxDepth = collision->layout().depth;
    } else {
        throw Error(std::string("engine: ") + call + ": the broad phase \"" +
                    std::string(broadPhaseName(scene.collision.broadPhase)) +
                    "\" keeps no boxes (the BVH and the octree do)");
    }
    return t;
}

int Engine::broadPhaseDepth() const {
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, m_impl->glFeatures);
    return m_impl->readBoxTree("broadPhaseDepth()").maxDepth;
}

std::vector<BroadPhaseBox> Engine::readBroadPhaseBoxes(int depth) const {
    const Impl& d = *m_impl;
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, d.glFeatures);
    Impl::BoxTree t = d.readBoxTree("readBroadPhaseBoxes()");
    if (depth < 0 || depth > t.maxDepth)
        throw Error("engine: readBroadPhaseBoxes(" + std::to_string(depth) + "): the depth must be 0 .. " +
                    std::to_string(t.maxDepth) + " (broadPhaseDepth())");
    std::vector<gpu::GpuBox> picked;
    if (t.bvh) {
        // A cut: the nodes at this depth and the leaves above it.
        const std::uint32_t faces = d.buffers.faceCount;
        for (std::size_t n = 0; n < t.boxes.size(); ++n)
            if (t.depth[n] == depth || (t.depth[n] >= 0 && t.depth[n] < depth && n + 1 >= faces))
                picked.push_back(t.boxes[n]);
        return toBoxes(picked);
    }
    // Octree: leaf cell c of an object (x fastest, cellsPerAxis per axis) lies in cell
    // (x, y, z) >> shift of the level `depth`, shift = leaf depth − depth.
    const model::OctreeLayout& layout = d.collision->layout();
    const int shift = t.maxDepth - depth;
    const std::uint32_t n = layout.cellsPerAxis, m = n >> shift;
    for (std::size_t o = 0; o < layout.firstBox.size(); ++o) {
        std::vector<gpu::GpuBox> level(std::size_t{m} * m * m);
        for (gpu::GpuBox& b : level) { // empty: lo > hi
            b.lo = glm::vec4(std::numeric_limits<float>::infinity());
            b.hi = glm::vec4(-std::numeric_limits<float>::infinity());
        }
        for (std::uint32_t c = 0; c < layout.boxesPerObject; ++c) {
            const gpu::GpuBox& leaf = t.boxes[layout.firstBox[o] + c];
            if (leaf.lo.x > leaf.hi.x) continue; // an empty leaf
            const std::uint32_t x = (c % n) >> shift, y = (c / n % n) >> shift, z = (c / (n * n)) >> shift;
            gpu::GpuBox& b = level[x + m * (y + m * z)];
            b.lo = glm::min(b.lo, leaf.lo);
            b.hi = glm::max(b.hi, leaf.hi);
        }
        for (const gpu::GpuBox& b : level)
            if (b.lo.x <= b.hi.x) picked.push_back(b);
    }
    return toBoxes(picked);
}

std::vector<std::uint32_t> Engine::bodyFirstFaces() const {
    std::vector<std::uint32_t> first;
    for (const model::ObjectRange& o : m_impl->model.objects) first.push_back(o.firstFace);
    return first;
}
const SubstepInfo& Engine::substepInfo() const {
    return m_impl->substeps;
}
const std::vector<std::string>& Engine::warnings() const {
    return m_impl->warnings;
}
const Scene& Engine::scene() const {
    return m_impl->scene;
}
std::uint32_t Engine::nodeCount() const {
    return m_impl->buffers.nodeCount;
}
std::uint32_t Engine::faceCount() const {
    return m_impl->buffers.faceCount;
}
std::uint32_t Engine::springCount() const {
    return m_impl->buffers.springCount;
}

std::vector<std::uint32_t> Engine::bodyFirstNodes() const {
    std::vector<std::uint32_t> first;
    for (const model::ObjectRange& o : m_impl->model.objects) first.push_back(o.firstNode);
    return first;
}

std::vector<glm::dvec3> Engine::readPositions() const {
    if (!m_impl->buffers.positions) return m_impl->model.positions;
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, m_impl->glFeatures);
    return unpackNodes(m_impl->buffers.positions, nodeCount());
}

std::vector<glm::dvec3> Engine::readVelocities() const {
    if (!m_impl->buffers.velocities) return m_impl->model.velocities;
    const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, m_impl->glFeatures);
    return unpackNodes(m_impl->buffers.velocities, nodeCount());
}

EnergyReport Engine::energy() const {
    const Impl& d = *m_impl;
    const bool gravity = d.scene.effects.has(Effect::Gravity);
    const cpu::Energy e =
        cpu::energy(readPositions(), readVelocities(), d.model.masses, d.model.inverseMasses,
                    gravity ? &d.scene.gravity : nullptr, d.plan.springs ? &d.model.springs : nullptr);
    EnergyReport report{e.kinetic, e.gravitational + e.elastic, 0.0, 0.0, 0.0};
    if (d.plan.safeStep) {
        const gl::HostStateGuard guard(gl::HostStateGuard::Scope::Transfer, d.glFeatures);
        const Impl::ContactEnergy contact = d.contactEnergy();
        report.contact = contact.energy;
        report.contactAmbiguity = contact.ambiguity;
        const passes::AppendLists& lists = d.collision->lists();
        const std::uint64_t terms = std::uint64_t{d.buffers.nodeCount} +
                                    (d.plan.springs ? d.buffers.springCount : 0u) +
                                    lists.capacity(GLC_LIST_VERTEX_FACE) + lists.capacity(GLC_LIST_EDGE_EDGE);
        report.resolution =
            passes::EnergyGuardPass::resolutionFactor(terms) * (e.magnitude + contact.magnitude);
    }
    return report;
}

/// ½·k·depth² of every penalty contact at the current positions: the contact geometry of the
/// response's rules (cpu::contactGeometries) on the last detection's feature pairs, sides from the
/// positions themselves (decision 0024); and the ground's penalty under implicit Euler. With the
/// magnitude scale of those terms as energy_guard.comp adds them.
template <typename F>
auto Engine::Impl::withContactInput(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                    F&& use) const {
    std::vector<std::uint8_t> faceClosed(model.faceCount());
    const model::OctreeLayout& layout = collision->layout();
    for (std::size_t f = 0; f < faceClosed.size(); ++f) faceClosed[f] = layout.closed[layout.faceObject[f]];
    const std::vector<std::uint32_t> nodeObject = model::nodeObjects(model);
    cpu::ContactInput in;
    in.positions = &x;
    in.velocities = &v;
    in.faceIndices = &model.faceIndices;
    in.faceOwned = &layout.faceOwned;
    in.faceClosed = &faceClosed;
    in.inverseMasses = &model.inverseMasses;
    in.nodeObject = &nodeObject;
    in.faceObject = &layout.faceObject;
    ContactParams params = plan.contact;
    params.substep = 0.0; // sides from x
    return use(params, in);
}

std::vector<cpu::ContactGeometry> Engine::Impl::contactsAt(const std::vector<glm::dvec3>& x,
                                                           const std::vector<glm::dvec3>& v,
                                                           const cpu::FeaturePairList& pairs) const {
    return withContactInput(x, v, [&](const ContactParams& params, const cpu::ContactInput& in) {
        return cpu::contactGeometries(params, in, pairs);
    });
}

double Engine::Impl::contactAmbiguityAt(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                        const cpu::FeaturePairList& pairs) const {
    return withContactInput(x, v, [&](const ContactParams& params, const cpu::ContactInput& in) {
        return cpu::ambiguousContactEnergy(params, in, pairs);
    });
}

Engine::Impl::ContactEnergy Engine::Impl::contactEnergy() const {
    const std::vector<glm::dvec3> x = unpackNodes(buffers.positions, buffers.nodeCount);
    const std::vector<glm::dvec3> v = unpackNodes(buffers.velocities, buffers.nodeCount);
    cpu::FeaturePairList pairs;
    pairs.vertexFace = collision->readVertexFacePairs();
    pairs.edgeEdge = collision->readEdgeEdgePairs();
    const ContactParams& params = plan.contact;
    ContactEnergy out;
    for (const cpu::ContactGeometry& c : contactsAt(x, v, pairs)) {
        const double e = 0.5 * params.stiffness * c.depth * c.depth;
        out.energy += e;
        out.magnitude += e + params.stiffness * c.depth * (glm::length(x[c.nodes[0]]) + params.thickness);
    }
    out.ambiguity = contactAmbiguityAt(x, v, pairs);
    // The implicit solve's ground penalty below the ground's band (decision 0024).
    const ImplicitParams& ip = plan.implicitParams;
    if (ip.groundStiffness > 0.0)
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double depth = ip.groundHeight + ip.groundBand - x[i].y;
            if (depth > 0.0 && model.inverseMasses[i] > 0.0) {
                const double e = 0.5 * ip.groundStiffness * depth * depth;
                out.energy += e;
                out.magnitude += e + ip.groundStiffness * depth *
                                         (std::abs(x[i].y) + std::abs(ip.groundHeight + ip.groundBand));
            }
        }
    return out;
}

std::uint32_t Engine::positionBuffer() const {
    return m_impl->buffers.positions.name();
}
std::uint32_t Engine::faceIndexBuffer() const {
    return m_impl->buffers.faces.name();
}

} // namespace glcollide
