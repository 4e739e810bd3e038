#include "cpu/collision_twin.hpp"

#include "cpu/oracle/exact_tri_tri.hpp"
#include "model/face_box.hpp"

#include <glm/common.hpp>

#include <limits>

namespace glcollide::cpu {

bool boxesOverlap(const FloatBox& a, const FloatBox& b) {
    return a.lo.x <= b.hi.x && a.lo.y <= b.hi.y && a.lo.z <= b.hi.z && b.lo.x <= a.hi.x && b.lo.y <= a.hi.y &&
           b.lo.z <= a.hi.z;
}

FloatBox faceBox(const std::vector<std::uint32_t>& faceIndices, const std::vector<glm::vec3>& positions,
                 std::uint32_t face, float halfThickness) {
    const glm::vec3& p0 = positions[faceIndices[3 * static_cast<std::size_t>(face)]];
    const glm::vec3& p1 = positions[faceIndices[3 * static_cast<std::size_t>(face) + 1]];
    const glm::vec3& p2 = positions[faceIndices[3 * static_cast<std::size_t>(face) + 2]];
    // min/max are exact; the two float subtractions/additions round exactly like the GPU's
    // (GLSL + and - are correctly rounded), so the boxes are bit-identical.
    return {glm::min(glm::min(p0, p1), p2) - glm::vec3(halfThickness),
            glm::max(glm::max(p0, p1), p2) + glm::vec3(halfThickness)};
}

bool validFacePair(const std::vector<std::uint32_t>& faceIndices,
                   const std::vector<std::uint32_t>& faceObject, std::uint32_t f, std::uint32_t g,
                   const PairRules& rules) {
    if (f == g) return false;
    if (faceObject[f] != faceObject[g]) return rules.betweenObjects;
    if (!rules.selfCollisions) return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (faceIndices[3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(i)] ==
                faceIndices[3 * static_cast<std::size_t>(g) + static_cast<std::size_t>(j)])
                return false;
    return true;
}

std::vector<FloatBox> twinLeafBoxes(const model::OctreeLayout& layout,
                                    const std::vector<std::uint32_t>& faceIndices,
                                    const std::vector<glm::vec3>& positions, double thickness) {
    const float half = model::halfThicknessFloat(thickness);
    constexpr float kInf = std::numeric_limits<float>::infinity();
    std::vector<FloatBox> boxes(layout.boxCount, FloatBox{glm::vec3(kInf), glm::vec3(-kInf)});
    for (std::uint32_t b = 0; b < layout.boxCount; ++b) {
        FloatBox& box = boxes[b];
        for (std::uint32_t k = layout.boxFaces.offsets[b]; k < layout.boxFaces.offsets[b + 1]; ++k) {
            const std::uint32_t f = layout.boxFaces.items[k];
            for (int c = 0; c < 3; ++c) {
                const glm::vec3& p =
                    positions[faceIndices[3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(c)]];
                box.lo = glm::min(box.lo, p);
                box.hi = glm::max(box.hi, p);
            }
        }
        box.lo -= glm::vec3(half);
        box.hi += glm::vec3(half);
    }
    return boxes;
}

std::vector<FacePair> twinCandidates(const std::vector<std::uint32_t>& faceIndices,
                                     const std::vector<std::uint32_t>& faceObject,
                                     const std::vector<glm::vec3>& positions, double thickness,
                                     const PairRules& rules) {
    const float half = model::halfThicknessFloat(thickness);
    const auto faces = static_cast<std::uint32_t>(faceIndices.size() / 3);
    std::vector<FloatBox> boxes(faces);
    for (std::uint32_t f = 0; f < faces; ++f) boxes[f] = faceBox(faceIndices, positions, f, half);
    return overlappingValidPairs(faceIndices, faceObject, boxes, rules);
}

std::vector<FacePair> overlappingValidPairs(const std::vector<std::uint32_t>& faceIndices,
                                            const std::vector<std::uint32_t>& faceObject,
                                            const std::vector<FloatBox>& boxes, const PairRules& rules) {
    const auto faces = static_cast<std::uint32_t>(boxes.size());
    std::vector<FacePair> pairs;
    for (std::uint32_t f = 0; f < faces; ++f)
        for (std::uint32_t g = f + 1; g < faces; ++g)
            if (validFacePair(faceIndices, faceObject, f, g, rules) && boxesOverlap(boxes[f], boxes[g]))
                pairs.push_back({f, g});
    return pairs;
}

std::vector<FacePair> twinIntersections(const std::vector<std::uint32_t>& faceIndices,
                                        const std::vector<glm::vec3>& positions,
                                        const std::vector<FacePair>& pairs) {
    auto triangle = [&](std::uint32_t f) {
        Triangle t;
        for (std::size_t c = 0; c < 3; ++c)
            t[c] = glm::dvec3(positions[faceIndices[3 * static_cast<std::size_t>(f) + c]]);
        return t;
    };
    std::vector<FacePair> out;
    for (const FacePair& p : pairs)
        if (exactTrianglesIntersect(triangle(p[0]), triangle(p[1]))) out.push_back(p);
    return out;
}

std::vector<std::vector<FacePair>> twinIntersectionsAlongMotion(const std::vector<std::uint32_t>& faceIndices,
                                                                const std::vector<std::uint32_t>& faceObject,
                                                                const std::vector<glm::vec3>& x0,
                                                                const std::vector<glm::vec3>& x1,
                                                                const PairRules& rules, int samples) {
    std::vector<std::vector<FacePair>> out;
    for (int k = 1; k <= samples; ++k) {
        const float t = static_cast<float>(k) / static_cast<float>(samples);
        std::vector<glm::vec3> x(x0.size());
        for (std::size_t i = 0; i < x.size(); ++i) x[i] = x0[i] + t * (x1[i] - x0[i]);
        out.push_back(
            twinIntersections(faceIndices, x, twinCandidates(faceIndices, faceObject, x, 0.0, rules)));
    }
    return out;
}

} // namespace glcollide::cpu
