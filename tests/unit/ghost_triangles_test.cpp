// Boundary loops and ghost triangles (src/model/ghost_triangles.cpp), checked against facts that do
// not use the loop code: edge counts by brute force over the faces, the grid's border nodes from
// their positions, shoelace areas, Euler's formula, the union-find components of the boundary
// edges, and the divergence theorem (a closed outward surface encloses a positive volume equal to
// the solid's).

#include "model/ghost_triangles.hpp"
#include "scene/scene_detail.hpp"
#include "tube_mesh.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace glcollide {
namespace {

using model::BoundaryLoop;
using model::GhostSettings;
using model::GhostTriangles;
using model::LoopFill;
using model::Triangle;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();
const std::string kExternal = GLCOLLIDE_TEST_DATA_DIR "/external/";

using DirectedCounts = std::map<std::pair<std::uint32_t, std::uint32_t>, int>;

/// How often each directed edge a -> b is run by `faces` (brute force, no sorting tricks).
DirectedCounts directedEdgeCounts(const std::vector<Triangle>& faces) {
    DirectedCounts counts;
    for (const Triangle& f : faces)
        for (int k = 0; k < 3; ++k) ++counts[{f[k], f[(k + 1) % 3]}];
    return counts;
}

/// Undirected edges with exactly one face.
std::set<std::pair<std::uint32_t, std::uint32_t>> oneFaceEdges(const std::vector<Triangle>& faces) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> undirected;
    for (const auto& [edge, count] : directedEdgeCounts(faces))
        undirected[std::minmax(edge.first, edge.second)] += count;
    std::set<std::pair<std::uint32_t, std::uint32_t>> result;
    for (const auto& [edge, count] : undirected)
        if (count == 1) result.insert(edge);
    return result;
}

/// Closed and consistently oriented: every edge run exactly once in each direction.
bool closedAndConsistent(const std::vector<Triangle>& faces) {
    const DirectedCounts counts = directedEdgeCounts(faces);
    for (const auto& [edge, count] : counts) {
        if (count != 1) return false;
        const auto reverse = counts.find({edge.second, edge.first});
        if (reverse == counts.end() || reverse->second != 1) return false;
    }
    return true;
}

/// Edges of a loop, in its direction (the closing edge only when the loop is closed).
std::vector<std::pair<std::uint32_t, std::uint32_t>> loopEdges(const BoundaryLoop& loop) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    const std::size_t n = loop.nodes.size();
    for (std::size_t k = 0; k + 1 < n; ++k) edges.emplace_back(loop.nodes[k], loop.nodes[k + 1]);
    if (loop.closed && n > 0) edges.emplace_back(loop.nodes.back(), loop.nodes.front());
    return edges;
}

/// Every loop edge a -> b is a one-face edge whose face runs it a -> b.
void expectRunAsTheirFaces(const std::vector<Triangle>& faces, const BoundaryLoop& loop) {
    const DirectedCounts counts = directedEdgeCounts(faces);
    const auto boundary = oneFaceEdges(faces);
    for (const auto& [a, b] : loopEdges(loop)) {
        EXPECT_TRUE(boundary.count(std::minmax(a, b))) << a << "-" << b << " is no boundary edge";
        EXPECT_EQ(counts.count({a, b}), 1u)
            << "the face of " << a << "-" << b << " runs it " << b << "->" << a;
    }
}

/// Twice the signed area of a loop projected on the XY plane (shoelace): > 0 counter-clockwise.
double shoelace(const BoundaryLoop& loop, const std::vector<glm::dvec3>& p) {
    double twice = 0.0;
    for (const auto& [a, b] : loopEdges(loop)) twice += p[a].x * p[b].y - p[b].x * p[a].y;
    return twice;
}

/// Signed volume enclosed by closed faces (divergence theorem: sum of p0 · (p1 × p2) / 6) and the
/// sum of |p0| |p1| |p2| / 6 that bounds its rounding error.
std::pair<double, double> signedVolume(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& p) {
    double volume = 0.0, magnitude = 0.0;
    for (const Triangle& f : faces) {
        volume += glm::dot(p[f[0]], glm::cross(p[f[1]], p[f[2]])) / 6.0;
        magnitude += glm::length(p[f[0]]) * glm::length(p[f[1]]) * glm::length(p[f[2]]) / 6.0;
    }
    return {volume, magnitude};
}

