#pragma once
// The AABB-octree layout of the collision broad phase (seeds/002, §BBUpdate, Fig. 7): each
// object's rest-pose bounding box is split into 2^depth cells per axis; every face belongs to the
// leaf box of the cell holding its rest centroid, for the whole simulation. Only the boxes'
// extents change at run time (BBUpdate refits them); the face→box assignment is built here once.
// Also the per-face data the collision passes need (object, leaf box, owned features from
// features.hpp) and the per-object closed flags. Built on the CPU from the FlatModel; the GPU gets
// the arrays as is.

#include "model/flat_model.hpp"

#include <cstdint>
#include <vector>

namespace glcollide::model {

struct OctreeLayout {
    int depth = 0;                         ///< 1..3
    std::uint32_t cellsPerAxis = 0;        ///< 2^depth
    std::uint32_t boxesPerObject = 0;      ///< 8^depth
    std::uint32_t boxCount = 0;            ///< objects * boxesPerObject
    std::vector<std::uint32_t> faceObject; ///< object of each face
    std::vector<std::uint32_t> faceBox;    ///< global leaf box of each face (firstBox + cell)
    std::vector<std::uint32_t> faceOwned;  ///< owned-feature bits (GLC_OWN_*) of each face: ownedFeatures
    Csr boxFaces;                          ///< faces of each leaf box, in increasing face index
    std::vector<std::uint32_t> firstBox;   ///< per object: o * boxesPerObject
    std::vector<std::uint8_t> closed;      ///< per object: isClosedSurface (every edge has exactly two faces)
};

/// Leaf cell (0 .. 8^depth - 1, x fastest) of a point in the box [lo, hi] split into `cellsPerAxis`
/// cells per axis; points outside are clamped to the border cells, and a flat axis (hi == lo)
/// maps to cell 0 on that axis.
std::uint32_t octreeCell(const glm::dvec3& point, const glm::dvec3& lo, const glm::dvec3& hi,
                         std::uint32_t cellsPerAxis);

/// Builds the layout from the rest pose `model.positions`. `depth` must be 1, 2 or 3 (throws
/// glcollide::Error otherwise).
OctreeLayout buildOctree(const FlatModel& model, int depth);

} // namespace glcollide::model
