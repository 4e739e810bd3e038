#pragma once
// CPU twin of the collision broad and narrow phase (BBUpdate, BBCollision, TriTri; seeds/002
// Alg. 1-3): brute force over all face pairs, in the same float arithmetic as the GPU for the
// boxes, so the candidate set and the leaf boxes must match the GPU's exactly; the intersection
// set comes from the exact rational oracle (oracle/exact_tri_tri.hpp) on the float positions widened to
// double, which the robust GPU narrow phase must reproduce (docs/broad-phase.md).

#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::cpu {

using FacePair = std::array<std::uint32_t, 2>; ///< (lower, higher) global face index

/// Which face pairs may collide (the `collisions` and `self_collisions` effects).
struct PairRules {
    bool betweenObjects = false; ///< faces of different objects
    bool selfCollisions = false; ///< faces of one object that share no node
};

/// A float AABB; empty when lo > hi on some axis (the empty leaf box is lo = +inf, hi = -inf).
struct FloatBox {
    glm::vec3 lo{0.0f}, hi{0.0f};
};

/// Boxes below are inflated by model::halfThicknessFloat(thickness) (model/face_box.hpp), as on the GPU.

/// Closed overlap: lo_a <= hi_b and lo_b <= hi_a on every axis.
bool boxesOverlap(const FloatBox& a, const FloatBox& b);

/// The AABB of face f's three float positions, then lo - half, hi + half, in float.
FloatBox faceBox(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& positions,
                 std::uint32_t face, float halfThickness);

/// The valid-pair rule for f != g: different objects with betweenObjects, or one object with
/// selfCollisions and no shared node.
bool validFacePair(const std::vector<std::uint32_t>& faceIndices,
                   const std::vector<std::uint32_t>& faceObject, std::uint32_t f, std::uint32_t g,
                   const PairRules& rules);

/// Leaf boxes of BBUpdate: per box, the union of its faces' vertices inflated by half, in float;
/// lo = +inf, hi = -inf for a box without faces.
std::vector<FloatBox> twinLeafBoxes(const model::OctreeLayout& layout,
                                    const std::vector<std::uint32_t>& faceIndices,
                                    const std::vector<glm::vec3>& positions, double thickness);

/// Candidates: valid pairs whose face boxes overlap, sorted. O(faces^2).
std::vector<FacePair> twinCandidates(const std::vector<std::uint32_t>& faceIndices,
                                     const std::vector<std::uint32_t>& faceObject,
                                     const std::vector<glm::vec3>& positions, double thickness,
                                     const PairRules& rules);

/// The valid pairs whose boxes (one per face) overlap, sorted: the brute force every candidate
/// twin shares (discrete face boxes here, swept ones in cpu/ccd_twin.hpp).
std::vector<FacePair> overlappingValidPairs(const std::vector<std::uint32_t>& faceIndices,
                                            const std::vector<std::uint32_t>& faceObject,
                                            const std::vector<FloatBox>& boxes, const PairRules& rules);

/// The pairs of `pairs` whose closed triangles intersect, by the exact oracle on the float
/// positions widened to double; keeps the input order.
std::vector<FacePair> twinIntersections(const std::vector<std::uint32_t>& faceIndices,
                                        const std::vector<glm::vec3>& positions,
                                        const std::vector<FacePair>& pairs);

/// The intersecting valid pairs (exact oracle) at t = k / samples, k = 1 ... samples, of the linear
/// motion x0 -> x1: one list per time. The oracle radial culling's theorem is tested against.
std::vector<std::vector<FacePair>> twinIntersectionsAlongMotion(const std::vector<std::uint32_t>& faceIndices,
                                                                const std::vector<std::uint32_t>& faceObject,
                                                                const std::vector<glm::vec3>& x0,
                                                                const std::vector<glm::vec3>& x1,
                                                                const PairRules& rules, int samples);

} // namespace glcollide::cpu
