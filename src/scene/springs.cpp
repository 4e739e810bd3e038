// Springs from mesh topology.
#include "scene/scene_detail.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <utility>

namespace glcollide::detail {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;

Edge makeEdge(std::uint32_t a, std::uint32_t b) {
    return a < b ? Edge{a, b} : Edge{b, a};
}

std::vector<Spring> springsFromEdges(std::vector<Edge> edges, SpringKind kind) {
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<Spring> out;
    out.reserve(edges.size());
    for (const auto& [a, b] : edges) {
        Spring s;
        s.a = a;
        s.b = b;
        s.kind = kind;
        out.push_back(s);
    }
    return out;
}

} // namespace

std::vector<Spring> surfaceEdgeSprings(const std::vector<Face>& faces, SpringKind kind) {
    std::vector<Edge> edges;
    edges.reserve(faces.size() * 3);
    for (const Face& f : faces)
        for (int i = 0; i < 3; ++i) edges.push_back(makeEdge(f[i], f[(i + 1) % 3]));
    return springsFromEdges(std::move(edges), kind);
}

std::vector<Spring> tetEdgeSprings(const std::vector<Tet>& tets) {
    std::vector<Edge> edges;
    edges.reserve(tets.size() * 6);
    for (const Tet& t : tets)
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) edges.push_back(makeEdge(t[i], t[j]));
    return springsFromEdges(std::move(edges), SpringKind::Edge);
}

std::vector<Spring> surfaceBendSprings(const std::vector<Face>& faces) {
    // Edge -> the vertices opposite it in the faces that use it.
    std::map<Edge, std::vector<std::uint32_t>> opposite;
    std::set<Edge> existing;
    for (const Face& f : faces)
        for (int i = 0; i < 3; ++i) {
            const Edge e = makeEdge(f[i], f[(i + 1) % 3]);
            opposite[e].push_back(f[(i + 2) % 3]);
            existing.insert(e);
        }
    std::vector<Edge> bends;
    std::set<Edge> seen;
    for (const auto& [edge, opp] : opposite) {
        if (opp.size() != 2 || opp[0] == opp[1]) continue; // boundary or non-manifold edge
        const Edge b = makeEdge(opp[0], opp[1]);
        // A closed tetrahedron's opposite vertices are already joined by an edge: no duplicate.
        if (existing.count(b) != 0 || !seen.insert(b).second) continue;
        bends.push_back(b);
    }
    return springsFromEdges(std::move(bends), SpringKind::Bend);
}

void setRestLengths(Body& body) {
    for (Spring& s : body.springs) s.restLength = glm::length(body.positions[s.b] - body.positions[s.a]);
}

} // namespace glcollide::detail
