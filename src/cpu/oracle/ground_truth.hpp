#pragma once
// Ground truth for the benchmark's accuracy measurements: the exact set of intersecting face pairs
// of a whole scene (the same answer as twinIntersections(twinCandidates(...)) with thickness 0,
// but fast enough for ~10^6 faces), and the deepest penetration of nodes into closed bodies.
//
// Where things live: src/model/ holds the model the GPU and the twins share (no GL, no GMP);
// src/cpu/ the CPU twins of the GPU passes; src/cpu/oracle/ (here) the references they and the GPU
// are judged by: exact_tri_tri (GMP), ground_truth (exact intersecting pairs of a scene, deepest
// penetration) and tri_tri_cases (the triangle pairs, with the oracle on a float pair).

#include "cpu/collision_twin.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::cpu {

/// Every valid face pair (validFacePair with `rules`) whose closed triangles intersect, by the
/// exact oracle (exactTrianglesIntersect on the float positions widened to double), sorted, each
/// pair (lower, higher). Equal to twinIntersections(twinCandidates(..., thickness 0, rules)).
/// faceIndices: 3 global node indices per face; faceObject: object of each face; positions: m.
/// Cost: a sort-and-sweep over the float face boxes, then a certified double-precision filter and
/// the exact oracle only on pairs whose boxes overlap; runs on all hardware threads. Positions
/// must be finite.
std::vector<FacePair> exactIntersectingPairs(const std::vector<std::uint32_t>& faceIndices,
                                             const std::vector<std::uint32_t>& faceObject,
                                             const std::vector<glm::vec3>& positions, const PairRules& rules);

/// Where a node went deepest into another object's closed body.
struct Penetration {
    double depth = 0.0;       ///< m, >= 0: distance from the node to the penetrated body's surface
    std::uint32_t node = 0;   ///< global node index (0 when depth is 0)
    std::uint32_t object = 0; ///< the object penetrated (0 when depth is 0)
};

/// Deepest penetration of nodes into closed bodies: for every node and every OTHER object B with
/// objectClosed[B], if the node is strictly inside B (generalised winding number of B's faces at
/// the node, |w| > 0.5, in double) its distance to B's surface (point-triangle distance in double).
/// Returns the largest such distance and where it happened; depth 0 when no node is inside another
/// body. A node on B's surface has distance 0 whichever way the winding test decides it, so it never
/// contributes a positive depth. Ties keep the first found (lowest object B, then lowest node).
/// faceIndices: 3 global node indices per face; faceObject: object of each face; nodeObject: object
/// of each node; positions: m; objectClosed: per object id (ids beyond its size count as open).
Penetration deepestPenetration(const std::vector<std::uint32_t>& faceIndices,
                               const std::vector<std::uint32_t>& faceObject,
                               const std::vector<std::uint32_t>& nodeObject,
                               const std::vector<glm::dvec3>& positions,
                               const std::vector<bool>& objectClosed);

} // namespace glcollide::cpu
