#pragma once
/// \file The engine: a scene's state in GPU buffers and the compute pipeline its effects call for.

#include <glcollide/scene.hpp>
#include <glcollide/setup_stats.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide {

/// One KHR_debug message, as EngineOptions::debugCallback receives it. The enums are GL's
/// (GL_DEBUG_SOURCE_*, GL_DEBUG_TYPE_*, GL_DEBUG_SEVERITY_*) as integers, so this header needs no
/// GL loader.
struct GlDebugMessage {
    std::uint32_t source = 0;
    std::uint32_t type = 0;
    std::uint32_t id = 0;
    std::uint32_t severity = 0;
    std::string_view text; ///< valid only during the call
};

struct EngineOptions {
    /// Time each pass with GL timestamp queries. step() then waits for the GPU at its end.
    bool gpuTiming = true;
    /// Debug output, opt-in. Empty (the default): the engine never reads or changes the context's
    /// debug callback or debug-output enables (it still labels its objects and pushes a
    /// GL_DEBUG_SOURCE_THIRD_PARTY group around each pass, which reach whatever callback the host
    /// installed). Set: for the engine's lifetime it installs a callback that calls this function
    /// and then the callback that was installed before (the host's, with its user parameter), and
    /// enables GL_DEBUG_OUTPUT and GL_DEBUG_OUTPUT_SYNCHRONOUS (so messages arrive on the calling
    /// thread, inside the engine call that caused them); destruction restores the previous
    /// callback, user parameter and enables. The callback slot is per context: while installed it
    /// sees every message of the context, the host's included. Must not throw (exceptions are
    /// swallowed) and must not call the engine. A host that installs its own callback after the
    /// engine's and chains to it must remove it before the engine is destroyed.
    std::function<void(const GlDebugMessage&)> debugCallback{};
    /// Detect non-finite states on the device: NodeUpdate tests every new position and velocity
    /// and records the first offending node; step() reads that 16-byte record once per frame (a
    /// wait for the GPU at the frame's end, which gpuTiming waits for anyway) until it is set, and
    /// reports it in StepStats::nonFinite. Also checks that the GPU completed the frame (a word
    /// written after it reads back), or step() throws: a lost context runs nothing
    /// (docs/integration.md). Off: no test, no read.
    bool checkFinite = true;
    /// The on-device self-check of robust precision, run at construction when the scene's
    /// collisions use robust precision and no pass on this device, driver and shader is remembered
    /// (docs/narrow-phase.md, "On-device self-check"; on llvmpipe about 4 s the first time with
    /// cold shader caches, then about 11 ms to find the remembered pass). Error: a disagreement
    /// with the exact oracle throws glcollide::Error naming the device, the driver and the first
    /// wrong case; Warn: it is added to warnings(); Off: no check. GLCOLLIDE_SELF_CHECK=
    /// error|warn|off, when set, wins. The result: setupStats().robustSelfCheck.
    SelfCheckMode robustSelfCheck = SelfCheckMode::Error;
    /// Run all substeps of a frame in one dispatch (FrameStep) when the scene qualifies: symplectic
    /// Euler, no collision effect, forces to integrate, at most 4096 nodes and no node with more
    /// than 64 springs. Same arithmetic as SpringUpdate + NodeUpdate, one dispatch per frame instead
    /// of two per substep (more for frames long enough to reach llvmpipe's loop limit). Off by
    /// default: on llvmpipe its one work group runs on one core, the per-substep passes on all, so
    /// it is not expected to win there; on a GPU, where a small scene's substep is launch-bound, it
    /// is expected to be faster. Neither is measured in a committed result yet
    /// (docs/integration.md, "Fewer dispatches").
    bool frameStep = false;
};

/// GPU time of one pass over all substeps of a frame.
struct PassTiming {
    std::string name;
    double gpuMilliseconds = 0.0; ///< 0 when gpuTiming is off
};

