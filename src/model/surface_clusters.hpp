#pragma once
// Clusters of an open surface for radial view-based culling (issue 24, decision 0025 "Clusters"):
// a surface that no single observer sees from inside (a flat sheet, a mask folding over a ball)
// is cut into clusters of its rest shape, grown under a normal-cone bound, and each cluster is
// closed by ghost fans into a surface of its own with an observer of its own behind it. The
// culling then frees faces per cluster and culls only pairs within one cluster. GL-free;
// docs/culling.md, "Clusters".

#include "model/ghost_triangles.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <numbers>
#include <vector>

namespace glcollide::model {

/// How clusters grow (surfaceClusters).
struct ClusterSettings {
    /// Half-angle (radians) of each cluster's normal cone: a face joins a cluster when the angle
    /// between its unit normal and the cluster's seed face's normal (at the given positions) is at
    /// most this. Range (0, π/2); default π/4. Smaller: flatter clusters, more of them, fewer pairs
    /// within one (only those are culled); larger: deeper observers (clusterObserverDepth).
    double maxAngle = std::numbers::pi / 4.0;
    /// Growth stops after the breadth-first layer that brings a cluster to this many faces or more,
    /// so clusters stay patches small enough to fold little even where the rest shape is flat
    /// (a sheet). 0: no limit; then a flat sheet is one cluster.
    std::uint32_t maxFaces = 0;
};

/// A partition of a surface's faces into clusters.
struct SurfaceClusters {
    std::vector<std::uint32_t> faceCluster; ///< per face: its cluster, 0 .. count - 1
    /// Per cluster: the unit normal of the face that seeded it (zero for a degenerate seed); every
    /// face of the cluster is within ClusterSettings::maxAngle of it (or degenerate).
    std::vector<glm::dvec3> axes;
    std::uint32_t count = 0;
};

/// Region growing: the lowest face not yet in a cluster seeds the next one, which grows breadth
/// first, one whole layer at a time, across edges that exactly two faces run in opposite
/// directions (manifold, consistently oriented) to faces whose normal lies within
/// settings.maxAngle of the seed's, until a layer brings it to settings.maxFaces or more. Then a
/// few rounds move a face two of whose neighbours lie in one other cluster there (within that
/// cluster's cone), and clusters are renumbered into edge-connected pieces (by lowest face). A face
/// with a zero normal (degenerate) joins any cluster that reaches it; as a seed it stays alone.
/// Round patches with few notches are what a cluster's observer sees best (docs/culling.md,
/// "Clusters"). Deterministic for a given face order. Throws std::out_of_range for a node index
/// >= positions.size() and std::invalid_argument for an angle outside (0, π/2).
SurfaceClusters surfaceClusters(const std::vector<Triangle>& faces, const std::vector<glm::dvec3>& positions,
                                const ClusterSettings& settings);

/// How far behind its cluster an observer stands, in units of the cluster's outer loop radius:
/// 1 / cos²(maxAngle). Why: a face within maxAngle of the cluster's axis, at most one radius from
/// the loop's centroid, keeps an observer that far behind the centroid on its back side while the
/// cluster keeps roughly its rest shape (a bowl as deep as the cone allows included). Deeper costs
/// nothing but footprint precision; shallower leaves tilted rim faces unproven.
double clusterObserverDepth(double maxAngle);

/// Where a loop stands: m, the mean of its nodes; â, its unit vector area (Newell:
/// Σ (x_i − m) × (x_{i+1} − m) normalised, which points to the side the faces spanning the loop
/// face; zero when the loop has no vector area); R, the nodes' largest distance from m.
struct LoopFrame {
    glm::dvec3 mean{0.0};
    glm::dvec3 axis{0.0};
    double radius = 0.0;
};
LoopFrame loopFrame(const std::vector<glm::dvec3>& loop);

/// What a ghost node of a cluster's closure is, from its loop's frame (m, â, R) and a depth d (in
/// loop radii): the loop's mean (the fan over a hole inside the cluster); the apex m − d·R·â; or a
/// skirt node x − d·R·â straight behind one loop node x.
enum class GhostKind : std::uint8_t { LoopMean, Apex, Skirt };

/// The closure of one cluster's outer loop (docs/culling.md, "Clusters"): with D the observer's
/// depth (clusterObserverDepth), a skirt hangs from the loop, each loop node x joined to a skirt
/// node x − 2D·R·â (two ghost faces per loop edge), and a fan closes the skirt's lower rim at the
/// apex m − 3D·R·â; the observer stands at m − D·R·â, above the skirt's lower rim and inside. Why a
/// skirt and not one fan from the loop to the apex: seen from the observer, a fan face spans from
/// the loop's direction to straight behind, so its footprint meets every face of the cluster — one
/// fan face not proven positive (a notch in the loop) would free nothing; a skirt face's footprint
/// is a narrow sliver by its loop edge, and the lower fan's lies behind the observer.
inline constexpr double kSkirtDepth = 2.0; ///< skirt nodes' depth, in observer depths
inline constexpr double kApexDepth = 3.0;  ///< the apex's depth, in observer depths

/// One ghost node of a closure.
struct ClusterGhostNode {
    std::uint32_t loop = 0; ///< index into ClusterClosure::loops: the frame it is placed by
    GhostKind kind = GhostKind::LoopMean;
    std::uint32_t hang = 0; ///< Skirt: the caller's node it hangs behind
    double depth = 0.0;     ///< Apex and Skirt: d, in loop radii
};

/// A ghost node's position at the given positions (of the caller's nodes): loopFrame of its loop,
/// then the formula of its kind.
glm::dvec3 ghostNodePosition(const ClusterGhostNode& node,
                             const std::vector<std::vector<std::uint32_t>>& loops,
                             const std::vector<glm::dvec3>& positions);

/// One cluster closed for the culling: every boundary loop of its faces found (model::boundaryLoops);
/// the outer loop (the largest perimeter) gets the skirt and apex above, every other loop (a hole
/// inside the cluster) a fan around its mean, as model::ghostTriangles makes them.
struct ClusterClosure {
    bool closed = false; ///< every loop closed and unpinched, and the result closed, oriented and connected
    /// Per loop: its nodes in loop order (the caller's node indices).
    std::vector<std::vector<std::uint32_t>> loops;
    std::uint32_t outerLoop = 0;
    std::vector<ClusterGhostNode> ghostNodes;
    /// Ghost faces: node n < positions.size() is the caller's node n, else ghost node
    /// n − positions.size().
    std::vector<Triangle> faces;
    std::vector<glm::dvec3> ghostPositions; ///< per ghost node, at the given positions
    glm::dvec3 observer{0.0};               ///< at the given positions
    double observerDepth = 0.0;             ///< D, in the outer loop's radii
    /// Six times the signed volume the cluster and its ghosts bound at the given positions:
    /// positive when they wind outward, seen from the observer's side (decision 0025, "Orientation").
    double volume6 = 0.0;
};
ClusterClosure closeCluster(const std::vector<Triangle>& clusterFaces,
                            const std::vector<glm::dvec3>& positions, double observerDepth);

} // namespace glcollide::model
