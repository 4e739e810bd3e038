#include "cpu/ccd_twin.hpp"

#include "cpu/ccd_library.hpp"
#include "model/face_box.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <limits>

namespace glcollide::cpu {

FloatBox sweptFaceBox(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                      const std::vector<glm::vec3>& x1, std::uint32_t face, float halfThickness) {
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (std::size_t c = 0; c < 3; ++c) {
        const std::uint32_t n = faceIndices[3 * static_cast<std::size_t>(face) + c];
        lo = glm::min(glm::min(lo, x0[n]), x1[n]); // min and max are exact: any order gives these
        hi = glm::max(glm::max(hi, x0[n]), x1[n]);
    }
    return {lo - glm::vec3(halfThickness), hi + glm::vec3(halfThickness)};
}

std::vector<FacePair> twinSweptCandidates(const std::vector<std::uint32_t>& faceIndices,
                                          const std::vector<std::uint32_t>& faceObject,
                                          const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                                          double thickness, const PairRules& rules) {
    const float half = model::halfThicknessFloat(thickness);
    const auto faces = static_cast<std::uint32_t>(faceIndices.size() / 3);
    std::vector<FloatBox> boxes(faces);
    for (std::uint32_t f = 0; f < faces; ++f) boxes[f] = sweptFaceBox(faceIndices, x0, x1, f, half);
    return overlappingValidPairs(faceIndices, faceObject, boxes, rules);
}

std::array<std::uint32_t, 4> vertexFaceNodes(const std::vector<std::uint32_t>& faceIndices,
                                             const IndexPair& vf) {
    const std::size_t f = 3 * static_cast<std::size_t>(vf[1]);
    return {vf[0], faceIndices[f], faceIndices[f + 1], faceIndices[f + 2]};
}

std::array<std::uint32_t, 4> edgeEdgeNodes(const std::vector<std::uint32_t>& faceIndices,
                                           const IndexPair& ee) {
    const auto corner = [&](std::uint32_t edge, std::uint32_t k) {
        return faceIndices[3 * static_cast<std::size_t>(edge / 3) + (edge % 3 + k) % 3];
    };
    return {corner(ee[0], 0), corner(ee[0], 1), corner(ee[1], 0), corner(ee[1], 1)};
}

FeatureCcdResult featureCcd(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& x0,
                            const std::vector<glm::vec3>& x1, const FeaturePairList& pairs,
                            std::uint32_t budget, float minSeparation) {
    constexpr float kNone = std::numeric_limits<float>::infinity();
    FeatureCcdResult r;
    r.nodeToi.assign(x0.size(), kNone);
    r.earliestToi = kNone;
    const auto test = [&](bool edgeEdge, const std::array<std::uint32_t, 4>& n) {
        const bool hit =
            shader::glcCcdInclusion(edgeEdge, x0[n[0]], x0[n[1]], x0[n[2]], x0[n[3]], x1[n[0]], x1[n[1]],
                                    x1[n[2]], x1[n[3]], minSeparation, static_cast<int>(budget));
        r.boxes += static_cast<std::uint32_t>(shader::glcCcdBoxes);
        if (shader::glcCcdCapped) ++r.capped;
        if (!hit) return;
        ++(edgeEdge ? r.edgeEdgeHits : r.vertexFaceHits);
        r.earliestToi = std::min(r.earliestToi, shader::glcCcdToi);
        for (std::uint32_t node : n) r.nodeToi[node] = std::min(r.nodeToi[node], shader::glcCcdToi);
    };
    for (const IndexPair& vf : pairs.vertexFace) test(false, vertexFaceNodes(faceIndices, vf));
    for (const IndexPair& ee : pairs.edgeEdge) test(true, edgeEdgeNodes(faceIndices, ee));
    return r;
}

} // namespace glcollide::cpu