/// Real faces followed by the ghost faces; positions followed by the ghost nodes.
std::vector<Triangle> withGhostFaces(std::vector<Triangle> faces, const GhostTriangles& g) {
    faces.insert(faces.end(), g.faces.begin(), g.faces.end());
    return faces;
}
std::vector<glm::dvec3> withGhostNodes(std::vector<glm::dvec3> p, const GhostTriangles& g) {
    const std::vector<glm::dvec3> ghosts = model::ghostNodePositions(g, p);
    p.insert(p.end(), ghosts.begin(), ghosts.end());
    return p;
}

/// Union-find roots.
std::uint32_t rootOf(std::vector<std::uint32_t>& parent, std::uint32_t n) {
    while (parent[n] != n) n = parent[n] = parent[parent[n]];
    return n;
}

/// Number of connected pieces of the graph of `edges` over the nodes they touch.
std::size_t pieces(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges, std::size_t nodeCount) {
    std::vector<std::uint32_t> parent(nodeCount);
    std::iota(parent.begin(), parent.end(), 0u);
    std::set<std::uint32_t> touched;
    for (const auto& [a, b] : edges) {
        parent[rootOf(parent, a)] = rootOf(parent, b);
        touched.insert(a);
        touched.insert(b);
    }
    std::set<std::uint32_t> roots;
    for (const std::uint32_t n : touched) roots.insert(rootOf(parent, n));
    return roots.size();
}

/// The n × n cloth of side 1 m without the faces inside the square [lo, hi]² (a hole of whole cells).
detail::SurfaceMesh clothWithSquareHole(int n, double lo, double hi) {
    const Body cloth = detail::generateCloth(1.0, 1.0, n, n, false, false);
    const auto inHole = [&](const glm::dvec3& p) {
        const double slack = 1e-9; // grid positions are within rounding of the cell corners
        return p.x >= lo - slack && p.x <= hi + slack && p.y >= lo - slack && p.y <= hi + slack;
    };
    detail::SurfaceMesh m{cloth.positions, {}};
    for (const auto& f : cloth.faces)
        if (!(inHole(cloth.positions[f[0]]) && inHole(cloth.positions[f[1]]) &&
              inHole(cloth.positions[f[2]])))
            m.faces.push_back(f);
    return m;
}

// ---- closed surfaces ----

TEST(GhostLoops, ClosedSurfacesHaveNone) {
    for (const Body& body : {detail::generateTetBox({1, 2, 3}, {2, 3, 2}), detail::generateSphere(1.0, 2)}) {
        ASSERT_TRUE(oneFaceEdges(body.faces).empty()); // the generators' surfaces are closed
        EXPECT_TRUE(model::boundaryLoops(body.faces, body.positions.size()).empty());
        EXPECT_TRUE(model::nonManifoldEdges(body.faces).empty());
        const GhostTriangles g = model::ghostTriangles(body.faces, body.positions, {kInf, kInf});
        EXPECT_TRUE(g.faces.empty());
        EXPECT_TRUE(g.ghostNodeLoop.empty());
    }
}

// ---- a cloth: one loop around the border ----

TEST(GhostLoops, SquareClothHasOneLoopAroundItsBorder) {
    for (const int n : {2, 3, 7}) {
        const Body cloth = detail::generateCloth(2.0, 2.0, n, n, false, false);
        const auto loops = model::boundaryLoops(cloth.faces, cloth.positions.size());
        ASSERT_EQ(loops.size(), 1u) << n;
        const BoundaryLoop& loop = loops[0];
        EXPECT_TRUE(loop.closed);
        EXPECT_TRUE(loop.pinchNodes.empty());
        EXPECT_EQ(loop.nodes.size(), 4u * (n - 1));
        // Its nodes: exactly the grid nodes on the border (|x| or |y| = 1 m), each once.
        std::set<std::uint32_t> border;
        for (std::uint32_t v = 0; v < cloth.positions.size(); ++v)
            if (std::abs(cloth.positions[v].x) == 1.0 || std::abs(cloth.positions[v].y) == 1.0)
                border.insert(v);
        EXPECT_EQ(std::set<std::uint32_t>(loop.nodes.begin(), loop.nodes.end()), border);
        EXPECT_EQ(loop.nodes.front(), *border.begin()); // starts at its lowest node
        expectRunAsTheirFaces(cloth.faces, loop);
        // Faces face +Z, so their border runs counter-clockwise seen from +Z: area 2 m × 2 m.
        // Tolerance: the grid coordinates are exact multiples of 2 / (n - 1) up to one rounding.
        EXPECT_NEAR(shoelace(loop, cloth.positions), 2.0 * 4.0, 64 * kEps * 4.0 * n);
    }
}