/// What the collision passes found (effects collisions / self_collisions).
struct CollisionStats {
    std::uint32_t boxPairs = 0;             ///< overlapping leaf-box pairs (octree broad phase), last substep
    std::uint32_t candidatePairs = 0;       ///< face pairs within the contact thickness, last substep
    std::uint32_t intersectingPairs = 0;    ///< face pairs whose closed triangles intersect, last substep
    std::uint32_t maxIntersectingPairs = 0; ///< the largest intersectingPairs of the frame's substeps
    std::uint32_t contacts = 0;             ///< contacts with a force, last substep (implicit: the solve's)
    std::uint32_t undecidedPairs =
        0; ///< robust: candidates the filtered test left to the exact pass, last substep
    std::uint32_t exactFallbacks =
        0;                         ///< robust: predicates the exact pass evaluated in integers, last substep
    std::uint32_t listGrowths = 0; ///< pair lists grown (and passes rerun) during the frame
    /// Feature pairs of the Representative-Triangle expansion (each owned vertex against the other
    /// face, each owned edge against each owned edge of the other face), last substep.
    std::uint32_t vertexFacePairs = 0;
    std::uint32_t edgeEdgePairs = 0;
    /// What a face-pair expansion without ownership would test, last substep: 6 vertex-face and
    /// 9 edge-edge pairs per candidate pair.
    std::uint64_t vertexFacePairsWithoutOwnership = 0;
    std::uint64_t edgeEdgePairsWithoutOwnership = 0;
    /// BVH broad phase: nodes whose box the traversal tested in the last substep (the tree's
    /// quality: a refit tree that loosens tests more nodes for the same candidates), rebuilds
    /// during the frame, and traversal dispatches per substep.
    std::uint32_t bvhNodeVisits = 0;
    std::uint32_t bvhRebuilds = 0;
    std::uint32_t bvhRounds = 0;
    /// Continuous detection (collision.detection = continuous), last substep unless said: the
    /// vertex-face and edge-edge pairs tested are vertexFacePairs and edgeEdgePairs (of the swept
    /// candidates); those that may touch during the substep; pairs whose refinement ran out of
    /// budget (answered "may touch"), and summed over the frame; boxes of (t, u, v) evaluated
    /// (modulo 2^32); the earliest time of impact of any substep of the frame, as a fraction of
    /// its substep (+inf when nothing may touch).
    std::uint32_t ccdVertexFaceHits = 0;
    std::uint32_t ccdEdgeEdgeHits = 0;
    std::uint32_t ccdCapped = 0;
    std::uint32_t ccdCappedInFrame = 0;
    std::uint32_t ccdBoxes = 0;
    float ccdEarliestToi = std::numeric_limits<float>::infinity();
    /// The intersection-free response's safe step (decision 0024), over the frame: substeps in
    /// which it cut any node's step, node steps cut (summed over rounds and substeps), the most
    /// cut-and-check rounds of one substep, and substeps in which the last resort froze every node.
    std::uint32_t safeStepSubsteps = 0;
    std::uint32_t safeStepCuts = 0;
    std::uint32_t safeStepMaxRounds = 0;
    std::uint32_t safeStepFrozeAll = 0;
    std::uint32_t safeStepGroundCrossings = 0; ///< node steps that crossed the ground (each cut its object)
    /// The intersection-free response's energy guard (decision 0024), over the frame: substeps
    /// whose total energy rose beyond the float resolution of its sum; of those, substeps whose
    /// step it pulled back (the kinetic energy could not pay) and pulled back all the way to the
    /// start at rest; the energy it took out (J), rises left in the state (J: rounding at the
    /// start only) and the largest rise (J). energyGuard: the guard runs (collision.energy_guard).
    bool energyGuard = false;
    std::uint32_t energyGuardSubsteps = 0;
    std::uint32_t energyGuardPulledBack = 0;
    std::uint32_t energyGuardBackToStart = 0;
    double energyGuardRemoved = 0.0;
    double energyGuardUnremoved = 0.0;
    double energyGuardLargestRise = 0.0;
    double energyGuardTotal = 0.0;   ///< J: the guard's float sum of the energy the frame ended with
    double energyGuardKinetic = 0.0; ///< J: its kinetic part
    double energyGuardContact = 0.0; ///< J: its penalty part (the contacts' and the ground's)
    /// Substeps of the frame whose start had intersecting face pairs (intersectingPairs > 0).
    std::uint32_t substepsWithIntersections = 0;
    /// Recovery from intersecting input (since the engine was made, not per frame): substeps that
    /// began with intersecting pairs before the first one that began without, and whether that
    /// one has come (intersection-free since). Feature pairs the safe step's CCD left out in the
    /// last substep because their faces intersect at its start.
    std::uint64_t substepsUntilIntersectionFree = 0;
    bool reachedIntersectionFree = false;
    std::uint32_t ccdTangledPairs = 0;
    /// Untangling (decision 0024, "Deep intersections"), over the frame: substeps whose start
    /// intersected and whose intersecting pairs pushed their nodes apart, the node steps moved
    /// (summed over those substeps), and intersecting pairs without a segment to shrink (coplanar or
    /// touching: no push).
    std::uint32_t untangleSubsteps = 0;
    std::uint32_t untangledNodes = 0;
    std::uint32_t untangleUnresolvedPairs = 0;
    /// Radial culling (collision.culling "radial", decision 0025): substeps of the frame that culled
    /// (their start was known intersection-free); of the last substep that culled, the faces with an
    /// observer, those not proven positive, the free ones, and the candidate pairs TriTri and the
    /// feature pairs the CCD left out; over the frame, the pairs left out. Ghost triangles
    /// (docs/culling.md): the ghost faces that close observed open surfaces and clusters; of the
    /// last substep that culled, the surfaces that did not wind exactly once around their observer
    /// at its start (the observer check; nothing of them freed), and the frame's substeps with such
    /// a surface.
    std::uint32_t radialSubsteps = 0;
    std::uint32_t radialObservedFaces = 0, radialNonPositiveFaces = 0, radialFreeFaces = 0;
    std::uint32_t radialGhostFaces = 0, radialViolatedSurfaces = 0, radialSubstepsViolated = 0;
    std::uint32_t radialCulledTriTri = 0, radialCulledCcd = 0;
    std::uint64_t radialCulledTriTriInFrame = 0, radialCulledCcdInFrame = 0;
    /// The first frame only: the start was checked standing still before the first substep
    /// (decision 0025, "Culling from the first substep"), and found without intersecting pairs,
    /// so the first substep could cull.
    bool radialStartChecked = false, radialStartFree = false;
};

