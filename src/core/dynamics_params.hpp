#pragma once
// Parameters of the dynamics passes, shared by the GPU passes (module passes) and their CPU
// twins (module cpu) so both are driven by the same values. Units are SI.

#include <glm/vec3.hpp>

#include <cstdint>

namespace glcollide {

/// NodeForce: which terms are compiled in, and their values.
struct NodeForceParams {
    bool gravity = false;
    bool damping = false;
    bool wind = false;
    glm::dvec3 gravityAcceleration{0.0, -9.81, 0.0}; ///< m/s²
    double dampingCoefficient = 0.0;                 ///< 1/s: f = -c·m·v
    glm::dvec3 windVelocity{0.0};                    ///< m/s
    double windDrag = 0.0;                           ///< kg/(m²·s)
};

/// SpringUpdate: the springs' force plus, in the same dispatch, the external force (so a
/// substep with springs needs no NodeForce dispatch).
struct SpringUpdateParams {
    NodeForceParams external;
};

/// NodeUpdate: one symplectic Euler substep of length h, with an optional ground plane.
struct NodeUpdateParams {
    double h = 0.0;                 ///< s, substep length
    bool forces = false;            ///< a force buffer exists (otherwise velocities stay constant)
    bool contacts = false;          ///< add (and clear) the fixed-point contact forces of ContactResponse
    double contactForceScale = 1.0; ///< fixed-point units per N of the contact forces
    bool ground = false;
    double groundHeight = 0.0;
    double restitution = 0.0;
    double friction = 0.0;
    /// m, > 0 (the intersection-free response's NodePredict): the ground is a contact, not a clamp;
    /// nodes this close above it get its velocity response and SafeStep cuts crossings (GLC_GROUND_BAND).
    double groundBand = 0.0;
    /// m/s, with groundBand: an approach slower than this is resting contact, not an impact, and
    /// gets no restitution (a node resting in the band approaches by what gravity adds in a
    /// substep; bouncing that back every substep put energy into resting piles: decision 0024).
    double restingSpeed = 0.0;
    /// With groundBand: apply the ground's velocity response to nodes in the band. Off for the
    /// NodePredict that follows an implicit solve (decision 0024, "Velocity filters before the
    /// solve"): a velocity changed after the solve no longer solves its system, and the ground's
    /// response there put energy into resting bodies; under implicit Euler the response runs
    /// before the solve (ContactApply), on the start velocity.
    bool bandResponse = true;
    /// N/m per node, with groundBand: the implicit solve's ground penalty (ImplicitParams). Its push
    /// over the substep, h·w·k_g·depth, is the normal impulse of a node resting in the band, which
    /// bounds the band's Coulomb friction: without it a resting node, not approaching, had no
    /// friction and a box slid on forever. 0: approaching nodes only (symplectic Euler).
    double groundStiffness = 0.0;
    /// m/s², with groundBand: the acceleration the solve that follows adds (gravity; 0 when the
    /// forces are already in v). The band's friction stops the tangential velocity after it, so a
    /// node that sticks does not creep (ContactParams::predictedAcceleration).
    glm::dvec3 predictedAcceleration{0.0};
    bool checkFinite = false; ///< record the first non-finite node in the health buffer (GPU only)
};

/// GroundImpact (the intersection-free response, decision 0024 "Restitution at any step"): a node that
/// came down into the ground's band within the substep leaves with at least e times its impact speed.
struct GroundImpactParams {
    double bandTop = 0.0;      ///< m: the ground's height plus its band (the contact thickness)
    double gravityY = 0.0;     ///< m/s²: gravity along the ground's normal (+y); 0 without gravity
    double restitution = 0.0;  ///< (0, 1]: the fraction of the impact speed a node leaves with
    double friction = 0.0;     ///< Coulomb μ (>= 0)
    double restingSpeed = 0.0; ///< m/s: slower impacts are resting contact (NodeUpdateParams::restingSpeed)
};

/// ContactImpact (the intersection-free response, decision 0024 "Restitution between bodies"): a
/// vertex-face or edge-edge pair that ends the substep in contact after an impact within it leaves
/// with at least e times its impact's normal speed. The contacts' own settings (thickness, friction,
/// fixed-point scale and cap, substep) are the response's ContactParams.
struct ContactImpactParams {
    double restitution = 0.0;  ///< (0, 1]: the fraction of the impact's normal speed the pair leaves with
    double restingSpeed = 0.0; ///< m/s: slower impacts are resting contact (NodeUpdateParams::restingSpeed)
    glm::dvec3 gravity{0.0};   ///< m/s²: the scene's gravity (0 without the effect)
    int iterations = 4;        ///< Jacobi rounds over the pairs (each: count, impulses, apply)
};

/// The implicit (backward) Euler velocity update of Baraff & Witkin 1998, one linearised step:
///   (M − h·∂f/∂v − h²·∂f/∂x) Δv = h·(f + h·∂f/∂x·v),   v += Δv
/// solved by block-Jacobi preconditioned conjugate gradients (docs/integration.md). Positions
/// then move by NodeUpdate without forces (x += h·v, ground).
struct ImplicitParams {
    double h = 0.0;           ///< s, substep length
    double airDamping = 0.0;  ///< 1/s: the air damping c (f = −c·m·v) of `external`, 0 when off
    bool springs = false;     ///< the springs effect is on
    NodeForceParams external; ///< gravity, air damping, wind: added in the setup dispatch
    /// N/m, > 0 (the intersection-free response, decision 0024): the ground enters the solve as a
    /// penalty k_g·(g + band − y) on every node below g + band, with its stiffness k_g in the
    /// matrix (GLC_IMPLICIT_GROUND), so a body resting on it is held by the solve itself.
    double groundStiffness = 0.0;
    double groundHeight = 0.0; ///< m
    double groundBand = 0.0;   ///< m
    /// Newton steps per substep (Scene: time.solver.newton_steps); above 1 the pass is built with
    /// contacts and each further step is ImplicitSolverPass::dispatchNewton: the system assembled
    /// again at the previous step's end x1 with the contacts found there.
    int newtonSteps = 1;
    /// m: a Newton step after the second is taken only while the step before it moved some node's
    /// end position by more than this (time.solver.newton_tolerance × the contacts' thickness;
    /// 0: every step). The engine decides from NewtonLineSearchPass's LineSearchStep::largestMove.
    double newtonMoveTolerance = 0.0;
    double tolerance = 1.0e-4; ///< stop when ‖r‖ ≤ tolerance·‖b‖
    int maxIterations = 256;   ///< CG iteration cap (include/glcollide/scene.hpp says why 256)
};

/// The largest scene FrameStep takes: one work group of 1024 invocations walks every node twice
/// per substep, which beats two dispatches per substep only while a dispatch's launch costs more
/// than the nodes' work (docs/integration.md, "Fewer dispatches"; not yet measured in a committed
/// run).
inline constexpr std::uint32_t kFrameStepMaxNodes = 4096;
/// Substeps one FrameStep dispatch runs at most (a frame with more takes several dispatches).
inline constexpr std::uint32_t kFrameStepSubstepsPerDispatch = 1024;

/// FrameStep: a whole frame of symplectic Euler substeps in one dispatch of one work group.
struct FrameStepParams {
    NodeForceParams external; ///< gravity, air damping, wind
    bool springs = false;
    NodeUpdateParams update; ///< h, ground, checkFinite (no forces buffer flag, no contacts)
    std::uint32_t substeps = 1;
    /// Substeps per dispatch: kFrameStepSubstepsPerDispatch, or fewer where an invocation would
    /// loop too often (passes::frameStepSubstepsPerDispatch).
    std::uint32_t substepsPerDispatch = kFrameStepSubstepsPerDispatch;
};

/// Nodes with more springs than this are gathered by a whole work group (GLC_HEAVY_ROW).
inline constexpr std::uint32_t kHeavyRow = 64;

} // namespace glcollide