TEST(GhostLoops, LoopSizeOfTheClothBorder) {
    const int n = 5;
    const Body cloth = detail::generateCloth(2.0, 1.0, n, n, false, false);
    const auto loops = model::boundaryLoops(cloth.faces, cloth.positions.size());
    ASSERT_EQ(loops.size(), 1u);
    const model::LoopSize size = model::loopSize(loops[0], cloth.positions);
    // Perimeter 2 (2 + 1) m; centroid the centre (the border nodes are symmetric); radius the
    // half diagonal. Tolerance: 16 edge lengths and sums, each a few roundings of numbers <= 6.
    const double tol = 64 * kEps * 6.0;
    EXPECT_NEAR(size.perimeter, 6.0, tol);
    EXPECT_NEAR(size.centroid.x, 0.0, tol);
    EXPECT_NEAR(size.centroid.y, 0.0, tol);
    EXPECT_NEAR(size.radius, std::sqrt(1.0 + 0.25), tol);
}

TEST(GhostLoops, IndependentOfFaceOrderAndFirstCorner) {
    const detail::SurfaceMesh m = clothWithSquareHole(9, -0.25, 0.25);
    std::vector<Triangle> shuffled(m.faces.size());
    // A fixed permutation (7 and the face count are coprime) and a cyclic turn of each face,
    // which keeps its orientation.
    ASSERT_EQ(std::gcd(std::size_t{7}, m.faces.size()), 1u);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
        const Triangle& t = m.faces[(7 * f) % m.faces.size()];
        shuffled[f] = f % 2 ? Triangle{t[1], t[2], t[0]} : t;
    }
    const auto a = model::boundaryLoops(m.faces, m.positions.size());
    const auto b = model::boundaryLoops(shuffled, m.positions.size());
    ASSERT_EQ(a.size(), 2u);
    ASSERT_EQ(b.size(), a.size());
    for (std::size_t l = 0; l < a.size(); ++l) EXPECT_EQ(a[l].nodes, b[l].nodes) << l;
}

// ---- a tube: two loops, closed by ghosts ----

