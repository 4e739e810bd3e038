#pragma once
// The engine's passes: one identifier each, their names stated once. Timer sections, debug groups,
// statistics and the pipeline plan all index by PassId, so no list of names is reconciled with
// another at run time.

#include <array>
#include <cstddef>
#include <cstdint>

namespace glcollide::passes {

/// In pipeline order (a substep dispatches them in this order when its scene calls for them).
enum class PassId : std::uint8_t {
    NodeForce,
    SpringUpdate,
    NodePredict,   ///< continuous detection: v += h·M⁻¹f and the predicted end positions x1 = x + h·v
    RadialCulling, ///< radial view-based culling: observers, classification, free faces (decision 0025)
    BBUpdate,
    BBCollision,
    BvhBuild,    ///< linear BVH: Morton codes, radix sort, hierarchy (when the cadence rebuilds)
    BvhRefit,    ///< linear BVH: node boxes bottom-up
    BvhTraverse, ///< linear BVH: candidate face pairs
    TriTri,
    FeaturePairs, ///< Representative Triangles: candidate face pairs -> vertex-face, edge-edge pairs
    Ccd,          ///< continuous detection: vertex-face and edge-edge CCD over the substep, times of impact
    SafeStep,     ///< intersection-free response: cut the steps of nodes that may touch, re-check, commit
    EnergyGuard,  ///< intersection-free response: a rise of the total energy taken out of the velocities
    Untangle,     ///< intersection-free response: pairs intersecting at x0 push x1 apart (deep intersections)
    ContactResponse,
    ContactApply,     ///< intersection-free response: a response iteration's forces into v and x1
    ImplicitSolve,    ///< implicit Euler: assemble A·Δv = b, conjugate gradients, v += Δv
    NewtonLineSearch, ///< implicit Euler: the fraction of a further Newton step that lowers Φ
    NodeUpdate,
    FrameStep ///< a small scene's whole frame (SpringUpdate + NodeUpdate per substep) in one dispatch
};

inline constexpr std::size_t kPassCount = 21;

inline constexpr std::array<const char*, kPassCount> kPassNames = {
    "NodeForce",        "SpringUpdate", "NodePredict", "RadialCulling",   "BBUpdate",     "BBCollision",
    "BvhBuild",         "BvhRefit",     "BvhTraverse", "TriTri",          "FeaturePairs", "Ccd",
    "SafeStep",         "EnergyGuard",  "Untangle",    "ContactResponse", "ContactApply", "ImplicitSolve",
    "NewtonLineSearch", "NodeUpdate",   "FrameStep"};

constexpr const char* passName(PassId id) {
    return kPassNames[static_cast<std::size_t>(id)];
}
constexpr std::size_t passIndex(PassId id) {
    return static_cast<std::size_t>(id);
}

} // namespace glcollide::passes
