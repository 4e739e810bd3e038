#pragma once
// Ghost triangles (issue 24, radial view-based culling): boundary loops of an open surface and the
// fans of "ghost" triangles that close the small ones (a sleeve's openings, a mask's ear holes), so
// that the surface seen by the culling is closed and consistently oriented. Ghosts take part in the
// culling's classification only; they never collide and never move nodes. GL-free; docs/culling.md.
//
// Orientation convention: a body's faces are counter-clockwise seen from outside (Body::faces). A
// boundary edge (an undirected node pair with exactly one face) is listed in the direction its face
// runs it; a loop is a chain of such directed edges. A ghost triangle runs its loop edge the other
// way, as the missing neighbour face would, so real and ghost faces together use every edge once in
// each direction.

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace glcollide::model {

/// A triangle by its three node indices, in winding order (as Body::faces).
using Triangle = std::array<std::uint32_t, 3>;

/// One chain of boundary edges. Edge k runs nodes[k] -> nodes[k + 1] (and, when closed, the last
/// edge nodes.back() -> nodes.front()), each in the direction of the one real face that has it.
struct BoundaryLoop {
    /// The chain's nodes. A closed loop starts at its lowest node (by its lowest-target outgoing
    /// edge when that node is a pinch node); an open chain at the lowest node that still had an
    /// unused outgoing boundary edge. So the order is reproducible.
    std::vector<std::uint32_t> nodes;
    /// False when the chain ran into a node with no unused outgoing boundary edge before coming
    /// back to its first edge: faces oriented inconsistently, or an edge with three or more faces
    /// next to the boundary. Such a chain is reported, never filled.
    bool closed = true;
    /// Nodes of this loop where several boundary wedges meet (a bow-tie or pinch vertex: two fans
    /// of faces touching at one node), sorted, each once. Empty for a manifold boundary.
    std::vector<std::uint32_t> pinchNodes;
};

/// Every boundary edge (an edge with exactly one face) chained into loops; see BoundaryLoop for
/// direction, start and order (loops sorted by their first edge). Never loops forever: every step
/// uses up one boundary edge.
///
/// Non-manifold input is reported, not repaired:
/// - a pinch node (several boundary wedges through one node) is split deterministically: a chain
///   arriving at it leaves by the boundary edge of the same wedge, found by turning around the node
///   through the faces between them (the walk follows interior edges shared by exactly two faces
///   with opposite directions). When that walk fails (non-manifold or inconsistent faces at the
///   node) it leaves by the unused outgoing edge with the lowest target node. The loops keep the
///   pinch node in pinchNodes;
/// - an edge with three or more faces is no boundary edge (see nonManifoldEdges); the chains next
///   to it may end open (BoundaryLoop::closed false).
/// Faces with a repeated node contribute no edge between equal nodes. Throws std::out_of_range for
/// a node index >= nodeCount.
std::vector<BoundaryLoop> boundaryLoops(const std::vector<Triangle>& faces, std::size_t nodeCount);

/// Undirected edges {lo, hi} (lo < hi) with three or more faces, sorted. Empty for a manifold surface.
std::vector<std::array<std::uint32_t, 2>> nonManifoldEdges(const std::vector<Triangle>& faces);

/// Size of a loop at given node positions.
struct LoopSize {
    double perimeter = 0.0;   ///< m: sum of the loop's edge lengths (closing edge included)
    glm::dvec3 centroid{0.0}; ///< m: mean of the loop's node positions (the ghost node's place)
    double radius = 0.0;      ///< m: largest distance from the centroid to a loop node
};
LoopSize loopSize(const BoundaryLoop& loop, const std::vector<glm::dvec3>& positions);

/// When a boundary loop is closed with ghost triangles. Defaults fill nothing: which holes are
/// "small" is a property of the scene (the lead's scene layer picks the automatic default).
struct GhostSettings {
    /// Largest perimeter (m) of a loop that is filled; a loop whose perimeter is <= it is filled.
    /// Range: >= 0 (0 fills nothing, +infinity fills every closed manifold loop). Suggested: about
    /// 1.5 × the perimeter of the largest opening that should be closed (a sleeve's cuff, an ear
    /// hole), which is usually well below the perimeter of an outer rim that should stay open.
    double maxPerimeter = 0.0;
    /// Largest radius (m, LoopSize::radius) of a loop that is filled; both limits must hold. An
    /// elongated opening has a larger radius for its perimeter (a slit: about perimeter / 4; a round
    /// hole: perimeter / (2 pi)), and its fan has long thin triangles. Range: >= 0; +infinity (the
    /// default) leaves the decision to maxPerimeter. Suggested: +infinity, or about 1.5 × the radius
    /// of the largest opening that should be closed.
    double maxRadius = std::numeric_limits<double>::infinity();
};

/// Why a loop was, or was not, filled.
enum class LoopFill : std::uint8_t {
    Filled,    ///< closed with a fan of ghost triangles around a ghost node
    TooLarge,  ///< perimeter above GhostSettings::maxPerimeter or radius above maxRadius
    NotClosed, ///< BoundaryLoop::closed is false (inconsistent or non-manifold faces)
    Pinched,   ///< the loop passes a pinch node: a fan would not make the node manifold
};

/// The ghost closure of a surface. Ghost node g has index nodeCount + g (after the real nodes).
///
/// Apex choice: each filled loop gets a new ghost node at the mean of its nodes, and the fan runs
/// from it. A fan from one loop vertex instead would need no extra node, but for a non-convex loop
/// some of its triangles fold over others or degenerate to slivers (a triangle between collinear
/// loop vertices has zero area), which the classification would see as spurious non-positive
/// triangles. The mean of the loop's nodes is a fixed affine combination (weight 1/n each), so the
/// GPU recomputes it from the moved loop every substep, and it stays inside the loop's convex hull.
struct GhostTriangles {
    std::vector<BoundaryLoop> loops; ///< every loop, as boundaryLoops returns them
    std::vector<LoopSize> sizes;     ///< per loop, at the positions given
    std::vector<LoopFill> fill;      ///< per loop
    /// Per ghost node: the loop it closes. Its position is the mean of that loop's nodes (weight
    /// 1 / loops[loop].nodes.size() each; a filled loop repeats no node).
    std::vector<std::uint32_t> ghostNodeLoop;
    /// Ghost triangles, loop by loop in loop order, edge by edge in loop order: for loop edge a -> b
    /// with ghost node g, the triangle (b, a, nodeCount + g).
    std::vector<Triangle> faces;
    /// Per ghost triangle: the ghost node (0-based) at its apex.
    std::vector<std::uint32_t> faceGhostNode;
};

/// Loops of `faces` and the ghost fans of those that `settings` accepts. Node count:
/// positions.size().
GhostTriangles ghostTriangles(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& positions,
                              const GhostSettings& settings);

/// Positions of the ghost nodes (the means of their loops' nodes) at `positions`.
std::vector<glm::dvec3> ghostNodePositions(const GhostTriangles& ghosts,
                                           const std::vector<glm::dvec3>& positions);

} // namespace glcollide::model
