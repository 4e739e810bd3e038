#pragma once
/// \file Scene description: what the engine simulates. Built by loadScene() from a JSON file or
/// assembled in code. Units are SI: metres, kilograms, seconds, newtons.

#include <glcollide/effects.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <filesystem>
#include <string_view>
#include <optional>
#include <string>
#include <vector>

namespace glcollide {

/// Which rule produced a spring; informative (statistics, export), never used by the solver.
enum class SpringKind : std::uint8_t { Edge, Structural, Shear, Bend };

/// A spring between two nodes of one body (indices local to the body).
struct Spring {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    double restLength = 0.0; ///< m, > 0
    double stiffness = 0.0;  ///< N/m, > 0
    double damping = 0.0;    ///< N·s/m along the spring, >= 0
    SpringKind kind = SpringKind::Edge;
};

/// One deformable object: nodes, surface triangles, optional tetrahedra, springs.
/// All per-node vectors have the same length. Indices are local to the body.
struct Body {
    std::string name;
    std::vector<glm::dvec3> positions;  ///< m, world space (transform already applied)
    std::vector<glm::dvec3> velocities; ///< m/s
    std::vector<double> masses;         ///< kg per node, > 0 (lumped)
    std::vector<std::uint8_t> pinned;   ///< 1 = node never moves (infinite mass)
    std::vector<std::array<std::uint32_t, 3>>
        faces; ///< surface triangles, counter-clockwise seen from outside
    std::vector<std::array<std::uint32_t, 4>> tets; ///< empty for surface bodies
    std::vector<Spring> springs;
    /// m, world space: radial culling's observer of this object, given by the scene (the object's
    /// "observer", transformed with it) instead of its nodes' centroid; it moves with four of the
    /// object's nodes (docs/culling.md, "User observers"). Only with "culling": "radial".
    std::optional<glm::dvec3> observer;
    /// m, world space: with `observer`, the other end of a segment observer (the object's
    /// "observer": [[x, y, z], [x, y, z]]; docs/culling.md, "Segment observers"), e.g. a limb's bone.
    std::optional<glm::dvec3> observerEnd;
    /// m, world space: radial culling's skeleton of this object (the object's "skeleton",
    /// transformed with it), one segment per bone: each face is watched by the bone nearest it at
    /// rest, each bone's faces closed by ghost fans into surfaces of their own (docs/culling.md,
    /// "Skeletons"), e.g. a limb bent at a joint. Empty: none. Not with `observer`.
    std::vector<std::array<glm::dvec3, 2>> skeleton;
};

/// A horizontal plane y = height that nodes cannot go below.
struct GroundPlane {
    double height = 0.0;      ///< m
    double restitution = 0.0; ///< 0..1: fraction of the normal speed kept on impact
    double friction = 0.0;    ///< >= 0: Coulomb coefficient applied to the tangential velocity
};

/// Linear aerodynamic drag of faces moving relative to a constant wind.
/// Per face: f = drag · area · ((wind − v_face)·n̂) n̂, shared equally by its three nodes.
struct Wind {
    glm::dvec3 velocity{0.0}; ///< m/s
    double drag = 1.0;        ///< kg/(m²·s), >= 0
};

/// Which broad phase finds candidate face pairs (docs/collisions.md).
enum class BroadPhase : std::uint8_t {
    Octree,   ///< AABB-octree boxes, overlapping box pairs expanded to face pairs: work ~ candidates
    Masked,   ///< the paper's scheme: every face pair dispatched, masked by the box-pair overlap mask
    AllPairs, ///< every face pair dispatched and tested: the reference the others are measured against
    Bvh,      ///< linear BVH over all faces, built, refit and traversed on the GPU: work ~ candidates
};

/// When the linear BVH is rebuilt (Morton codes, sort, hierarchy); every other substep only
/// refits its boxes. A refit tree stays correct but loosens as the mesh deforms; the traversal's
/// node visits (CollisionCounts::bvhNodeVisits) measure what that costs.
enum class BvhRebuild : std::uint8_t {
    EverySubstep,
    EveryFrame,
    EveryNFrames, ///< BvhSettings::rebuildFrames
    Never,        ///< built once, on the first substep; refit after
};

/// Settings of the linear BVH broad phase (`collision.bvh` in a scene).
struct BvhSettings {
    BvhRebuild rebuild = BvhRebuild::EveryFrame;
    int rebuildFrames = 1; ///< >= 1: frames between rebuilds with EveryNFrames
    /// Nodes one traversal invocation visits per dispatch before it saves its place and a further
    /// dispatch resumes it. Below 65,535 because llvmpipe ends a shader loop silently after that
    /// many iterations (at most 65534); small values are for tests.
    std::uint32_t visitsPerRound = 16384;
};

/// When contacts are looked for (`collision.detection`; docs/ccd.md, "In the engine").
enum class Detection : std::uint8_t {
    Discrete,  ///< at the start of each substep: pairs within the thickness
    Continuous ///< over each substep: swept boxes, vertex-face / edge-edge CCD, times of impact
};

/// Settings of the continuous detection (`collision.ccd` in a scene).
struct CcdSettings {
    /// Boxes of (t, u, v) one pair's refinement may evaluate before it answers "may touch" at its
    /// lower bound (counted in --stats as capped). At most 21,844: llvmpipe ends a shader
    /// invocation after 65,535 loop iterations and a box costs three.
    std::uint32_t budget = 4096;
    /// m, >= 0: the pairs that count as touching come within this distance; 0 = true contact.
    double minSeparation = 0.0;
};

/// How the contact response acts (docs/collisions.md, decision 0019).
enum class ContactResponse : std::uint8_t {
    Penalty, ///< penalty force k·(h − d) − c·v_n within the thickness (elastic: bodies bounce)
    Bridson, ///< Bridson et al. 2002: inelastic stop of approaching pairs + limited penalty (cloth)
    /// Bridson's velocity response, then a safe step (decision 0024): continuous detection over the
    /// substep, and every node of a pair that may touch advances only to a fraction of its earliest
    /// time of impact (a node frozen where that is not enough). No face pair starts to intersect.
    /// Needs continuous detection (the default with this response). The default response of a
    /// scene with collisions (decision 0024, "The default").
    IntersectionFree,
};

/// Which exact tests are skipped for pairs that provably cannot intersect (`collision.culling`;
/// docs/culling.md, decision 0025). Culling changes the work, never the answers.
enum class Culling : std::uint8_t {
    None,
    /// Radial view-based culling: each closed object gets an observer (the centroid of its nodes);
    /// its faces proven to stay in front of it, whose directions meet no other face's that is not
    /// proven so, intersect nothing of the object during the substep: TriTri and the zero-separation
    /// CCD leave out their self-collision pairs. Needs self_collisions and the intersection_free
    /// response (whose intersection-free substeps are the theorem's premise).
    Radial,
};

/// Where radial culling's observers stand (`collision.observers`; docs/culling.md, "Clusters").
enum class RadialObservers : std::uint8_t {
    /// One observer per object that is closed by itself or by ghost fans over its boundary loops
    /// (ghost_max_perimeter); an open object that cannot be so closed is split into clusters.
    Auto,
    /// One observer per object closed by itself or by ghosts; other objects get none.
    Objects,
    /// Every object that is not closed by itself is split into clusters of its initial shape, each
    /// closed by ghost fans and watched from behind; only pairs within one cluster are culled.
    Clusters,
};

enum class TriTriPrecision : std::uint8_t {
    Fast,   ///< float with epsilons: may disagree with the exact answer near degenerate configurations
    Robust, ///< float filter with a certified error bound, exact fallback: always the exact answer
};

/// Settings of the `collisions` and `self_collisions` effects.
struct CollisionSettings {
    BroadPhase broadPhase = BroadPhase::Octree;
    int octreeDepth = 2; ///< 1, 2 or 3: 8^depth leaf boxes per object (2 = the paper's 64)
    TriTriPrecision precision = TriTriPrecision::Robust;
    double thickness = 0.01;  ///< m, > 0: contact distance; boxes are inflated by half of it per side
    double stiffness = 1.0e4; ///< N/m, > 0: penalty stiffness per vertex-face or edge-edge contact
    double damping = 0.0;     ///< N·s/m, >= 0: damping of the normal relative velocity in a contact
    /// >= 0: Coulomb coefficient μ of the vertex-face and edge-edge contacts (the tangential force
    /// is at most μ times the normal one, and at most what stops the sliding); 0: frictionless
    double friction = 0.0;
    /// 0 … 1, intersection_free only: the fraction of a vertex-face or edge-edge impact's normal
    /// speed the pair leaves with (ContactImpact, decision 0024 "Restitution between bodies");
    /// approaches slower than what gravity adds in two substeps are resting contact. 0: inelastic.
    double restitution = 0.0;
    /// 1 … 64, with restitution > 0: ContactImpact's rounds of projected Jacobi over the impact pairs;
    /// more rounds bring every pair nearer its target where several pairs share nodes (the accuracy
    /// and its cost: docs/benchmarks.md, "Restitution between bodies").
    int restitutionIterations = 16;
    /// s, > 0: Bridson's response (bridson, and intersection_free where it pushes: under symplectic
    /// Euler and while recovering from intersecting input) separates a pair within the thickness
    /// at no more than depth / max(10·substep, relaxationTime). A time of the scene's own: the same
    /// scene in other units of time sets it in those units (decision 0020, "Units").
    double relaxationTime = 0.01;
    /// The default, intersection_free, needs `detection` Continuous (its default too); penalty and
    /// bridson were built for, and are measured with, Discrete: set both when choosing them.
    ContactResponse response = ContactResponse::IntersectionFree;
    /// intersection_free only: a rise of the total energy in a substep (beyond the float resolution
    /// of its sum) is taken out of the velocities (decision 0024, "Energy guard"). Needs a closed
    /// scene: no wind, which does work on it (the engine leaves it out where the wind blows).
    bool energyGuard = true;
    /// intersection_free only: how many times per substep Bridson's velocity response runs on the
    /// contacts, each followed by ContactApply (decision 0024, "Response iterations"). Each pass
    /// moves a node by the average of its contacts' corrections (Jacobi), so a body resting on many
    /// contacts needs several to stop its approach; too few under symplectic Euler let a pile sink
    /// until the safe step froze it. Range 1 ... 64; 0 (default): automatic, 8 under symplectic
    /// Euler, 4 before an implicit solve (the solve holds the contacts there).
    int responseIterations = 0;
    std::uint32_t initialCapacity = 4096; ///< >= 1: first size of every pair list (grown on overflow)
    BvhSettings bvh;                      ///< used by BroadPhase::Bvh
    Detection detection = Detection::Continuous;
    CcdSettings ccd; ///< used by Detection::Continuous
    Culling culling = Culling::None;
    /// Radial culling (docs/culling.md, "Ghost triangles"): an object whose surface is open gets an
    /// observer when fans of ghost triangles over its boundary loops close it; a loop is closed when
    /// its perimeter (m) is at most this. Ghosts only take part in the classification (they never
    /// collide), so a large fan costs culling, never answers. Range >= 0 (0: no ghosts, open objects
    /// are not culled); default +infinity (every closed, manifold, unpinched loop). Suggested: about
    /// 1.5 × the perimeter of the largest opening that should be closed (a cuff, an ear hole).
    double ghostMaxPerimeter = std::numeric_limits<double>::infinity();
    RadialObservers observers = RadialObservers::Auto;
    /// Radial culling's clusters (docs/culling.md, "Clusters"): half-angle (radians) of each
    /// cluster's normal cone at the initial positions. Range (0, π/2); default π/4.
    double clusterMaxAngle = 0.7853981633974483;
    /// Radial culling's clusters: a cluster stops growing after the breadth-first ring that brings
    /// it to this many faces (0: no limit). Default 64: of 64, 256, 1,024 and no limit, 64 freed the
    /// most faces of a draped sheet (docs/culling.md, "Clusters").
    std::uint32_t clusterMaxFaces = 64;
};

/// How a substep advances the nodes (docs/integration.md).
enum class Integrator : std::uint8_t {
    SymplecticEuler, ///< explicit: v += h·M⁻¹f(x, v); x += h·v. Conditionally stable (auto substeps)
    ImplicitEuler    ///< Baraff & Witkin 1998: one linearised backward-Euler step, solved by PCG
};

/// The implicit integrator's linear solve: preconditioned conjugate gradients on the GPU.
struct ImplicitSolverSettings {
    /// Stop when ‖r‖ ≤ tolerance · ‖b‖ (residual of the velocity-change system relative to its
    /// right-hand side), > 0.
    double tolerance = 1.0e-4;
    /// Iteration cap per solve, 1 … 1024 (two dispatches each). A solve stops within 16 iterations
    /// of converging, so the cap costs only the substeps that need it; 256 because at one substep
    /// per frame 64 left most solves of the shipped contact scenes unconverged (decision 0024,
    /// "Converged solves").
    int maxIterations = 256;
    /// Newton steps of backward Euler per substep, 1 … 4, or 0: automatic (2 where the contacts are
    /// in the solve — the intersection_free response — else 1). Above 1 (intersection_free only)
    /// each further step detects the previous step's end x1 and solves again at x1 with the
    /// contacts found there, so contacts that enter the thickness during the substep act in the
    /// solve itself (decision 0024, "Newton steps"); each costs one more detection and solve.
    int newtonSteps = 0;
    /// A Newton step after the second is taken only while the step before it moved some node's end
    /// position by more than this fraction of collision.thickness, [0, 1]; 0 takes every step. The
    /// thickness is where the contacts' forces change, so a step that moved no node by a good part
    /// of it leaves the next step's system nearly the one just solved (decision 0024, "Newton
    /// steps until converged"). A step the line search rejects ends the steps at any tolerance (the
    /// next would solve the same system again). Needs the line search (without it every step is
    /// taken).
    double newtonTolerance = 0.25;
    /// Each further Newton step keeps the first of the fractions 1, ½, ¼ of its change whose
    /// incremental potential is not above the step's start (decision 0024, "Line search"), else
    /// none; false takes the whole step (for comparison).
    bool lineSearch = true;
    /// The margin beyond collision.thickness, as a multiple of it, [0, 4], within which a listed
    /// pair that approaches at the start velocities enters the first solve of a substep (the
    /// intersection_free response) with the contacts' stiffness and no force: the tangent
    /// quadratic bound of its penalty where it is, so the step cannot carry it into the thickness
    /// unopposed; the Newton steps take the contacts within the thickness (decision 0024,
    /// "Approaching pairs in the solve"). 0 (default): only pairs within the thickness. For scenes
    /// that come to rest on themselves (scenes/cloth_ball.json, mask_fold.json set 1); not the
    /// default: at 1 substep per frame it made layered cloth worse.
    double contactMargin = 0.0;
};

struct TimeSettings {
    double dt = 1.0 / 60.0; ///< s per frame, > 0
    Integrator integrator = Integrator::SymplecticEuler;
    /// Substeps per frame. 0 = automatic: for symplectic Euler the smallest count that keeps it
    /// stable for the stiffest spring at its lightest node; for implicit Euler one substep per
    /// frame (see docs/integration.md).
    int substeps = 0;
    ImplicitSolverSettings solver; ///< used by Integrator::ImplicitEuler
    int frames = 240;              ///< frames `glcollide run` simulates by default, > 0
};

/// Where `glcollide render` looks from; a scene without one is framed automatically.
struct CameraSettings {
    glm::dvec3 eye{0.0, 0.0, 5.0}; ///< m
    glm::dvec3 target{0.0};        ///< m, != eye
    glm::dvec3 up{0.0, 1.0, 0.0};  ///< non-zero, not parallel to target - eye
    double fovDeg = 45.0;          ///< vertical field of view in degrees, (0, 180)
};

struct Scene {
    static constexpr int kFormatVersion = 1;

