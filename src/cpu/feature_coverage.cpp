#include "cpu/feature_coverage.hpp"

#include "cpu/ccd_twin.hpp"
#include "cpu/contact_twin.hpp"
#include "model/face_box.hpp"
#include "model/features.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <set>

namespace glcollide::cpu {

OwnershipCoverage ownershipCoverage(const std::vector<std::uint32_t>& faceIndices,
                                    const std::vector<std::uint32_t>& faceObject,
                                    const std::vector<glm::vec3>& positions, double thickness,
                                    const PairRules& rules) {
    const auto faces = static_cast<std::uint32_t>(faceIndices.size() / 3);
    // Faces around each node and each edge, in increasing face index: the first is the owner.
    std::vector<std::vector<std::uint32_t>> nodeFaces(positions.size());
    std::map<std::uint64_t, std::vector<std::uint32_t>> edgeFaces;
    for (std::uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = model::faceEdge(faceIndices, f, k);
            nodeFaces[a].push_back(f);
            edgeFaces[model::edgeKey(a, b)].push_back(f);
        }
    const auto x = [&](std::uint32_t n) { return glm::dvec3(positions[n]); };
    const auto anyValid = [&](const std::vector<std::uint32_t>& fs, const std::vector<std::uint32_t>& gs) {
        for (std::uint32_t f : fs)
            for (std::uint32_t g : gs)
                if (f != g && validFacePair(faceIndices, faceObject, f, g, rules)) return true;
        return false;
    };
    OwnershipCoverage c;
    for (std::uint32_t v = 0; v < nodeFaces.size(); ++v) {
        if (nodeFaces[v].empty()) continue;
        for (std::uint32_t g = 0; g < faces; ++g) {
            const std::uint32_t* n = &faceIndices[3 * std::size_t{g}];
            if (n[0] == v || n[1] == v || n[2] == v) continue;
            const glm::dvec3 w = closestOnTriangle(x(v), x(n[0]), x(n[1]), x(n[2]));
            const double d = glm::length(x(v) - (w.x * x(n[0]) + w.y * x(n[1]) + w.z * x(n[2])));
            if (!(d < thickness) || !anyValid(nodeFaces[v], {g})) continue;
            ++c.vertexFaceNear;
            if (!validFacePair(faceIndices, faceObject, nodeFaces[v].front(), g, rules)) ++c.vertexFaceLost;
        }
    }
    std::vector<std::pair<std::uint64_t, const std::vector<std::uint32_t>*>> edges;
    for (const auto& [key, around] : edgeFaces) edges.emplace_back(key, &around);
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const auto a0 = static_cast<std::uint32_t>(edges[i].first >> 32);
        const auto a1 = static_cast<std::uint32_t>(edges[i].first);
        for (std::size_t j = i + 1; j < edges.size(); ++j) {
            const auto b0 = static_cast<std::uint32_t>(edges[j].first >> 32);
            const auto b1 = static_cast<std::uint32_t>(edges[j].first);
            if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) continue;
            const auto [s, t] = closestSegmentParams(x(a0), x(a1), x(b0), x(b1));
            const double d = glm::length((x(a0) + s * (x(a1) - x(a0))) - (x(b0) + t * (x(b1) - x(b0))));
            if (!(d < thickness) || !anyValid(*edges[i].second, *edges[j].second)) continue;
            ++c.edgeEdgeNear;
            if (!validFacePair(faceIndices, faceObject, edges[i].second->front(), edges[j].second->front(),
                               rules))
                ++c.edgeEdgeLost;
        }
    }
    return c;
}

namespace {

// The swept box of nodes `nodes` over x0 -> x1, inflated by `half`: sweptFaceBox's operations on a
// subset of a face's nodes, so it lies inside the box of every face containing them.
template <std::size_t N>
FloatBox sweptFeatureBox(const std::array<std::uint32_t, N>& nodes, const std::vector<glm::vec3>& x0,
                         const std::vector<glm::vec3>& x1, float half) {
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const std::uint32_t n : nodes) {
        lo = glm::min(glm::min(lo, x0[n]), x1[n]);
        hi = glm::max(glm::max(hi, x0[n]), x1[n]);
    }
    return {lo - glm::vec3(half), hi + glm::vec3(half)};
}

} // namespace

