// Clusters of an open surface (surface_clusters.hpp): region growing over the faces' edge
// adjacency, and the apex and observer that close and watch a cluster.

#include "model/surface_clusters.hpp"

#include "model/features.hpp"
#include "model/radial_surfaces.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace glcollide::model {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

/// Per face and edge k (corner k → corner k + 1): the face across it when exactly two faces use
/// the edge and run it in opposite directions, else kNone.
std::vector<std::array<std::uint32_t, 3>> orientedNeighbours(const std::vector<Triangle>& faces) {
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> uses; // undirected edge → faces
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (std::size_t k = 0; k < 3; ++k)
            uses[edgeKey(faces[f][k], faces[f][(k + 1) % 3])].push_back(static_cast<std::uint32_t>(f));
    std::vector<std::array<std::uint32_t, 3>> across(faces.size(), {kNone, kNone, kNone});
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
            if (a == b) continue;
            const std::vector<std::uint32_t>& users = uses[edgeKey(a, b)];
            if (users.size() != 2) continue;
            const std::uint32_t g = users[0] == f ? users[1] : users[0];
            if (g == f) continue;
            const Triangle& t = faces[g];
            for (std::size_t j = 0; j < 3; ++j)
                if (t[j] == b && t[(j + 1) % 3] == a) across[f][k] = g; // runs it b → a
        }
    return across;
}

glm::dvec3 unitNormal(const Triangle& t, const std::vector<glm::dvec3>& x) {
    const glm::dvec3 n = glm::cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]);
    const double length = glm::length(n);
    return length > 0.0 ? n / length : glm::dvec3(0.0);
}

/// A few rounds over the faces: a face two of whose three neighbours lie in one other cluster,
/// within that cluster's cone, moves there (a notch filled, a spike cut). Fewer notches, fewer
/// ghost faces seen from behind. Bounded and in face order: deterministic.
void smoothBoundaries(SurfaceClusters& c, const std::vector<std::array<std::uint32_t, 3>>& across,
                      const std::vector<glm::dvec3>& normals, const std::vector<glm::dvec3>& axes,
                      double minCos) {
    constexpr int kRounds = 4;
    for (int round = 0; round < kRounds; ++round) {
        bool moved = false;
        for (std::size_t f = 0; f < across.size(); ++f) {
            const std::array<std::uint32_t, 3>& n = across[f];
            for (int k = 0; k < 3; ++k) {
                if (n[k] == kNone) continue;
                const std::uint32_t other = c.faceCluster[n[k]];
                if (other == c.faceCluster[f]) continue;
                int there = 0;
                for (std::uint32_t g : n) there += g != kNone && c.faceCluster[g] == other ? 1 : 0;
                const bool inCone =
                    normals[f] == glm::dvec3(0.0) || glm::dot(normals[f], axes[other]) >= minCos;
                if (there >= 2 && inCone && axes[other] != glm::dvec3(0.0)) {
                    c.faceCluster[f] = other;
                    moved = true;
                }
                break; // the first neighbour of another cluster decides
            }
        }
        if (!moved) break;
    }
}

/// Renumbers the clusters so that each is one edge-connected piece (moving faces may cut one in
/// two; a cluster must be connected to be closed), numbered by their lowest face.
void splitIntoPieces(SurfaceClusters& c, const std::vector<std::array<std::uint32_t, 3>>& across) {
    std::vector<std::uint32_t> piece(c.faceCluster.size(), kNone);
    std::uint32_t count = 0;
    for (std::size_t seed = 0; seed < piece.size(); ++seed) {
        if (piece[seed] != kNone) continue;
        piece[seed] = count;
        std::vector<std::uint32_t> stack{static_cast<std::uint32_t>(seed)};
        while (!stack.empty()) {
            const std::uint32_t f = stack.back();
            stack.pop_back();
            for (std::uint32_t g : across[f])
                if (g != kNone && piece[g] == kNone && c.faceCluster[g] == c.faceCluster[f]) {
                    piece[g] = count;
                    stack.push_back(g);
                }
        }
        ++count;
    }
    std::vector<glm::dvec3> axes(count);
    for (std::size_t f = 0; f < piece.size(); ++f) axes[piece[f]] = c.axes[c.faceCluster[f]];
    c.faceCluster = std::move(piece);
    c.axes = std::move(axes);
    c.count = count;
}

} // namespace

