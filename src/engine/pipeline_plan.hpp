#pragma once
// Composes the pass list and the buffer set from a scene's effects, without touching GL, so
// "simulate only what the scene calls for" is decided in one place and testable on its own.

#include "core/contact_params.hpp"
#include "core/dynamics_params.hpp"
#include "passes/device_buffers.hpp"
#include "passes/energy_guard.hpp"
#include "passes/newton_line_search.hpp"
#include "passes/pass_id.hpp"

#include <glcollide/scene.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::engine {

/// One call the engine makes per substep, each on one pass object. The substep's order is written
/// once, in PipelinePlan::stages(); the engine runs the list and the pass list (timers,
/// statistics) is derived from it.
enum class Stage : std::uint8_t {
    NodeForce,          ///< external forces alone (scenes without springs)
    SpringUpdate,       ///< spring forces plus the external force
    NodePredict,        ///< continuous detection: v += h·M⁻¹f and the predicted end positions x1
    CollisionDetection, ///< broad phase, TriTri and FeaturePairs (their own PassIds)
    ImplicitSolve,      ///< implicit Euler: the springs' linear solve, v += Δv
    NewtonPredict,      ///< NodePredict of a further Newton step: x1 = x0 + h·v of the last step
    NewtonDetection,    ///< CollisionDetection of a Newton step's x1 (its counts are not the substep's)
    ImplicitNewton,     ///< implicit Euler: a further Newton step at x1 with the contacts found there
    NewtonLineSearch,   ///< implicit Euler: the fraction of that step that lowers the incremental potential
    ContactResponse,    ///< contact forces or impulses on the feature pairs
    SafeStep,           ///< intersection-free response: steps cut to before the first contact, committed
    EnergyGuard,        ///< intersection-free response: a rise of the total energy taken out of v or x1
    Untangle,           ///< intersection-free response: pairs intersecting at x0 push x1 apart (only
                        ///< while the start intersects; decision 0024, "Deep intersections")
    Commit,             ///< intersection-free response: the checked x1 becomes the positions
    ContactIterations,  ///< intersection-free response: (ContactResponse, ContactApply) × responseIterations
    RecoveryIterations, ///< intersection-free response under implicit Euler: ContactIterations with
                        ///< repulsion after the solve, only while the last start intersected
    NodeUpdate,         ///< velocities and positions, pins, ground
    FrameStep           ///< a whole frame of SpringUpdate + NodeUpdate in one dispatch (once per frame)
};

struct PipelinePlan {
    bool nodeForce = false;
    bool springs = false; ///< the springs effect: SpringUpdate or the implicit solver gathers them
    bool springUpdate = false;
    bool nodeUpdate = false;
    NodeForceParams nodeForceParams;
    SpringUpdateParams springUpdateParams;
    NodeUpdateParams nodeUpdateParams; ///< h is filled in once substeps are known
    /// Implicit Euler (time.integrator): ImplicitSolve replaces SpringUpdate and NodeUpdate's force
    /// and contact terms; NodeUpdate only moves the positions (x += h·v) and applies the ground.
    bool implicitSolve = false;
    /// FrameStep replaces the per-substep passes (set by the engine, which knows the model's size
    /// and rows: EngineOptions::frameStep).
    bool frameStep = false;
    ImplicitParams implicitParams; ///< h is filled in once substeps are known

    /// Collision detection and response (effects collisions / self_collisions).
    bool collisions = false;
    bool betweenObjects = false; ///< pairs of faces of different objects
    bool selfCollisions = false; ///< pairs of faces of one object that share no node
    /// collision.detection = continuous: NodePredict computes x1 before the collision stages,
    /// which run on [x0, x1] (swept boxes, CCD); NodeUpdate then runs without forces.
    bool continuous = false;
    NodeUpdateParams nodePredictParams; ///< NodePredict's forces and h (continuous only)
    /// collision.response = intersection_free (decision 0024): ContactResponse acts on the previous
    /// substep's feature pairs at x0, NodePredict adds its forces and the ground to x1, and SafeStep
    /// cuts the steps the CCD finds unsafe and commits x1 (no NodeUpdate).
    bool safeStep = false;
    /// Safe step: the velocity response runs this many times, each followed by ContactApply (its
    /// forces into v and x1), so a node in several contacts converges towards stopping all of
    /// their approaches instead of the single Jacobi average (decision 0024, "Response
    /// iterations"; CollisionSettings::responseIterations, automaticResponseIterations()).
    int responseIterations = 4;
    NodeUpdateParams contactApplyParams; ///< safe step: ContactApply (contacts and ground only)
    /// Safe step under implicit Euler: the penalty contacts of the last substep's feature pairs
    /// enter the solve's matrix (ImplicitSolverPass with contacts; docs/integration.md).
    bool implicitContacts = false;
    /// Further Newton steps with time.solver.line_search and no wind (Φ needs a potential):
    /// NewtonLineSearch after each (decision 0024, "Line search").
    bool lineSearch = false;
    passes::LineSearchParams lineSearchParams;
    /// Safe step with collision.energyGuard: EnergyGuard after SafeStep (decision 0024).
    bool energyGuard = false;
    passes::EnergyGuardParams energyGuardParams;
    CollisionSettings collision;
    ContactParams contact;

    /// What a substep runs, in order: the one place that states the substep's order.
    [[nodiscard]] std::vector<Stage> stages() const;
    [[nodiscard]] std::vector<Stage> safeStepStages() const; ///< stages() of the intersection-free response
    /// stages() without collisions, or with a response that acts as forces or impulses (penalty, bridson).
    [[nodiscard]] std::vector<Stage> forceResponseStages() const;
    /// The passes a substep dispatches, in order (stages() with the collision detection expanded
    /// into its passes).
    [[nodiscard]] std::vector<passes::PassId> passIds() const;
    /// Their names (passes::passName).
    [[nodiscard]] std::vector<std::string> passes() const;
    /// The engine's own buffers the scene needs (DeviceBuffers declaration order): the one place
    /// that decides them; Engine allocates exactly these. The collision detection's lists and
    /// tables and the solver's vectors follow them in Engine::allocatedBuffers().
    [[nodiscard]] std::vector<passes::BufferId> bufferIds() const;
    /// Their labels (passes::bufferLabel).
    [[nodiscard]] std::vector<std::string> buffers() const;
};

PipelinePlan planPipeline(const Scene& scene);
/// The intersection-free response's velocity-response iterations per substep when the scene sets
/// none (CollisionSettings::responseIterations 0): 8 under symplectic Euler, 4 under implicit.
int automaticResponseIterations(Integrator integrator);
/// The intersection-free response's part of the plan (its ResponseModel calls it).
void planSafeStep(const Scene& scene, PipelinePlan& plan);

} // namespace glcollide::engine
