#include "model/features.hpp"

#include <algorithm>
#include <vector>
#include <unordered_map>

namespace glcollide::model {

std::vector<std::uint32_t> ownedFeatures(const std::vector<std::uint32_t>& faceIndices) {
    const std::size_t faces = faceIndices.size() / 3;
    std::unordered_map<std::uint32_t, std::uint32_t> nodeOwner;
    std::unordered_map<std::uint64_t, std::uint32_t> edgeOwner;
    nodeOwner.reserve(faces * 3);
    edgeOwner.reserve(faces * 3);
    // Visiting faces in increasing index, the first face to see a feature is its lowest face.
    for (std::uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            nodeOwner.try_emplace(a, f);
            edgeOwner.try_emplace(edgeKey(a, b), f);
        }
    std::vector<std::uint32_t> owned(faces, 0u);
    for (std::uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            if (nodeOwner.at(a) == f) owned[f] |= ownVertexBit(k);
            if (edgeOwner.at(edgeKey(a, b)) == f) owned[f] |= ownEdgeBit(k);
        }
    return owned;
}

std::vector<std::uint32_t> featureOwners(const std::vector<std::uint32_t>& faceIndices) {
    const auto faces = static_cast<std::uint32_t>(faceIndices.size() / 3);
    std::unordered_map<std::uint32_t, std::uint32_t> nodeOwner;
    std::unordered_map<std::uint64_t, std::uint32_t> edgeOwner;
    for (std::uint32_t f = 0; f < faces; ++f) // increasing index: the first face seen is the owner
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            nodeOwner.try_emplace(a, f);
            edgeOwner.try_emplace(edgeKey(a, b), f);
        }
    std::vector<std::uint32_t> owners(6 * static_cast<std::size_t>(faces));
    for (std::uint32_t f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            owners[6 * std::size_t{f} + static_cast<std::size_t>(k)] = nodeOwner.at(a);
            owners[6 * std::size_t{f} + 3 + static_cast<std::size_t>(k)] = edgeOwner.at(edgeKey(a, b));
        }
    return owners;
}

bool isClosedSurface(const std::vector<std::uint32_t>& faceIndices, std::uint32_t firstFace,
                     std::uint32_t faceCount) {
    if (faceCount == 0) return false;
    std::unordered_map<std::uint64_t, std::uint32_t> edgeFaces;
    edgeFaces.reserve(static_cast<std::size_t>(faceCount) * 3);
    for (std::uint32_t f = firstFace; f < firstFace + faceCount; ++f)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = faceEdge(faceIndices, f, k);
            ++edgeFaces[edgeKey(a, b)];
        }
    return std::all_of(edgeFaces.begin(), edgeFaces.end(), [](const auto& e) { return e.second == 2; });
}

std::vector<std::uint32_t> nodeFaceTable(const std::vector<std::uint32_t>& faceIndices,
                                         std::size_t nodeCount) {
    std::vector<std::vector<std::uint32_t>> around(nodeCount);
    for (std::size_t f = 0; f < faceIndices.size() / 3; ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            std::vector<std::uint32_t>& faces = around.at(faceIndices[3 * f + k]);
            if (faces.empty() || faces.back() != f)
                faces.push_back(static_cast<std::uint32_t>(f)); // faces in order
        }
    std::vector<std::uint32_t> table(nodeCount + 1);
    std::size_t next = nodeCount + 1;
    for (std::size_t n = 0; n < nodeCount; ++n) {
        table[n] = static_cast<std::uint32_t>(next);
        table.insert(table.end(), around[n].begin(), around[n].end());
        next += around[n].size();
    }
    table[nodeCount] = static_cast<std::uint32_t>(next);
    return table;
}

} // namespace glcollide::model
