#pragma once
// Parameters of the contact response (ContactResponse pass and its CPU twin), derived from a
// scene's CollisionSettings in one place so both sides use the same numbers. docs/collisions.md.

#include <glcollide/scene.hpp>

#include <algorithm>
#include <cmath>

namespace glcollide {

struct ContactParams {
    double thickness = 0.0;  ///< m: contact distance h
    double stiffness = 0.0;  ///< N/m per contact
    double damping = 0.0;    ///< N·s/m on the normal relative speed
    double forceCap = 0.0;   ///< N per contact: 4·k·h (twice the force at the deepest signed depth 2h)
    double forceScale = 1.0; ///< fixed-point units per N of the GPU's integer force sums
    /// s: the substep length dt, set by the engine once it has chosen the substeps. It gives the
    /// positions at the start of the substep (x − dt·v: the side a vertex must be kept on) and
    /// the inelastic (velocity-level) part of the force. 0: penalty only, sides from the current
    /// positions (decision 0019).
    double substep = 0.0;
    /// Bridson (decision 0019): approaching pairs are stopped by an inelastic impulse and the
    /// penalty is limited to what separates them at depth / max(10·dt, relaxationTime).
    bool velocityResponse = false;
    /// Sides of open surfaces from x − dt·v (decision 0019). Off for the intersection-free response
    /// (decision 0024): its x is intersection-free and v is already this substep's, so the current
    /// side is the one to keep.
    bool sidesFromPrevious = true;
    /// Bridson's penalty part (raise v_n of a pair within the thickness up to the target speed).
    /// Off for the intersection-free response under implicit Euler (decision 0024, "Velocity
    /// filters before the solve"): its iterations run before the solve, on the start velocity,
    /// as inelastic impulses and friction only, and the penalty is in the solve's matrix.
    bool repulsion = true;
    /// Without repulsion: the forces at the start of the substep (gravity, springs, damping, wind:
    /// the force buffer of NodeForce or SpringUpdate) predict what the solve that follows adds,
    /// h·w·f per node, and friction stops the relative tangential velocity *after* it, so a
    /// contact that sticks does not creep by one substep of those forces per substep (decision
    /// 0024). A program variant (GLC_PREDICTED_FORCES): the force buffer is bound.
    bool predictedForces = false;
    /// s: the thickness is restored over at least this long (CollisionSettings::relaxationTime; 0.05
    /// let cloth sink into a pinned sphere)
    double relaxationTime = 0.01;
    /// Coulomb μ between bodies: each pushing contact also opposes the relative tangential velocity
    /// with at most μ times its normal force and at most what stops it in the substep (needs
    /// substep > 0). 0: frictionless.
    double friction = 0.0;
    /// m: the implicit solve's contacts (implicit_contact_find.comp, cpu::implicitContacts) also take
    /// the listed pairs beyond the thickness but within it plus this margin that approach at the
    /// velocities the solve is linearised at: each gets the stiffness k and no force, the tangent
    /// quadratic bound of its penalty where it is, so a step cannot carry it into the thickness
    /// unopposed (decision 0024, "Approaching pairs in the solve"). 0: contacts within the
    /// thickness only. Set by the plan from time.solver.contact_margin for the first solve; the
    /// engine's Newton steps set 0 (held at x1, a landing body hovered out of its friction's
    /// reach); the responses ignore it.
    double solveMargin = 0.0;
    /// s: the implicit solve leaves out a pair within the thickness that leaves it: its relative
    /// normal velocity vn (at the velocities the solve is linearised at) carries it out of the
    /// thickness within this time, vn·leavingStep ≥ depth, and is a bounce, vn > leavingSpeed. Its
    /// linearised penalty is two-sided — it would pull the leaving pair back and hold it, which the
    /// one-sided penalty never does — so a bounce left the band at a fraction of its speed (decision
    /// 0024, "Restitution between bodies"). Set by the engine to the substep h when contacts between
    /// bodies have a restitution; 0: every pair within the thickness (the responses ignore it).
    double leavingStep = 0.0;
    /// m/s: slower separations stay in the solve (resting contact: what gravity adds in two substeps,
    /// NodeUpdateParams::restingSpeed; left out, a pair resting on the band's edge came and went).
    double leavingSpeed = 0.0;
};

/// Contacts that may add to one node in one substep before its int32 fixed-point sum could
/// overflow. Each contributes at most forceCap·√(1 + μ²) (the normal force and the friction at
/// most μ times it), so the scale leaves room for this many.
inline constexpr double kContactsPerNodeHeadroom = 1024.0;

/// m: the separation the intersection-free response's safe step keeps (decision 0024): a pair may
/// not come closer than this (or than half its distance at the start of the substep) within a
/// substep. A quarter of the thickness, inside the band where the response pushes pairs apart;
/// the scene's ccd.min_separation when that is larger, up to the thickness (the swept boxes are
/// inflated by half of it per side: pairs closer than that are candidates, farther ones may not be).
inline double safeStepSeparation(const CollisionSettings& s) {
    return std::clamp(s.ccd.minSeparation, 0.25 * s.thickness, s.thickness);
}

inline ContactParams contactParams(const CollisionSettings& s) {
    ContactParams p;
    p.thickness = s.thickness;
    p.stiffness = s.stiffness;
    p.damping = s.damping;
    p.velocityResponse =
        s.response == ContactResponse::Bridson || s.response == ContactResponse::IntersectionFree;
    p.sidesFromPrevious = s.response != ContactResponse::IntersectionFree;
    p.friction = s.friction;
    p.relaxationTime = s.relaxationTime;
    p.forceCap = 4.0 * s.stiffness * s.thickness;
    // Largest power of two with headroom·cap·√(1 + μ²)·scale ≤ 2^31 - 1: resolution
    // cap·√(1 + μ²)·headroom/2^31 (~5e-7 of the cap without friction), exact in float.
    const double largestContribution = p.forceCap * std::sqrt(1.0 + p.friction * p.friction);
    p.forceScale =
        std::exp2(std::floor(std::log2(2147483647.0 / (kContactsPerNodeHeadroom * largestContribution))));
    return p;
}

} // namespace glcollide
