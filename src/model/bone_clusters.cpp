// Clusters of a surface by the bones of a skeleton (bone_clusters.hpp).

#include "model/bone_clusters.hpp"

#include "model/features.hpp"
#include "model/radial_surfaces.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace glcollide::model {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

std::uint32_t nearestBone(const glm::dvec3& x, const std::vector<Bone>& bones) {
    std::uint32_t best = 0;
    double bestDistance = squaredDistanceToBone(x, bones[0]);
    for (std::uint32_t b = 1; b < bones.size(); ++b) {
        const double d = squaredDistanceToBone(x, bones[b]);
        if (d < bestDistance) { // strictly: a tie stays with the lower bone
            best = b;
            bestDistance = d;
        }
    }
    return best;
}

} // namespace

double squaredDistanceToBone(const glm::dvec3& x, const Bone& bone) {
    const glm::dvec3 axis = bone[1] - bone[0];
    const double length2 = glm::dot(axis, axis);
    const double u = length2 > 0.0 ? std::clamp(glm::dot(x - bone[0], axis) / length2, 0.0, 1.0) : 0.0;
    const glm::dvec3 d = x - (bone[0] + u * axis);
    return glm::dot(d, d);
}

BoneClusters boneClusters(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& positions,
                          const std::vector<Bone>& bones) {
    if (bones.empty()) throw std::invalid_argument("a skeleton needs at least one bone");
    for (std::size_t b = 0; b < bones.size(); ++b)
        if (bones[b][0] == bones[b][1])
            throw std::invalid_argument("bone " + std::to_string(b) + " has no length (its ends are equal)");
    std::vector<std::uint32_t> bone(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        for (std::uint32_t n : faces[f])
            if (n >= positions.size())
                throw std::out_of_range("face " + std::to_string(f) + " names node " + std::to_string(n) +
                                        " of " + std::to_string(positions.size()));
        const Triangle& t = faces[f];
        bone[f] = nearestBone((positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3.0, bones);
    }
    // Pieces: union-find over the edges two faces of one bone share (any direction: a piece that
    // is not consistently oriented fails its closure, it is not split further).
    std::vector<std::uint32_t> parent(faces.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&parent](std::uint32_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::unordered_map<std::uint64_t, std::uint32_t> firstUser;
    for (std::uint32_t f = 0; f < faces.size(); ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
            if (a == b) continue;
            const auto [it, fresh] = firstUser.emplace(edgeKey(a, b), f);
            if (!fresh && bone[it->second] == bone[f]) {
                const std::uint32_t ra = root(it->second), rb = root(f);
                parent[std::max(ra, rb)] = std::min(ra, rb); // the lowest face is the root
            }
        }
    BoneClusters clusters;
    clusters.faceCluster.assign(faces.size(), kNone);
    std::vector<std::uint32_t> pieceOfRoot(faces.size(), kNone);
    for (std::uint32_t f = 0; f < faces.size(); ++f) {
        const std::uint32_t r = root(f);
        if (pieceOfRoot[r] == kNone) {
            pieceOfRoot[r] = clusters.count++;
            clusters.clusterBone.push_back(bone[f]);
        }
        clusters.faceCluster[f] = pieceOfRoot[r];
    }
    return clusters;
}

BoneClosure closeBoneCluster(const std::vector<Triangle>& pieceFaces,
                             const std::vector<glm::dvec3>& positions) {
    BoneClosure closure;
    GhostSettings fillEvery;
    fillEvery.maxPerimeter = std::numeric_limits<double>::infinity();
    closure.ghosts = ghostTriangles(pieceFaces, positions, fillEvery);
    for (const LoopFill fill : closure.ghosts.fill)
        if (fill != LoopFill::Filled) return closure;
    std::vector<std::uint32_t> all;
    for (const Triangle& t : pieceFaces) all.insert(all.end(), t.begin(), t.end());
    for (const Triangle& t : closure.ghosts.faces) all.insert(all.end(), t.begin(), t.end());
    const auto count = static_cast<std::uint32_t>(all.size() / 3);
    if (!isClosedOrientedConnected(all, 0, count)) return closure;
    std::vector<glm::dvec3> x = positions;
    for (const glm::dvec3& g : ghostNodePositions(closure.ghosts, positions)) x.push_back(g);
    for (std::size_t f = 0; f < all.size(); f += 3)
        closure.volume6 += glm::dot(x[all[f]], glm::cross(x[all[f + 1]], x[all[f + 2]]));
    closure.closed = true;
    return closure;
}

} // namespace glcollide::model
