#pragma once
// CPU twin of continuous detection's GPU stages (docs/ccd.md, "In the engine"): the swept face
// boxes of every broad phase built with GLC_SWEPT (shaders/common/face_bounds.glsl) and the Ccd
// stage (shaders/passes/feature_ccd.comp), which runs the same GLSL compiled as C++
// (cpu/ccd_library.hpp) on each feature pair.

#include "cpu/collision_twin.hpp"
#include "cpu/contact_twin.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::cpu {

/// The AABB of face f's nodes at the start (x0) and predicted end (x1) of the substep, then
/// lo - half, hi + half, in float: bit for bit face_bounds.glsl with GLC_SWEPT.
FloatBox sweptFaceBox(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                      const std::vector<glm::vec3>& x1, std::uint32_t face, float halfThickness);

/// Swept candidates: valid pairs whose swept face boxes overlap, sorted. O(faces^2).
std::vector<FacePair> twinSweptCandidates(const std::vector<std::uint32_t>& faceIndices,
                                          const std::vector<std::uint32_t>& faceObject,
                                          const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                                          double thickness, const PairRules& rules);

/// The four nodes of a feature pair in the CCD's order: (vertex, face corners) or (edge a, edge b).
std::array<std::uint32_t, 4> vertexFaceNodes(const std::vector<std::uint32_t>& faceIndices,
                                             const IndexPair& vf);
std::array<std::uint32_t, 4> edgeEdgeNodes(const std::vector<std::uint32_t>& faceIndices,
                                           const IndexPair& ee);

/// What the Ccd stage computes for a substep.
struct FeatureCcdResult {
    std::vector<float> nodeToi; ///< per node, its earliest time of impact; +inf when none
    std::uint32_t vertexFaceHits = 0, edgeEdgeHits = 0, capped = 0, boxes = 0;
    float earliestToi = 0.0f; ///< +inf when no pair may touch
};

/// The Ccd stage on the feature pairs `pairs` over [x0, x1], with the GPU's budget and minimum
/// separation (both as the kernel reads them: float).
FeatureCcdResult featureCcd(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                            const std::vector<glm::vec3>& x1, const FeaturePairList& pairs,
                            std::uint32_t budget, float minSeparation);

} // namespace glcollide::cpu
