#include "cpu/feature_coverage.hpp"

#include "cpu/contact_twin.hpp"
#include "model/features.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <map>

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

} // namespace glcollide::cpu
