#pragma once
// Clusters of a surface by the bones of a skeleton, for radial view-based culling (issue 24,
// decision 0025 "Skeletons"): a limb bent at a joint is seen badly from any one segment, so each
// bone watches the faces nearest it. Every face goes to its nearest bone at the rest shape, each
// bone's faces are split into edge-connected pieces, and each piece is closed by fans of ghost
// triangles over all its boundary loops (the cuts at the joints and the surface's own openings)
// into a surface of its own, watched by its bone. The culling then frees faces per piece and culls
// only pairs within one piece, where the theorem of the segment observer holds. GL-free;
// docs/culling.md, "Skeletons".

#include "model/ghost_triangles.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::model {

/// A bone: a segment from its first end to its second (m).
using Bone = std::array<glm::dvec3, 2>;

/// Squared distance from `x` to the segment `bone` (its nearest point, clamped to the ends).
double squaredDistanceToBone(const glm::dvec3& x, const Bone& bone);

/// A partition of a surface's faces into pieces, each watched by one bone.
struct BoneClusters {
    std::vector<std::uint32_t> faceCluster; ///< per face: its piece, 0 .. count - 1
    std::vector<std::uint32_t> clusterBone; ///< per piece: the bone that watches it
    std::uint32_t count = 0;
};

/// Every face goes to the bone nearest its centroid at `positions` (ties: the lowest bone), and each
/// bone's faces are split into pieces connected through edges that two of them share; pieces are
/// numbered by their lowest face. Deterministic. Throws std::invalid_argument for no bones or a bone
/// of no length, std::out_of_range for a node index >= positions.size().
BoneClusters boneClusters(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& positions,
                          const std::vector<Bone>& bones);

/// One piece closed for the culling: every boundary loop of its faces filled with a fan around the
/// loop's mean (model::ghostTriangles with no size limit).
struct BoneClosure {
    /// Every loop filled, and faces plus fans one closed, consistently oriented, connected surface.
    bool closed = false;
    GhostTriangles ghosts; ///< ghost node g is node positions.size() + g
    /// Six times the signed volume the piece and its fans bound at `positions`: positive when they
    /// wind outward (decision 0025, "Orientation").
    double volume6 = 0.0;
};
BoneClosure closeBoneCluster(const std::vector<Triangle>& pieceFaces,
                             const std::vector<glm::dvec3>& positions);

} // namespace glcollide::model