TEST(GhostTriangles, TubeIsClosedAndOrientedAfterFilling) {
    const std::uint32_t ring = 12, rings = 5;
    const double radius = 0.3, length = 1.1;
    const detail::SurfaceMesh m = test::tube(ring, rings, radius, length, false);
    const GhostTriangles g = model::ghostTriangles(m.faces, m.positions, {kInf, kInf});
    ASSERT_EQ(g.loops.size(), 2u);
    for (const BoundaryLoop& loop : g.loops) {
        EXPECT_TRUE(loop.closed);
        EXPECT_EQ(loop.nodes.size(), ring);
        expectRunAsTheirFaces(m.faces, loop);
    }
    EXPECT_EQ(g.fill, std::vector<LoopFill>(2, LoopFill::Filled));
    ASSERT_EQ(g.ghostNodeLoop.size(), 2u);
    EXPECT_EQ(g.faces.size(), 2u * ring);
    EXPECT_FALSE(closedAndConsistent(m.faces));
    EXPECT_TRUE(closedAndConsistent(withGhostFaces(m.faces, g)));

    // Ghost nodes at the ring centres (0, 0, 0) and (0, 0, length): the mean of a regular polygon.
    // Tolerance: a sum of 12 positions of size <= radius + length, each with one rounding of
    // cos / sin, then a division.
    const std::vector<glm::dvec3> ghosts = model::ghostNodePositions(g, m.positions);
    const double tolCentre = 4 * ring * kEps * (radius + length);
    for (std::size_t k = 0; k < ghosts.size(); ++k) {
        const double z = g.loops[g.ghostNodeLoop[k]].nodes.front() < ring ? 0.0 : length;
        EXPECT_NEAR(glm::distance(ghosts[k], glm::dvec3(0, 0, z)), 0.0, tolCentre) << k;
    }

    // Divergence theorem: the capped tube is the prism over a regular 12-gon of circumradius
    // `radius`: volume (ring / 2) r² sin(2 pi / ring) · length > 0. Tolerance: each triple product
    // (about 8 roundings) and the sum over F terms (<= F roundings), measured against the sum of
    // |p0| |p1| |p2| / 6, plus the ghost nodes' own error (tolCentre) times the largest face
    // area factor; 2 (F + 16) eps covers both.
    const auto all = withGhostFaces(m.faces, g);
    const auto [volume, magnitude] = signedVolume(all, withGhostNodes(m.positions, g));
    const double prism = ring / 2.0 * radius * radius * std::sin(2.0 * std::numbers::pi / ring) * length;
    EXPECT_GT(volume, 0.0);
    EXPECT_NEAR(volume, prism,
                2.0 * static_cast<double>(all.size() + 16) * kEps * magnitude + tolCentre * radius * length);
}

TEST(GhostTriangles, InwardTubeEnclosesNegativeVolume) {
    // The same tube with every face flipped: the loops and ghosts flip with it, so the closed
    // surface encloses minus the prism's volume (the ghosts follow the real faces, never a fixed
    // direction).
    const std::uint32_t ring = 9, rings = 3;
    const detail::SurfaceMesh m = test::tube(ring, rings, 0.5, 0.7, true);
    const GhostTriangles g = model::ghostTriangles(m.faces, m.positions, {kInf, kInf});
    ASSERT_EQ(g.faces.size(), 2u * ring);
    const auto all = withGhostFaces(m.faces, g);
    EXPECT_TRUE(closedAndConsistent(all));
    const auto [volume, magnitude] = signedVolume(all, withGhostNodes(m.positions, g));
    const double prism = ring / 2.0 * 0.25 * std::sin(2.0 * std::numbers::pi / ring) * 0.7;
    // Tolerance: as in TubeIsClosedAndOrientedAfterFilling.
    EXPECT_NEAR(volume, -prism,
                2.0 * static_cast<double>(all.size() + 16) * kEps * magnitude +
                    4 * ring * kEps * 1.2 * 0.5 * 0.7);
}

// ---- a cloth with a small hole: the hole is filled, the border is not ----

