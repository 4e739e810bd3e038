#pragma once
// CPU twin of the linear BVH broad phase (src/passes/broad_phase/bvh_broad_phase.*): Morton codes
// in the same float operations, the Karras hierarchy with escape links in the same integer
// arithmetic (so it must equal the GPU's links exactly, given the same sorted keys), the refit in
// the same float min/max (exact), and the stackless traversal. Node numbering as in
// shaders/common/bvh.glsl: internal nodes 0 .. n-2 (root 0), the leaf of sorted face i at n-1+i;
// links (x, y, z, w) = (left | face, right | sorted index, parent, escape).

#include "cpu/collision_twin.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::cpu {

inline constexpr std::uint32_t kBvhNone = 0xFFFFFFFFu;

/// The 30-bit Morton code of `centroid` on a grid of 1024^3 cubes over the bounds [lo, hi]: every
/// axis scaled by the largest extent (bvh_morton.comp).
std::uint32_t mortonCode(const glm::vec3& centroid, const glm::vec3& lo, const glm::vec3& hi);

/// The centre of face f's vertex box (bvh_centroid.glsl).
glm::vec3 faceCentroid(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& positions,
                       std::uint32_t face);

/// Karras 2012 over keys sorted ascending (ties broken by index), with parents and escapes.
std::vector<glm::uvec4> twinHierarchy(const std::vector<std::uint32_t>& sortedKeys,
                                      const std::vector<std::uint32_t>& sortedFaces);

/// Every node's box: leaves the inflated face boxes (cpu::faceBox), internal nodes the union of
/// their children.
std::vector<FloatBox> twinRefit(const std::vector<glm::uvec4>& links,
                                const std::vector<std::uint32_t>& faceIndices,
                                const std::vector<glm::vec3>& positions, float halfThickness);

/// The traversal of bvh_traverse.comp: valid pairs whose leaf boxes overlap, (lower, higher)
/// face, each once; `nodeVisits` (if not null) receives the nodes tested. Unsorted.
std::vector<FacePair> twinBvhCandidates(const std::vector<glm::uvec4>& links,
                                        const std::vector<FloatBox>& boxes,
                                        const std::vector<std::uint32_t>& faceIndices,
                                        const std::vector<std::uint32_t>& faceObject, const PairRules& rules,
                                        std::uint64_t* nodeVisits = nullptr);

} // namespace glcollide::cpu