/// The first non-finite state NodeUpdate produced (EngineOptions::checkFinite).
struct NonFiniteReport {
    bool found = false;
    std::uint64_t frame = 0;      ///< the frame (StepStats::frame numbering, from 1) it happened in
    int substep = 0;              ///< index within that frame, 0 .. substeps-1
    std::uint32_t object = 0;     ///< body index in scene order
    std::uint32_t node = 0;       ///< node index within that body (the lowest one found in that substep)
    std::uint32_t globalNode = 0; ///< the same node in the global (concatenated) node order
};

/// The implicit integrator's linear solves in one frame (all zero for symplectic Euler).
struct SolverStats {
    bool implicit = false;                 ///< the scene integrates with implicit Euler
    std::uint32_t maxIterations = 0;       ///< most conjugate-gradient iterations of one substep
    double maxRelativeResidual = 0.0;      ///< largest final ‖r‖/‖b‖ of one substep
    std::uint32_t totalIterations = 0;     ///< summed over the frame's substeps
    std::uint32_t unconvergedSubsteps = 0; ///< substeps that stopped at the cap above the tolerance
    /// The further Newton steps' line search (time.solver.line_search, decision 0024): steps
    /// searched, steps that kept a fraction below 1 of their change, steps that kept none of it.
    bool lineSearch = false;
    std::uint32_t lineSearchSteps = 0;
    std::uint32_t lineSearchShortened = 0;
    std::uint32_t lineSearchRejected = 0;
    /// Further Newton steps of time.solver.newton_steps not taken because the step before had
    /// converged (moved no node by more than time.solver.newton_tolerance of the thickness) or
    /// kept none of its change; not those of substeps that recover from an intersecting start.
    std::uint32_t newtonStepsSkipped = 0;
};