TEST(GhostTriangles, SmallHoleFilledBorderNot) {
    // 9 × 9 nodes, cells of 1/8 m; the hole is the 4 cells of [-0.125, 0.125]²: perimeter 1 m,
    // 8 edges. The border: 4 m, 32 edges. Threshold 2 m between them.
    const detail::SurfaceMesh m = clothWithSquareHole(9, -0.125, 0.125);
    // Euler for a disc with one hole (genus 0, b = 2): V - E + F = 0.
    // The centre node lies inside the hole and belongs to no face: count the nodes the faces use.
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::set<std::uint32_t> used;
    for (const auto& [e, count] : directedEdgeCounts(m.faces)) {
        edges.insert(std::minmax(e.first, e.second));
        used.insert(e.first);
    }
    ASSERT_EQ(static_cast<long>(used.size()) - static_cast<long>(edges.size()) +
                  static_cast<long>(m.faces.size()),
              0);

    const GhostTriangles g = model::ghostTriangles(m.faces, m.positions, {2.0, kInf});
    ASSERT_EQ(g.loops.size(), 2u);
    std::size_t hole = 0;
    for (std::size_t l = 0; l < 2; ++l) {
        expectRunAsTheirFaces(m.faces, g.loops[l]);
        if (g.loops[l].nodes.size() == 8) hole = l;
    }
    const std::size_t border = 1 - hole;
    EXPECT_EQ(g.loops[hole].nodes.size(), 8u);
    EXPECT_EQ(g.loops[border].nodes.size(), 32u);
    // The border (around the surface) runs counter-clockwise seen from +Z, the hole clockwise:
    // shoelace areas +1 m² and -(1/4)² m². Tolerance: a few roundings of coordinates <= 0.5.
    EXPECT_NEAR(shoelace(g.loops[border], m.positions), 2.0, 256 * kEps);
    EXPECT_NEAR(shoelace(g.loops[hole], m.positions), -2.0 * 0.0625, 256 * kEps);

    EXPECT_EQ(g.fill[hole], LoopFill::Filled);
    EXPECT_EQ(g.fill[border], LoopFill::TooLarge);
    EXPECT_EQ(g.faces.size(), 8u);
    ASSERT_EQ(g.ghostNodeLoop, std::vector<std::uint32_t>{static_cast<std::uint32_t>(hole)});
    for (const Triangle& t : g.faces) EXPECT_EQ(t[2], m.positions.size()); // ghost node 0
    // After filling, the only one-face edges are the border's, and every other edge is run once
    // each way.
    const auto all = withGhostFaces(m.faces, g);
    std::set<std::pair<std::uint32_t, std::uint32_t>> borderEdges;
    for (const auto& [a, b] : loopEdges(g.loops[border])) borderEdges.insert(std::minmax(a, b));
    EXPECT_EQ(oneFaceEdges(all), borderEdges);
    const DirectedCounts counts = directedEdgeCounts(all);
    for (const auto& [e, count] : counts) {
        EXPECT_EQ(count, 1) << e.first << "->" << e.second;
        if (!borderEdges.count(std::minmax(e.first, e.second))) {
            EXPECT_EQ(counts.count({e.second, e.first}), 1u) << e.first << "->" << e.second;
        }
    }
    // The threshold is inclusive and both limits must hold.
    EXPECT_EQ(model::ghostTriangles(m.faces, m.positions, {0.5, kInf}).fill[hole], LoopFill::TooLarge);
    EXPECT_EQ(model::ghostTriangles(m.faces, m.positions, {kInf, 0.1}).fill[hole], LoopFill::TooLarge);
    EXPECT_EQ(model::ghostTriangles(m.faces, m.positions, {kInf, kInf}).fill[border], LoopFill::Filled);
}

// ---- non-manifold input: reported, never looping ----

TEST(GhostLoops, BowTieReportsItsPinchNode) {
    // Two triangles sharing only node 0.
    const std::vector<Triangle> faces = {{0, 1, 2}, {0, 3, 4}};
    const std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
    const auto loops = model::boundaryLoops(faces, p.size());
    ASSERT_EQ(loops.size(), 2u);
    EXPECT_EQ(loops[0].nodes, (std::vector<std::uint32_t>{0, 1, 2}));
    EXPECT_EQ(loops[1].nodes, (std::vector<std::uint32_t>{0, 3, 4}));
    for (const BoundaryLoop& loop : loops) {
        EXPECT_TRUE(loop.closed);
        EXPECT_EQ(loop.pinchNodes, std::vector<std::uint32_t>{0});
    }
    const GhostTriangles g = model::ghostTriangles(faces, p, {kInf, kInf});
    EXPECT_EQ(g.fill, std::vector<LoopFill>(2, LoopFill::Pinched));
    EXPECT_TRUE(g.faces.empty());
}

