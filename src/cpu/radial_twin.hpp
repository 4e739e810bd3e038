#pragma once
// CPU twin of RadialClassify (passes/radial_classify.hpp): the same GLSL (common/radial_sign.glsl)
// compiled as C++, one face after another.

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::cpu {

/// Bit f % 32 of word f / 32 set when face f (node indices faceIndices[3f .. 3f+2]) is proven
/// positive for its observer over x0 → x1; observers[2k], observers[2k + 1]: observer k at t = 0
/// and t = 1; faceObserver[f] = 0xffffffff: no observer, never positive.
std::vector<std::uint32_t> radialPositiveMask(const std::vector<std::uint32_t>& faceIndices,
                                              const std::vector<glm::vec3>& x0,
                                              const std::vector<glm::vec3>& x1,
                                              const std::vector<std::uint32_t>& faceObserver,
                                              const std::vector<glm::vec3>& observers);

/// Decision 0025's free faces, by brute force: face f is free when it is proven positive for its
/// observer and its footprint cone meets the cone of no face of the same observer that is not
/// positive. A free face cannot intersect another face of its observer's closed surface during the
/// substep (the theorem of decision 0025, under its conditions (a) and (b)); faces of other
/// observers and faces without one are not covered. 1 per free face.
std::vector<std::uint8_t> radialFreeFaces(const std::vector<std::uint32_t>& faceIndices,
                                          const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                                          const std::vector<std::uint32_t>& faceObserver,
                                          const std::vector<glm::vec3>& observers);

} // namespace glcollide::cpu
