// Boundary loops and ghost fans (ghost_triangles.hpp). The edges of all faces are sorted once by
// their undirected key; an edge group of one entry is a boundary edge, directed as its face runs it.

#include "model/ghost_triangles.hpp"

#include "model/features.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace glcollide::model {
namespace {

/// One face's use of an edge: from -> to in the face's winding order.
struct DirectedEdge {
    std::uint64_t key = 0; ///< edgeKey(from, to): equal for both directions
    std::uint32_t from = 0;
    std::uint32_t to = 0;
    std::uint32_t face = 0;
};

/// Every edge use of every face, sorted by (key, from, face): the uses of one undirected edge are
/// neighbours. Edges between equal nodes (a face with a repeated node) are left out.
std::vector<DirectedEdge> sortedEdgeUses(const std::vector<Triangle>& faces, std::size_t nodeCount) {
    std::vector<DirectedEdge> uses;
    uses.reserve(3 * faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = faces[f][static_cast<std::size_t>(k)];
            const std::uint32_t b = faces[f][static_cast<std::size_t>((k + 1) % 3)];
            if (a >= nodeCount || b >= nodeCount)
                throw std::out_of_range("boundaryLoops: face " + std::to_string(f) + " uses node " +
                                        std::to_string(std::max(a, b)) + " of " + std::to_string(nodeCount));
            if (a == b) continue;
            uses.push_back({edgeKey(a, b), a, b, static_cast<std::uint32_t>(f)});
        }
    std::sort(uses.begin(), uses.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
        if (x.key != y.key) return x.key < y.key;
        if (x.from != y.from) return x.from < y.from;
        return x.face < y.face;
    });
    return uses;
}

/// The uses [first, last) of the undirected edge {a, b} in `uses`.
std::pair<std::size_t, std::size_t> usesOf(const std::vector<DirectedEdge>& uses, std::uint32_t a,
                                           std::uint32_t b) {
    const std::uint64_t key = edgeKey(a, b);
    const auto byKey = [](const DirectedEdge& e, std::uint64_t k) { return e.key < k; };
    const auto first = std::lower_bound(uses.begin(), uses.end(), key, byKey);
    auto last = first;
    while (last != uses.end() && last->key == key) ++last;
    return {static_cast<std::size_t>(first - uses.begin()), static_cast<std::size_t>(last - uses.begin())};
}

/// The corner of `face` after node v in winding order (v must be a corner).
std::uint32_t nextCorner(const Triangle& face, std::uint32_t v) {
    for (std::size_t k = 0; k < 3; ++k)
        if (face[k] == v) return face[(k + 1) % 3];
    return v; // unreachable for a corner
}

/// The boundary edges and, per node, its outgoing ones.
class BoundaryEdges {
  public:
    BoundaryEdges(const std::vector<Triangle>& faces, std::size_t nodeCount)
        : faces_(faces), uses_(sortedEdgeUses(faces, nodeCount)), firstOut_(nodeCount + 1, 0) {
        for (std::size_t i = 0; i < uses_.size();) {
            const auto [first, last] = groupAt(i);
            if (last - first == 1) edges_.push_back(uses_[first]);
            i = last;
        }
        // Sorted by (from, to): the outgoing edges of a node are neighbours, lowest target first.
        std::sort(edges_.begin(), edges_.end(), [](const DirectedEdge& x, const DirectedEdge& y) {
            return x.from != y.from ? x.from < y.from : x.to < y.to;
        });
        for (const DirectedEdge& e : edges_) ++firstOut_[e.from + 1];
        for (std::size_t n = 0; n < nodeCount; ++n) firstOut_[n + 1] += firstOut_[n];
        used_.assign(edges_.size(), false);
    }

    std::size_t size() const { return edges_.size(); }
    const DirectedEdge& edge(std::size_t i) const { return edges_[i]; }
    bool used(std::size_t i) const { return used_[i]; }
    void use(std::size_t i) { used_[i] = true; }
    std::size_t outDegree(std::uint32_t node) const { return firstOut_[node + 1] - firstOut_[node]; }