struct StepStats {
    std::uint64_t frame = 0; ///< frames completed, this one included
    double time = 0.0;       ///< s of simulated time after this frame (or substep: stepSubstep())
    /// Substeps done of the frame in progress (Engine::stepSubstep): 0 at a frame boundary (after
    /// step(), or after the stepSubstep() that completed a frame), else 1 .. substeps-1.
    int substepInFrame = 0;
    int substeps = 0;
    double wallMilliseconds = 0.0; ///< CPU wall time of step(), including the wait for timings
    std::vector<PassTiming> passes;
    bool collisions = false; ///< the collision passes ran (then `collision` is filled)
    bool continuous = false; ///< continuous detection (then the collision.ccd* fields are filled)
    bool safeStep =
        false; ///< the intersection-free response (then the collision.safeStep* fields are filled)
    CollisionStats collision;
    SolverStats solver;
    /// Compute dispatches per substep in this frame, counted as issued (the implicit solver issues
    /// its whole iteration cap; iterations after convergence return at once; collision list
    /// reruns add to it). Launches cost time of their own on a GPU.
    double dispatchesPerSubstep = 0.0;
    /// Set by the first frame whose NodeUpdate produced a non-finite position or velocity (an
    /// infinity or a NaN: the integration diverged) and kept, unchanged, by every later frame.
    NonFiniteReport nonFinite;
};

/// How the substep count was chosen (docs/integration.md).
struct SubstepInfo {
    int substeps = 1;               ///< used per frame
    int stableSubsteps = 1;         ///< what the stability rule asks for
    double substepLength = 0.0;     ///< s
    double maxStableSubstep = 0.0;  ///< s, +inf when nothing limits it
    std::uint32_t limitingNode = 0; ///< global index of the node that sets the limit
    bool automatic = true;
};

/// Energies in joules, computed in double precision from the read-back state.
struct EnergyReport {
    double kinetic = 0.0;
    double potential = 0.0; ///< gravity (if on) + springs (if on)
    /// The intersection-free response's penalty contacts (decision 0024): ½·k·depth² summed over the
    /// feature pairs within the thickness at the current positions (the last detection's lists,
    /// which hold every such pair), plus under implicit Euler the ground's penalty ½·k·depth² per
    /// node below the ground's band. 0 for the other responses.
    double contact = 0.0;
    /// J: the intersection-free response's energy guard compares float sums of these terms on the
    /// GPU, each off by at most this (EnergyGuardPass::resolutionFactor × the terms' magnitude
    /// scale); it lets the total rise by the start's plus the end's. 0 for the other responses.
    double resolution = 0.0;
    /// J: the part of `contact` a float evaluation of the same state may count differently — the
    /// contacts of feature pairs at the boundary of their closest-feature regions (an edge's end, a
    /// face's edge), where which pair counts a vertex near an edge jumps (decision 0024, "Known
    /// failures"): the GPU's sum may differ from `contact` by up to this. Usually 0.
    double contactAmbiguity = 0.0;
    [[nodiscard]] double total() const { return kinetic + potential + contact; }
};

/// A pull on one node by the host (a mouse perturbation, as in MuJoCo's simulate): a spring from
/// the node to a target point, applied as an external force in every substep while it is set
/// (Engine::setPull). The spring's force on the node is stiffness·(target − x) − damping·v.
struct NodePull {
    std::uint32_t globalNode = 0; ///< the node, in the global (concatenated) node order
    glm::dvec3 target{0.0};       ///< m
    double stiffness = 0.0;       ///< N/m, >= 0
    double damping = 0.0;         ///< N·s/m, >= 0: against the node's own velocity
};

/// The Representative-Triangle feature pairs of the last collision detection (Engine::readFeaturePairs):
/// what the contact response tests, each list sorted.
struct FeaturePairs {
    /// (global node, global face): a vertex owned by one face of a candidate pair against the other.
    std::vector<std::array<std::uint32_t, 2>> vertexFace;
    /// (3·fa + e, 3·fb + g), global faces: owned edge e of face fa against owned edge g of fb; edge e
    /// runs from the face's corner e to corner (e + 1) mod 3 (faceIndexBuffer() order).
    std::vector<std::array<std::uint32_t, 2>> edgeEdge;
};

