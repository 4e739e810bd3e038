#include "model/radial_surfaces.hpp"

#include <map>
#include <numeric>
#include <utility>

namespace glcollide::model {
namespace {
struct Components {
    std::vector<std::uint32_t> parent;
    explicit Components(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    std::uint32_t root(std::uint32_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void join(std::uint32_t a, std::uint32_t b) { parent[root(a)] = root(b); }
};
} // namespace

bool isClosedOrientedConnected(const std::vector<std::uint32_t>& faceIndices, std::uint32_t firstFace,
                               std::uint32_t faceCount) {
    if (faceCount == 0) return false;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> directed; // a→b: its face
    for (std::uint32_t f = 0; f < faceCount; ++f)
        for (int k = 0; k < 3; ++k) {
            const std::size_t base = 3 * std::size_t{firstFace + f};
            const std::pair<std::uint32_t, std::uint32_t> edge{faceIndices[base + k],
                                                               faceIndices[base + (k + 1) % 3]};
            if (edge.first == edge.second || !directed.emplace(edge, f).second) return false;
        }
    Components components(faceCount);
    for (const auto& [edge, face] : directed) {
        const auto twin = directed.find({edge.second, edge.first});
        if (twin == directed.end()) return false; // an open edge, or two faces running it one way
        components.join(face, twin->second);
    }
    const std::uint32_t first = components.root(0);
    for (std::uint32_t f = 1; f < faceCount; ++f)
        if (components.root(f) != first) return false;
    return true;
}

} // namespace glcollide::model
