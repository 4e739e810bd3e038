#pragma once
// What the Representative-Triangle ownership costs (docs/design/decisions/
// 0018-representative-triangles.md): a feature's pairs come only from the candidates of its owner
// face (the lowest-indexed face containing it). A vertex near a face G that shares a node with
// the vertex's owner face is therefore never tested, even when another face around the vertex
// makes a valid pair with G (the same for an edge near an edge). A face-pair expansion without
// ownership, which tests every vertex of every candidate face, would test it. This brute-force
// CPU measurement counts those pairs on a state, so the loss is a number, not a guess.

#include "cpu/collision_twin.hpp"
#include "cpu/contact_twin.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::cpu {

struct OwnershipCoverage {
    /// (vertex, face) pairs, the vertex not in the face, closer than the thickness, where some
    /// face containing the vertex makes a valid pair with the face (so an expansion of every
    /// vertex of every candidate tests it).
    std::uint64_t vertexFaceNear = 0;
    /// Of those, the pairs whose owner face and face are no valid pair: never tested.
    std::uint64_t vertexFaceLost = 0;
    /// (edge, edge) pairs without a common node, closer than the thickness, where some face of
    /// each makes a valid pair; and of those, the pairs whose owner faces are no valid pair.
    std::uint64_t edgeEdgeNear = 0;
    std::uint64_t edgeEdgeLost = 0;
};

/// Brute force over all vertex-face and edge-edge pairs, in double precision on `positions`
/// widened; distance: to the closest point (cpu::closestOnTriangle, cpu::closestSegmentParams).
OwnershipCoverage ownershipCoverage(const std::vector<std::uint32_t>& faceIndices,
                                    const std::vector<std::uint32_t>& faceObject,
                                    const std::vector<glm::vec3>& positions, double thickness,
                                    const PairRules& rules);

/// What the CCD must see over a substep x0 -> x1 and what a feature-pair list misses of it.
struct CcdCoverage {
    /// (vertex p, face B): p in some face A with (A, B) valid and the swept face boxes overlapping,
    /// and p's swept box (its two positions, inflated by the half thickness) overlapping B's.
    std::uint64_t vertexFaceNeeded = 0, vertexFaceMissing = 0;
    /// (edge e, edge g) without a common node: faces A around e and B around g with (A, B) valid
    /// and overlapping, and the edges' swept boxes overlapping.
    std::uint64_t edgeEdgeNeeded = 0, edgeEdgeMissing = 0;
    /// Entries of the list that name a feature pair an earlier entry named (edge pairs in either
    /// order): a contact the response would count twice.
    std::uint64_t vertexFaceRepeated = 0, edgeEdgeRepeated = 0;
};

/// Brute force over every valid face pair whose swept boxes (cpu::sweptFaceBox) overlap: every
/// vertex of one face against the other face and every edge pair, kept when the features' own
/// swept boxes overlap (a feature's box lies inside every face box around it, same float
/// operations, so a pair whose feature boxes do not overlap cannot touch within the thickness);
/// counts those absent from `pairs` (edge pairs in either order), and the entries of `pairs` that
/// repeat one. Independent of ownership.
CcdCoverage ccdCoverage(const std::vector<std::uint32_t>& faceIndices,
                        const std::vector<std::uint32_t>& faceObject, const std::vector<glm::vec3>& x0,
                        const std::vector<glm::vec3>& x1, double thickness, const PairRules& rules,
                        const FeaturePairList& pairs);

} // namespace glcollide::cpu