/// One feature contact (Engine::readContacts): a feature pair within the contact thickness by the
/// response's rules (shaders/common/contact_pair.glsl).
struct FeatureContact {
    bool edgeEdge = false; ///< false: a vertex against a face
    /// Global nodes. Vertex-face: the vertex, then the face's three corners; edge-edge: edge a's two
    /// ends, then edge b's.
    std::array<std::uint32_t, 4> nodes{};
    /// Side A's weights are >= 0 and sum to 1, side B's are <= 0 and sum to −1: the closest points
    /// are pA = Σ max(wᵢ, 0)·xᵢ and pB = Σ max(−wᵢ, 0)·xᵢ.
    std::array<double, 4> weights{};
    glm::dvec3 normal{0.0}; ///< unit, from side B to side A
    double depth = 0.0;     ///< m: how far inside the contact thickness (thickness − distance)
};

/// An axis-aligned box of the broad phase (Engine::readBroadPhaseBoxes), m.
struct BroadPhaseBox {
    glm::dvec3 lo{0.0};
    glm::dvec3 hi{0.0};
};

/// Simulates a scene on the current GL ≥ 4.3 context: a HeadlessContext or the caller's own.
/// Not thread-safe; every call needs the construction context (or a sharing one) current.
///
/// GL state contract (docs/embedding.md, "GL state contract"): every call that issues GL commands (the
/// constructor, step(), stepSubstep(), detectCollisions(), the read*() functions, broadPhaseDepth(),
/// energy(), the destructor and move assignment) leaves the host's state as it found it: the current program,
/// the generic and indexed (0..37, with start and size) GL_SHADER_STORAGE_BUFFER bindings,
/// GL_DISPATCH_INDIRECT_BUFFER, GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER and GL_QUERY_BUFFER are saved and
/// restored; vertex arrays, GL_ARRAY_BUFFER, GL_ELEMENT_ARRAY_BUFFER, framebuffers, textures and capabilities
/// are never touched; no query is left active (timing uses glQueryCounter). Exceptions: a pending GL error
/// flag may be consumed (buffer allocation checks glGetError for GL_OUT_OF_MEMORY), and the debug callback is
/// changed only when EngineOptions::debugCallback asks for it. Any number of engines may share a context;
/// they share no state.
class Engine {
  public:
    /// Validates the scene, composes the pass list from its effects, allocates the buffers those
    /// passes need and uploads the state. Throws Error on bad scenes, missing GL 4.3, shader
    /// errors, or effects this version does not implement.
    explicit Engine(const Scene& scene, const EngineOptions& options = {});
    ~Engine();
    Engine(Engine&&) noexcept;
    Engine& operator=(Engine&&) noexcept;