CcdCoverage ccdCoverage(const std::vector<std::uint32_t>& faceIndices,
                        const std::vector<std::uint32_t>& faceObject, const std::vector<glm::vec3>& x0,
                        const std::vector<glm::vec3>& x1, double thickness, const PairRules& rules,
                        const FeaturePairList& pairs) {
    const auto faces = static_cast<std::uint32_t>(faceIndices.size() / 3);
    const float half = model::halfThicknessFloat(thickness);
    std::set<IndexPair> seenVertexFace;
    std::set<std::array<std::uint64_t, 2>> seenEdgeEdge;
    const auto edgeKeyOf = [&](std::uint32_t edge) {
        const auto [a, b] = model::faceEdge(faceIndices, edge / 3, static_cast<int>(edge % 3));
        return model::edgeKey(a, b);
    };
    std::uint64_t vertexFaceRepeated = 0, edgeEdgeRepeated = 0;
    for (const IndexPair& vf : pairs.vertexFace)
        vertexFaceRepeated += seenVertexFace.insert(vf).second ? 0u : 1u;
    for (const IndexPair& ee : pairs.edgeEdge) {
        const std::uint64_t a = edgeKeyOf(ee[0]), b = edgeKeyOf(ee[1]);
        edgeEdgeRepeated += seenEdgeEdge.insert({std::min(a, b), std::max(a, b)}).second ? 0u : 1u;
    }
    std::vector<FloatBox> boxes(faces);
    for (std::uint32_t f = 0; f < faces; ++f) boxes[f] = sweptFaceBox(faceIndices, x0, x1, f, half);
    std::set<IndexPair> neededVertexFace;
    std::set<std::array<std::uint64_t, 2>> neededEdgeEdge;
    const auto corner = [&](std::uint32_t f, std::uint32_t k) { return faceIndices[3 * std::size_t{f} + k]; };
    const auto vertexAgainst = [&](std::uint32_t p, std::uint32_t face) {
        if (boxesOverlap(sweptFeatureBox(std::array{p}, x0, x1, half), boxes[face]))
            neededVertexFace.insert({p, face});
    };
    for (const auto& [a, b] : overlappingValidPairs(faceIndices, faceObject, boxes, rules)) {
        for (std::uint32_t k = 0; k < 3;
             ++k) { // a valid pair shares no node: no vertex lies in the other face
            vertexAgainst(corner(a, k), b);
            vertexAgainst(corner(b, k), a);
        }
        for (std::uint32_t e = 0; e < 3; ++e)
            for (std::uint32_t g = 0; g < 3; ++g) {
                const auto ea = model::faceEdge(faceIndices, a, static_cast<int>(e));
                const auto eb = model::faceEdge(faceIndices, b, static_cast<int>(g));
                if (!boxesOverlap(sweptFeatureBox(ea, x0, x1, half), sweptFeatureBox(eb, x0, x1, half)))
                    continue;
                const std::uint64_t ka = model::edgeKey(ea[0], ea[1]), kb = model::edgeKey(eb[0], eb[1]);
                neededEdgeEdge.insert({std::min(ka, kb), std::max(ka, kb)});
            }
    }
    CcdCoverage c;
    c.vertexFaceRepeated = vertexFaceRepeated;
    c.edgeEdgeRepeated = edgeEdgeRepeated;
    c.vertexFaceNeeded = neededVertexFace.size();
    c.edgeEdgeNeeded = neededEdgeEdge.size();
    for (const IndexPair& p : neededVertexFace) c.vertexFaceMissing += seenVertexFace.count(p) ? 0u : 1u;
    for (const auto& p : neededEdgeEdge) c.edgeEdgeMissing += seenEdgeEdge.count(p) ? 0u : 1u;
    return c;
}

} // namespace glcollide::cpu