TEST(GhostLoops, TwoClothsTouchingAtACornerSplitAtTheirWedges) {
    // Two 4 × 4 cloths; the second's top-left node is the first's bottom-right node. The pinch
    // node has two incoming and two outgoing boundary edges: each loop must stay on its own cloth.
    const int n = 4;
    const Body cloth = detail::generateCloth(1.0, 1.0, n, n, false, false);
    const std::uint32_t pinch = n * n - 1; // the first cloth's bottom-right node (index j n + i)
    std::vector<Triangle> faces = cloth.faces;
    std::vector<glm::dvec3> p = cloth.positions;
    std::vector<std::uint32_t> second(n * n); // the second cloth's node -> combined index
    const glm::dvec3 shift = cloth.positions[pinch] - cloth.positions[0];
    for (std::uint32_t v = 0; v < second.size(); ++v) {
        second[v] = v == 0 ? pinch : static_cast<std::uint32_t>(p.size());
        if (v != 0) p.push_back(cloth.positions[v] + shift);
    }
    for (const auto& f : cloth.faces) faces.push_back({second[f[0]], second[f[1]], second[f[2]]});
    // Swap labels so that the second cloth's boundary edge out of the pinch goes to node 1: a
    // chain of the first cloth (from node 0) that took the lowest outgoing edge at the pinch would
    // cross over; only turning around the pinch through the faces keeps it on its cloth.
    const DirectedCounts counts = directedEdgeCounts(faces);
    std::uint32_t q = 0;
    for (const auto& [a, b] : oneFaceEdges(faces)) {
        const std::uint32_t other = a == pinch ? b : b == pinch ? a : 0;
        if (other >= static_cast<std::uint32_t>(n * n) && counts.count({pinch, other})) q = other;
    }
    ASSERT_NE(q, 0u);
    std::vector<bool> onFirst(p.size());
    for (std::uint32_t v = 0; v < p.size(); ++v) onFirst[v] = v < static_cast<std::uint32_t>(n * n);
    const auto relabel = [q](std::uint32_t v) { return v == q ? 1u : v == 1u ? q : v; };
    for (auto& f : faces)
        for (auto& v : f) v = relabel(v);
    std::swap(p[1], p[q]);
    const bool firstOfQ = onFirst[q];
    onFirst[q] = onFirst[1];
    onFirst[1] = firstOfQ;
    onFirst[pinch] = true;

    const auto loops = model::boundaryLoops(faces, p.size());
    ASSERT_EQ(loops.size(), 2u);
    for (std::size_t l = 0; l < 2; ++l) {
        EXPECT_TRUE(loops[l].closed);
        EXPECT_EQ(loops[l].nodes.size(), 4u * (n - 1));
        EXPECT_EQ(loops[l].pinchNodes, std::vector<std::uint32_t>{pinch});
        expectRunAsTheirFaces(faces, loops[l]);
        const auto offPinch = std::find_if(loops[l].nodes.begin(), loops[l].nodes.end(),
                                           [&](std::uint32_t v) { return v != pinch; });
        ASSERT_NE(offPinch, loops[l].nodes.end());
        const bool first = onFirst[*offPinch];
        for (const std::uint32_t v : loops[l].nodes)
            EXPECT_TRUE(v == pinch || onFirst[v] == first) << "loop " << l << " node " << v;
    }
}

TEST(GhostLoops, EdgeWithThreeFacesReportedAndNotFilled) {
    const std::vector<Triangle> faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    const std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    EXPECT_EQ(model::nonManifoldEdges(faces), (std::vector<std::array<std::uint32_t, 2>>{{0, 1}}));
    const GhostTriangles g = model::ghostTriangles(faces, p, {kInf, kInf});
    // Every one-face edge (6 of them) lies on exactly one chain; nothing is filled.
    std::multiset<std::pair<std::uint32_t, std::uint32_t>> chained;
    for (const BoundaryLoop& loop : g.loops)
        for (const auto& [a, b] : loopEdges(loop)) chained.insert(std::minmax(a, b));
    const auto boundary = oneFaceEdges(faces);
    EXPECT_EQ(chained,
              (std::multiset<std::pair<std::uint32_t, std::uint32_t>>(boundary.begin(), boundary.end())));
    EXPECT_TRUE(g.faces.empty());
    for (const LoopFill fill : g.fill) EXPECT_NE(fill, LoopFill::Filled);
}

TEST(GhostLoops, InconsistentOrientationEndsOpen) {
    // Both faces run 0 -> 1: the boundary chains 1 -> 2 -> 0 and 1 -> 3 -> 0 lead nowhere.
    const std::vector<Triangle> faces = {{0, 1, 2}, {0, 1, 3}};
    const std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
    const GhostTriangles g = model::ghostTriangles(faces, p, {kInf, kInf});
    ASSERT_EQ(g.loops.size(), 2u);
    for (const BoundaryLoop& loop : g.loops) EXPECT_FALSE(loop.closed);
    EXPECT_EQ(g.fill, std::vector<LoopFill>(2, LoopFill::NotClosed));
    EXPECT_TRUE(g.faces.empty());
}