    /// Advances one frame of Scene::time.dt in `substepInfo().substeps` substeps (after
    /// stepSubstep() calls mid-frame: the frame's remaining substeps). Throws only
    /// when a collision pair list must grow beyond what the device can hold (more than
    /// GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes, or GL out of memory): glcollide::Error names the
    /// list and the limit, rather than dropping pairs. The frame is then incomplete; destroy the
    /// engine (the host's GL state is restored as on every return).
    ///
    /// Barriers. step() begins with glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT), so host shader
    /// writes (SSBO or image stores) to positionBuffer() made before the call are seen; writes by
    /// glBufferSubData / glCopyBufferSubData need no barrier. It ends with
    /// glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
    /// GL_SHADER_STORAGE_BARRIER_BIT): right after it the host may draw positionBuffer() as a
    /// GL_ARRAY_BUFFER and faceIndexBuffer() as a GL_ELEMENT_ARRAY_BUFFER, or read them as SSBOs in
    /// its own shaders, with no barrier of its own. Any other use of the engine's results (uniform
    /// or texture buffer, glGetBufferSubData, glCopyBufferSubData, mapping, indirect draw) needs the
    /// host's own glMemoryBarrier with that use's bit first.
    void step();
    /// Advances one substep (length substepInfo().substepLength) of the frame in progress: after
    /// substepInfo().substeps calls from a frame boundary the state is bit for bit the state one
    /// step() gives (the same dispatches in the same order). A frame's bookkeeping stays per frame:
    /// the call that begins a frame does what step() does at a frame's start (clears the frame's
    /// collision and solver statistics, records the energy guard's start, starts the GPU timers),
    /// and the call that ends it does what step() does at its end (frame += 1, the finite-state and
    /// completion checks, the solver statistics, the energy guard's counts, the passes' GPU times
    /// and the wall time, summed over the frame's calls). In between, lastStep() has frame
    /// unchanged, substepInFrame the substeps done, time = frame·dt + substepInFrame·h, and the
    /// collision counts of the substeps done so far (contacts: this substep's). Radial culling's
    /// check that the host moved no node runs at every call (it changes no state; its dispatches
    /// count in dispatchesPerSubstep). The energy guard's
    /// start is recorded at the frame's start and after each pull, as in step(): a node the host
    /// moves by writing positionBuffer() between two substeps of a frame is a rise the guard may
    /// take back out. step() called mid-frame finishes the frame in progress (its remaining
    /// substeps). Barriers and GL state: as step(). Throws Error under EngineOptions::frameStep
    /// (a frame is one dispatch there: it has no substep to stop after), and as step() does.
    void stepSubstep();
    [[nodiscard]] const StepStats& lastStep() const;
    /// Sets (or, with nullopt, removes) the host's pull on one node, applied from the next step()
    /// on, at the start of every substep, before the scene's passes: v += h·w·f with f the pull's
    /// force and w the node's inverse mass (symplectic Euler takes it as one more external force;
    /// implicit Euler takes it explicitly, so a stiffness with h·sqrt(k·w) well below 1 keeps it
    /// stable). A pinned node is not moved. Its own small compute pass (shaders/passes/node_pull.comp),
    /// built at the first call and dispatched only while a pull is set; with EngineOptions::frameStep
    /// it is applied once per frame with h = dt. Under the intersection-free response the energy
    /// guard may take the pull's work back out as an energy rise. Throws Error for a node out of
    /// range, a non-finite target or a negative stiffness or damping. Needs the context current.
    void setPull(std::optional<NodePull> pull);
    [[nodiscard]] const std::optional<NodePull>& pull() const;
    /// What construction spent building compute programs: per program the wall time and whether
    /// it came from the program binary cache (GLCOLLIDE_CACHE_DIR; docs/cli.md, docs/integration.md).
    [[nodiscard]] const SetupStats& setupStats() const;

    /// The passes dispatched each substep, in order ("NodeForce", "SpringUpdate", "BBUpdate",
    /// "BBCollision", "TriTri", "ContactResponse", "NodeUpdate"; only those the effects call for).
    [[nodiscard]] std::vector<std::string> pipeline() const;
    /// Labels of the GPU buffers allocated for this scene ("positions", "springs", ...).
    [[nodiscard]] std::vector<std::string> allocatedBuffers() const;
    [[nodiscard]] std::size_t allocatedBytes() const;
    /// Bytes of the implicit solver's own buffers (part of allocatedBytes(); 0 for symplectic Euler).
    [[nodiscard]] std::size_t solverBytes() const;
    [[nodiscard]] const SubstepInfo& substepInfo() const;
    /// Warnings found at construction (e.g. explicit substeps below the stability limit).
    [[nodiscard]] const std::vector<std::string>& warnings() const;

    [[nodiscard]] const Scene& scene() const;
    [[nodiscard]] std::uint32_t nodeCount() const;
    [[nodiscard]] std::uint32_t faceCount() const;
    [[nodiscard]] std::uint32_t springCount() const;
    /// First global node index of each body (bodies are concatenated in scene order).
    [[nodiscard]] std::vector<std::uint32_t> bodyFirstNodes() const;