    /// The edge a chain takes after arriving at `incoming`'s end node, or size() when there is none.
    std::size_t next(std::size_t incoming) const {
        const std::uint32_t v = edges_[incoming].to;
        if (outDegree(v) == 1) {
            const std::size_t only = firstOut_[v];
            return used_[only] ? size() : only;
        }
        const std::size_t sameWedge = outgoingOfWedge(incoming);
        if (sameWedge < size() && !used_[sameWedge]) return sameWedge;
        for (std::size_t i = firstOut_[v]; i < firstOut_[v + 1]; ++i)
            if (!used_[i]) return i; // fallback: the lowest unused target
        return size();
    }

  private:
    std::pair<std::size_t, std::size_t> groupAt(std::size_t i) const {
        std::size_t last = i;
        while (last < uses_.size() && uses_[last].key == uses_[i].key) ++last;
        return {i, last};
    }

    /// Turning around v = incoming.to from the face of `incoming` through interior edges (two faces,
    /// opposite directions) until an outgoing boundary edge of v: the boundary edge that closes the
    /// same wedge of faces. size() when the walk meets a non-manifold or inconsistent edge. At most
    /// one step per face, so it ends even on malformed input.
    std::size_t outgoingOfWedge(std::size_t incoming) const {
        const std::uint32_t v = edges_[incoming].to;
        std::uint32_t face = edges_[incoming].face;
        for (std::size_t step = 0; step <= faces_.size(); ++step) {
            const std::uint32_t w = nextCorner(faces_[face], v); // this face runs v -> w
            const auto [first, last] = usesOf(uses_, v, w);
            if (last - first == 1) return indexOfBoundary(v, w);
            if (last - first != 2) return size();
            const DirectedEdge& other = uses_[first].face == face ? uses_[first + 1] : uses_[first];
            if (other.from != w) return size(); // both faces run v -> w: inconsistent orientation
            face = other.face;
        }
        return size();
    }

    std::size_t indexOfBoundary(std::uint32_t from, std::uint32_t to) const {
        for (std::size_t i = firstOut_[from]; i < firstOut_[from + 1]; ++i)
            if (edges_[i].to == to) return i;
        return size();
    }

    const std::vector<Triangle>& faces_;
    std::vector<DirectedEdge> uses_;
    std::vector<DirectedEdge> edges_; ///< boundary edges sorted by (from, to)
    std::vector<std::size_t> firstOut_;
    std::vector<bool> used_;
};

/// Sorted, unique nodes of `loop` that have several outgoing boundary edges.
std::vector<std::uint32_t> pinchNodesOf(const std::vector<std::uint32_t>& loop, const BoundaryEdges& edges) {
    std::vector<std::uint32_t> pinch;
    for (const std::uint32_t n : loop)
        if (edges.outDegree(n) > 1) pinch.push_back(n);
    std::sort(pinch.begin(), pinch.end());
    pinch.erase(std::unique(pinch.begin(), pinch.end()), pinch.end());
    return pinch;
}

} // namespace

std::vector<BoundaryLoop> boundaryLoops(const std::vector<Triangle>& faces, std::size_t nodeCount) {
    BoundaryEdges edges(faces, nodeCount);
    std::vector<BoundaryLoop> loops;
    // Starting edges in (from, to) order: a loop starts at its lowest node, since all of its
    // edges are unused until it is walked.
    for (std::size_t start = 0; start < edges.size(); ++start) {
        if (edges.used(start)) continue;
        BoundaryLoop loop;
        loop.nodes.push_back(edges.edge(start).from);
        // The start edge stays unused until the loop ends, so that next() may return it: the
        // loop is closed. Every other step uses up one edge, so the walk ends.
        std::size_t current = start;
        for (;;) {
            const std::size_t following = edges.next(current);
            if (following == start) break;
            if (following >= edges.size()) {
                loop.closed = false;
                loop.nodes.push_back(edges.edge(current).to);
                break;
            }
            edges.use(following);
            loop.nodes.push_back(edges.edge(following).from);
            current = following;
        }
        edges.use(start);
        loop.pinchNodes = pinchNodesOf(loop.nodes, edges);
        loops.push_back(std::move(loop));
    }
    return loops;
}