    std::string name;
    std::filesystem::path sourcePath; ///< empty for scenes built in code
    EffectSet effects;
    glm::dvec3 gravity{0.0, -9.81, 0.0}; ///< m/s², used when effects has Gravity
    double damping = 0.0;                ///< 1/s, viscous damping coefficient (Damping)
    Wind wind;                           ///< used when effects has Wind
    GroundPlane ground;                  ///< used when effects has Ground
    CollisionSettings collision;         ///< used when effects has Collisions or SelfCollisions
    TimeSettings time;
    std::optional<CameraSettings> camera; ///< used by `glcollide render`; none: framed automatically
    std::vector<Body> bodies;
};

/// Loads a JSON scene (format in docs/scene-format.md). Mesh paths resolve relative to the
/// scene file. Throws glcollide::Error naming the file and JSON pointer (or mesh file and line).
Scene loadScene(const std::filesystem::path& path);

/// Parses a scene from JSON text. `baseDir` resolves mesh paths; `sourceName` names the text
/// in error messages.
Scene parseScene(const std::string& jsonText, const std::filesystem::path& baseDir,
                 const std::string& sourceName);

/// The scene-format names of the broad phases: "octree", "masked", "all_pairs", "bvh".
const char* integratorName(Integrator kind);
std::optional<Integrator> integratorFromName(std::string_view name);
const char* broadPhaseName(BroadPhase kind);
std::optional<BroadPhase> broadPhaseFromName(std::string_view name);
/// The response named `name` in scenes ("penalty", "bridson", "intersection_free"); nullopt if unknown.
std::optional<ContactResponse> responseFromName(std::string_view name);
/// The detection a response brings when the scene names none (decision 0024, "The default"):
/// intersection_free's safe step reads the continuous detection's times of impact; penalty and
/// bridson were built for, and are measured with, the discrete one.
Detection detectionOf(ContactResponse response);

/// Replaces the scene's broad phase by the one named (the CLI's --broad-phase). Throws
/// glcollide::Error when the name is unknown or the scene has no collision effect.
void overrideBroadPhase(Scene& scene, std::string_view name);

/// The scene `glcollide run` simulates when given none: a cloth pinned at two corners.
Scene defaultScene();

/// Checks the invariants documented on Body/Scene (sizes match, indices in range, finite
/// values, positive masses, rest lengths and stiffnesses). Throws glcollide::Error.
void validateScene(const Scene& scene);

} // namespace glcollide