    /// Reads node positions / velocities back (waits for the GPU).
    [[nodiscard]] std::vector<glm::dvec3> readPositions() const;
    [[nodiscard]] std::vector<glm::dvec3> readVelocities() const;
    /// Face pairs (global face indices, first < second, sorted) whose closed triangles
    /// intersected in the last substep; empty without collision effects. Reads back.
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readIntersectingPairs() const;
    /// Candidate face pairs of the last substep's broad phase (sorted). Reads back.
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readCandidatePairs() const;
    /// Continuous detection: each node's earliest time of impact in the last substep, as a
    /// fraction of the substep in [0, 1], never later than the true one; +inf for a node no pair
    /// may touch. Empty under discrete detection.
    [[nodiscard]] std::vector<float> readTimesOfImpact() const;
    /// Runs the broad and narrow phase on the current positions without moving anything (no forces,
    /// no contact response, no timing): afterwards readCandidatePairs() / readIntersectingPairs()
    /// describe exactly the state readPositions() returns (after step() they describe the positions
    /// before the last substep's NodeUpdate). Returns the counts (contacts 0); all zero without the
    /// collision effects. Waits for the GPU (one counter readback).
    CollisionStats detectCollisions();
    /// The feature pairs of the last detection (the last substep's, or detectCollisions()'): the
    /// device's lists, read back and sorted (under continuous detection with the orphans that
    /// ownership loses, each once). Throws Error for a scene without collision effects.
    [[nodiscard]] FeaturePairs readFeaturePairs() const;
    /// The contacts among readFeaturePairs(), vertex-face first: the response's rules evaluated in
    /// double precision (the CPU twin, src/cpu/contact_twin.hpp) at the current positions, which
    /// after detectCollisions() are the positions the pairs were found at (after step(), the pairs
    /// are the last substep's, found before its node update). Sides are taken from the current
    /// positions, as energy() does. Throws Error for a scene without collision effects.
    [[nodiscard]] std::vector<FeatureContact> readContacts() const;
    /// The broad phase's boxes at tree depth `depth` (0: the root level), as refit by the last
    /// detection (the last substep's, or detectCollisions()'): the boxes of a cut through the tree,
    /// so together they hold every face's box (inflated by the contact thickness where the broad
    /// phase inflates). BVH ("bvh"): the nodes at that depth, and the leaves (one face each) above
    /// it. Octree ("octree", and the masked broad phase's boxes): per object, the cells of that
    /// level of its octree, each the union of its leaf boxes (the device stores the leaves, at
    /// depth broadPhaseDepth()); empty cells are left out. Reads back. Throws Error for a scene
    /// without collision effects, a broad phase without boxes ("all_pairs"), or a depth outside
    /// 0 .. broadPhaseDepth().
    [[nodiscard]] std::vector<BroadPhaseBox> readBroadPhaseBoxes(int depth) const;
    /// The deepest level readBroadPhaseBoxes() takes: the BVH's depth (its deepest leaf; it can
    /// change when the tree is rebuilt, so this reads the tree back), the octree's collision.octree_depth.
    /// Throws as readBroadPhaseBoxes() does for a scene without boxes.
    [[nodiscard]] int broadPhaseDepth() const;
    /// First global face index of each body.
    [[nodiscard]] std::vector<std::uint32_t> bodyFirstFaces() const;

    /// Kinetic and potential energy of the current state (reads back).
    [[nodiscard]] EnergyReport energy() const;

    /// GL name of the position buffer: nodeCount() vec4 (xyz metres, w inverse mass in 1/kg, 0 =
    /// pinned): a GL_ARRAY_BUFFER attribute of 4 GL_FLOAT, stride 16, offset 0, drawable right
    /// after step() (see its barriers). The name stays valid and the buffer keeps its size for the
    /// engine's lifetime; 0 only for a scene without nodes.
    /// The host may write positions (xyz; keep w), e.g. to drag nodes; it must not resize,
    /// re-specify or delete the buffer.
    [[nodiscard]] std::uint32_t positionBuffer() const;
    /// GL name of the face buffer: faceCount() x 3 GLuint node indices (CCW seen from outside), a
    /// GL_ELEMENT_ARRAY_BUFFER for glDrawElements(GL_TRIANGLES, 3 * faceCount(), GL_UNSIGNED_INT,
    /// 0). Read-only for the host: the collision structures are built from the faces once.
    [[nodiscard]] std::uint32_t faceIndexBuffer() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace glcollide