TEST(GhostLoops, NodeOutOfRangeThrows) {
    EXPECT_THROW(model::boundaryLoops({{0, 1, 5}}, 3), std::out_of_range);
}

// ---- the DEDO mask (tests/data/external/dedo-cloth-with-holes/mask_0.obj) ----

TEST(GhostTriangles, DedoMaskLoopsMatchEulerAndBoundaryPieces) {
    const detail::SurfaceMesh m = detail::importSurfaceMesh(kExternal + "dedo-cloth-with-holes/mask_0.obj");
    const auto boundary = oneFaceEdges(m.faces);
    // Independent loop count 1: the pieces of the boundary-edge graph, valid when every boundary
    // node has exactly two boundary edges (checked).
    std::map<std::uint32_t, int> boundaryDegree;
    for (const auto& [a, b] : boundary) ++boundaryDegree[a], ++boundaryDegree[b];
    for (const auto& [node, degree] : boundaryDegree) ASSERT_EQ(degree, 2) << "node " << node;
    const std::size_t boundaryPieces = pieces({boundary.begin(), boundary.end()}, m.positions.size());
    // Independent loop count 2: Euler, V - E + F = 2 c - 2 g - b, with c the connected pieces of
    // the surface and genus g = 0 (a flat cut sheet).
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::set<std::uint32_t> used;
    for (const auto& [e, count] : directedEdgeCounts(m.faces)) {
        edges.insert(std::minmax(e.first, e.second));
        used.insert(e.first);
    }
    const std::size_t components = pieces({edges.begin(), edges.end()}, m.positions.size());
    const long euler =
        static_cast<long>(used.size()) - static_cast<long>(edges.size()) + static_cast<long>(m.faces.size());
    const long eulerLoops = 2 * static_cast<long>(components) - euler;

    // m: between the ear loops (1.29 m) and the rim (3.71 m), printed below; docs/culling.md.
    const double threshold = 2.0;
    const GhostTriangles g = model::ghostTriangles(m.faces, m.positions, {threshold, kInf});
    EXPECT_EQ(g.loops.size(), boundaryPieces);
    EXPECT_EQ(static_cast<long>(g.loops.size()), eulerLoops);
    std::size_t chainedEdges = 0;
    for (std::size_t l = 0; l < g.loops.size(); ++l) {
        const BoundaryLoop& loop = g.loops[l];
        EXPECT_TRUE(loop.closed);
        EXPECT_TRUE(loop.pinchNodes.empty());
        expectRunAsTheirFaces(m.faces, loop);
        chainedEdges += loop.nodes.size();
        // Filled exactly when the perimeter, summed here again, is at most the threshold.
        double perimeter = 0.0;
        for (const auto& [a, b] : loopEdges(loop)) perimeter += glm::distance(m.positions[a], m.positions[b]);
        EXPECT_EQ(g.fill[l] == LoopFill::Filled, perimeter <= threshold) << "loop " << l;
        std::cout << "mask loop " << l << ": " << loop.nodes.size() << " edges, perimeter " << perimeter
                  << " m, radius " << g.sizes[l].radius << " m, "
                  << (g.fill[l] == LoopFill::Filled ? "filled" : "not filled") << "\n";
    }
    EXPECT_EQ(chainedEdges, boundary.size());
    // Every loop filled: the mask becomes a closed, consistently oriented surface.
    const GhostTriangles all = model::ghostTriangles(m.faces, m.positions, {kInf, kInf});
    EXPECT_EQ(all.ghostNodeLoop.size(), g.loops.size());
    EXPECT_TRUE(closedAndConsistent(withGhostFaces(m.faces, all)));
    std::cout << "mask: V " << m.positions.size() << ", E " << edges.size() << ", F " << m.faces.size()
              << ", components " << components << ", loops " << g.loops.size() << "\n";
}

} // namespace
} // namespace glcollide