std::vector<std::array<std::uint32_t, 2>> nonManifoldEdges(const std::vector<Triangle>& faces) {
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * faces.size());
    for (const Triangle& f : faces)
        for (std::size_t k = 0; k < 3; ++k)
            if (f[k] != f[(k + 1) % 3]) keys.push_back(edgeKey(f[k], f[(k + 1) % 3]));
    std::sort(keys.begin(), keys.end());
    std::vector<std::array<std::uint32_t, 2>> result;
    for (std::size_t i = 0; i < keys.size();) {
        std::size_t last = i;
        while (last < keys.size() && keys[last] == keys[i]) ++last;
        if (last - i >= 3)
            result.push_back({static_cast<std::uint32_t>(keys[i] >> 32),
                              static_cast<std::uint32_t>(keys[i] & 0xffffffffu)});
        i = last;
    }
    return result;
}

LoopSize loopSize(const BoundaryLoop& loop, const std::vector<glm::dvec3>& positions) {
    LoopSize size;
    const std::size_t n = loop.nodes.size();
    if (n == 0) return size;
    const std::size_t edgeCount = loop.closed ? n : n - 1;
    for (std::size_t k = 0; k < edgeCount; ++k)
        size.perimeter += glm::distance(positions[loop.nodes[k]], positions[loop.nodes[(k + 1) % n]]);
    for (const std::uint32_t node : loop.nodes) size.centroid += positions[node];
    size.centroid /= static_cast<double>(n);
    for (const std::uint32_t node : loop.nodes)
        size.radius = std::max(size.radius, glm::distance(positions[node], size.centroid));
    return size;
}

GhostTriangles ghostTriangles(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& positions,
                              const GhostSettings& settings) {
    GhostTriangles ghosts;
    ghosts.loops = boundaryLoops(faces, positions.size());
    for (std::size_t l = 0; l < ghosts.loops.size(); ++l) {
        const BoundaryLoop& loop = ghosts.loops[l];
        const LoopSize size = loopSize(loop, positions);
        ghosts.sizes.push_back(size);
        LoopFill fill = LoopFill::Filled;
        if (!loop.closed)
            fill = LoopFill::NotClosed;
        else if (!loop.pinchNodes.empty())
            fill = LoopFill::Pinched;
        else if (!(size.perimeter <= settings.maxPerimeter && size.radius <= settings.maxRadius))
            fill = LoopFill::TooLarge;
        ghosts.fill.push_back(fill);
        if (fill != LoopFill::Filled) continue;

        const auto ghost = static_cast<std::uint32_t>(ghosts.ghostNodeLoop.size());
        const auto apex = static_cast<std::uint32_t>(positions.size()) + ghost;
        ghosts.ghostNodeLoop.push_back(static_cast<std::uint32_t>(l));
        const std::size_t n = loop.nodes.size();
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint32_t a = loop.nodes[k], b = loop.nodes[(k + 1) % n];
            ghosts.faces.push_back({b, a, apex}); // runs b -> a: the real face runs a -> b
            ghosts.faceGhostNode.push_back(ghost);
        }
    }
    return ghosts;
}

std::vector<glm::dvec3> ghostNodePositions(const GhostTriangles& ghosts,
                                           const std::vector<glm::dvec3>& positions) {
    std::vector<glm::dvec3> result;
    result.reserve(ghosts.ghostNodeLoop.size());
    for (const std::uint32_t l : ghosts.ghostNodeLoop) {
        glm::dvec3 sum(0.0);
        for (const std::uint32_t node : ghosts.loops[l].nodes) sum += positions[node];
        result.push_back(sum / static_cast<double>(ghosts.loops[l].nodes.size()));
    }
    return result;
}

} // namespace glcollide::model