SurfaceClusters surfaceClusters(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& positions,
                                const ClusterSettings& settings) {
    if (!(settings.maxAngle > 0.0 && settings.maxAngle < std::numbers::pi / 2.0))
        throw std::invalid_argument("surfaceClusters: the normal cone's half-angle " +
                                    std::to_string(settings.maxAngle) + " rad is not in (0, pi/2)");
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (std::uint32_t n : faces[f])
            if (n >= positions.size())
                throw std::out_of_range("surfaceClusters: face " + std::to_string(f) + " uses node " +
                                        std::to_string(n) + " of " + std::to_string(positions.size()));
    const std::vector<std::array<std::uint32_t, 3>> across = orientedNeighbours(faces);
    std::vector<glm::dvec3> normals;
    for (const Triangle& t : faces) normals.push_back(unitNormal(t, positions));
    const double minCos = std::cos(settings.maxAngle);

    SurfaceClusters result;
    result.faceCluster.assign(faces.size(), kNone);
    std::vector<glm::dvec3>& axes = result.axes;
    for (std::size_t seed = 0; seed < faces.size(); ++seed) {
        if (result.faceCluster[seed] != kNone) continue;
        const std::uint32_t cluster = result.count++;
        const glm::dvec3 axis = normals[seed];
        axes.push_back(axis);
        result.faceCluster[seed] = cluster;
        if (axis == glm::dvec3(0.0)) continue; // a degenerate seed has no direction to grow by
        // Whole breadth-first layers (rings around the seed), so a cluster is a round patch and
        // its boundary turns one way around it as far as the mesh allows: a notch in the boundary
        // makes ghost faces that its observer sees from behind (docs/culling.md, "Clusters").
        std::vector<std::uint32_t> layer{static_cast<std::uint32_t>(seed)};
        std::size_t size = 1;
        while (!layer.empty() && (settings.maxFaces == 0 || size < settings.maxFaces)) {
            std::vector<std::uint32_t> next;
            for (std::uint32_t f : layer)
                for (std::uint32_t g : across[f]) {
                    if (g == kNone || result.faceCluster[g] != kNone) continue;
                    const bool degenerate = normals[g] == glm::dvec3(0.0);
                    if (!degenerate && glm::dot(normals[g], axis) < minCos) continue;
                    result.faceCluster[g] = cluster;
                    next.push_back(g);
                }
            size += next.size();
            layer = std::move(next);
        }
    }
    smoothBoundaries(result, across, normals, axes, minCos);
    splitIntoPieces(result, across);
    return result;
}

double clusterObserverDepth(double maxAngle) {
    const double c = std::cos(maxAngle);
    return 1.0 / (c * c);
}

LoopFrame loopFrame(const std::vector<glm::dvec3>& loop) {
    LoopFrame frame;
    if (loop.empty()) return frame;
    for (const glm::dvec3& x : loop) frame.mean += x;
    frame.mean /= static_cast<double>(loop.size());
    glm::dvec3 area(0.0);
    for (std::size_t i = 0; i < loop.size(); ++i) {
        area += glm::cross(loop[i] - frame.mean, loop[(i + 1) % loop.size()] - frame.mean);
        frame.radius = std::max(frame.radius, glm::length(loop[i] - frame.mean));
    }
    const double length = glm::length(area);
    if (length > 0.0) frame.axis = area / length;
    return frame;
}

glm::dvec3 ghostNodePosition(const ClusterGhostNode& node,
                             const std::vector<std::vector<std::uint32_t>>& loops,
                             const std::vector<glm::dvec3>& positions) {
    std::vector<glm::dvec3> loop;
    for (std::uint32_t n : loops.at(node.loop)) loop.push_back(positions.at(n));
    const LoopFrame f = loopFrame(loop);
    switch (node.kind) {
    case GhostKind::LoopMean:
        return f.mean;
    case GhostKind::Apex:
        return f.mean - node.depth * f.radius * f.axis;
    case GhostKind::Skirt:
        return positions.at(node.hang) - node.depth * f.radius * f.axis;
    }
    return f.mean;
}

