#pragma once
// CPU twin of RadialClassify (passes/radial_classify.hpp): the same GLSL (common/radial_sign.glsl)
// compiled as C++, one face after another.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glcollide::cpu {

/// Segment observers (decision 0025, "Segment observers"): per observer k, segmentEnds[2k] and
/// segmentEnds[2k + 1] are the segment's second end B at t = 0 and t = 1 (the first end is the
/// observer's point in `observers`) with w = 1, or w = 0 for a point observer. Empty: all points.
using RadialSegmentEnds = std::vector<glm::vec4>;

/// One observed face as RadialClassify sees it: proven positive, its footprint cone, and for a
/// segment observer its feet (the interval of u its points' feet lie in; [0, 1] for a point
/// observer or a cone of every direction).
struct RadialFaceView {
    bool positive = false;
    glm::vec4 cone{0.0f, 0.0f, 1.0f, -1.0f};
    glm::vec2 feet{0.0f, 1.0f};
};

/// RadialClassify's view of face f, turned round first when `inward`.
RadialFaceView radialFaceView(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                              const std::vector<glm::vec3>& x1, std::size_t f, std::uint32_t observer,
                              const std::vector<glm::vec3>& observers, const RadialSegmentEnds& segmentEnds,
                              bool inward = false);

/// Bit f % 32 of word f / 32 set when face f (node indices faceIndices[3f .. 3f+2]) is proven
/// positive for its observer over x0 → x1; observers[2k], observers[2k + 1]: observer k at t = 0
/// and t = 1; faceObserver[f] = 0xffffffff: no observer, never positive.
std::vector<std::uint32_t>
radialPositiveMask(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                   const std::vector<glm::vec3>& x1, const std::vector<std::uint32_t>& faceObserver,
                   const std::vector<glm::vec3>& observers, const RadialSegmentEnds& segmentEnds = {});

/// Decision 0025's free faces, by brute force: face f is free when it is proven positive for its
/// observer and its footprint (cone, and feet for a segment observer) meets that of no face of the
/// same observer that is not positive. A free face cannot intersect another face of its observer's
/// closed surface during the substep (the theorem of decision 0025, under its conditions (a) and
/// (b)); faces of other observers and faces without one are not covered. 1 per free face.
std::vector<std::uint8_t> radialFreeFaces(const std::vector<std::uint32_t>& faceIndices,
                                          const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                                          const std::vector<std::uint32_t>& faceObserver,
                                          const std::vector<glm::vec3>& observers,
                                          const RadialSegmentEnds& segmentEnds = {});

/// RadialWinding's twin (decision 0025, "The winding number"): per observer, the signed crossings
/// of the ray from observers[k] (its position at x0) along GLC_RADIAL_RAY with the faces whose
/// faceObserver is k (each turned round when inward[k]), by the same certified predicate
/// (glcRadialRayCrossing), and whether some crossing was undecided. `faceIndices`, `x0`: real and
/// ghost faces and nodes together.
struct RadialWindingNumber {
    std::int32_t number = 0;
    bool undecided = false;
};
std::vector<RadialWindingNumber> radialWindingNumbers(const std::vector<std::uint32_t>& faceIndices,
                                                      const std::vector<glm::vec3>& x0,
                                                      const std::vector<std::uint32_t>& faceObserver,
                                                      const std::vector<glm::vec3>& observers,
                                                      const std::vector<bool>& inward);

/// A face pair of a closed surface made of real and ghost faces: indices into the concatenation of
/// the real faces and then the ghost faces (face f >= realFaces is ghost face f - realFaces).
using RadialFacePair = std::array<std::uint32_t, 2>;

/// Violated pairs (issue 24; decision 0025, "The premise without a winding-number pass"): at one
/// state, the pairs of a real and a ghost face, or of two ghost faces, of one surface closed by
/// ghost triangles that intersect (the engine's exact test, glcTriTriExact) and share no node. The
/// theorem's premise needs the closed surface embedded at the start of the substep; the engine's
/// TriTri checks the real pairs, and this the pairs with a ghost face. One such pair and the
/// surface's observer must not cull in that substep. `faceIndices`: 3 per face, real faces first
/// (`realFaces` of them), then the ghost faces; `positions`: real nodes, then ghost nodes. Brute
/// force with a box test first; sorted, each pair (lower, higher) once. Throws glcollide::Error
/// when the exact test cannot decide a pair (glcExactFailed).
std::vector<RadialFacePair> radialViolatedPairs(const std::vector<std::uint32_t>& faceIndices,
                                                std::size_t realFaces,
                                                const std::vector<glm::vec3>& positions);

} // namespace glcollide::cpu