ClusterClosure closeCluster(const std::vector<Triangle>& clusterFaces,
                            const std::vector<glm::dvec3>& positions, double observerDepth) {
    // Local node numbers, so the loop search costs the cluster's size, not the surface's.
    std::map<std::uint32_t, std::uint32_t> local;
    for (const Triangle& t : clusterFaces)
        for (std::uint32_t n : t) {
            if (n >= positions.size())
                throw std::out_of_range("closeCluster: node " + std::to_string(n) + " of " +
                                        std::to_string(positions.size()));
            local.emplace(n, 0u);
        }
    std::vector<std::uint32_t> global;
    for (auto& [n, l] : local) {
        l = static_cast<std::uint32_t>(global.size());
        global.push_back(n);
    }
    std::vector<Triangle> faces;
    for (const Triangle& t : clusterFaces) faces.push_back({local[t[0]], local[t[1]], local[t[2]]});

    ClusterClosure c;
    c.observerDepth = observerDepth;
    const std::vector<BoundaryLoop> loops = boundaryLoops(faces, global.size());
    if (loops.empty()) return c;
    double longest = -1.0;
    for (std::uint32_t k = 0; k < loops.size(); ++k) {
        if (!loops[k].closed || !loops[k].pinchNodes.empty() || loops[k].nodes.size() < 3) return c;
        std::vector<std::uint32_t> nodes;
        double perimeter = 0.0;
        for (std::size_t i = 0; i < loops[k].nodes.size(); ++i) {
            nodes.push_back(global[loops[k].nodes[i]]);
            perimeter += glm::length(positions[global[loops[k].nodes[(i + 1) % loops[k].nodes.size()]]] -
                                     positions[nodes.back()]);
        }
        if (perimeter > longest) longest = perimeter, c.outerLoop = k;
        c.loops.push_back(std::move(nodes));
    }
    const auto nodeCount = static_cast<std::uint32_t>(positions.size());
    const auto ghost = [&](const ClusterGhostNode& g) {
        c.ghostNodes.push_back(g);
        return nodeCount + static_cast<std::uint32_t>(c.ghostNodes.size() - 1);
    };
    for (std::uint32_t k = 0; k < c.loops.size(); ++k) {
        const std::vector<std::uint32_t>& loop = c.loops[k];
        const std::size_t n = loop.size();
        if (k != c.outerLoop) { // a hole: a fan around the mean, as ghostTriangles makes it
            const std::uint32_t g = ghost({k, GhostKind::LoopMean, 0, 0.0});
            for (std::size_t i = 0; i < n; ++i) c.faces.push_back({loop[(i + 1) % n], loop[i], g});
            continue;
        }
        const std::uint32_t apex = ghost({k, GhostKind::Apex, 0, kApexDepth * observerDepth});
        std::vector<std::uint32_t> skirt;
        for (std::uint32_t x : loop)
            skirt.push_back(ghost({k, GhostKind::Skirt, x, kSkirtDepth * observerDepth}));
        for (std::size_t i = 0; i < n; ++i) {
            // Loop edge a -> b (as its real face runs it): the skirt runs it b -> a.
            const std::uint32_t a = loop[i], b = loop[(i + 1) % n], sa = skirt[i], sb = skirt[(i + 1) % n];
            c.faces.push_back({b, a, sa});
            c.faces.push_back({b, sa, sb});
            c.faces.push_back({sb, sa, apex});
        }
    }
    for (const ClusterGhostNode& g : c.ghostNodes)
        c.ghostPositions.push_back(ghostNodePosition(g, c.loops, positions));
    std::vector<glm::dvec3> outer;
    for (std::uint32_t n : c.loops[c.outerLoop]) outer.push_back(positions[n]);
    const LoopFrame frame = loopFrame(outer);
    c.observer = frame.mean - observerDepth * frame.radius * frame.axis;

    std::vector<std::uint32_t> closed;
    for (const Triangle& t : clusterFaces) closed.insert(closed.end(), t.begin(), t.end());
    for (const Triangle& t : c.faces) closed.insert(closed.end(), t.begin(), t.end());
    c.closed = isClosedOrientedConnected(closed, 0, static_cast<std::uint32_t>(closed.size() / 3));
    // Relative to the observer: a cluster far from the origin keeps its volume's precision.
    const auto at = [&](std::uint32_t n) {
        return (n < nodeCount ? positions[n] : c.ghostPositions[n - nodeCount]) - c.observer;
    };
    for (std::size_t f = 0; f < closed.size(); f += 3)
        c.volume6 += glm::dot(at(closed[f]), glm::cross(at(closed[f + 1]), at(closed[f + 2])));
    return c;
}

} // namespace glcollide::model
