#pragma once
// RadialCulling — radial view-based culling (issue 24, decision 0025, docs/culling.md "Culling"):
// the first stage of a substep's collision detection when the scene asks for it. Its dispatches:
// RadialObservers (an object's observer is the centroid of its nodes at x0 and at x1), with ghost
// triangles RadialGhostNodes (ghost nodes from their loops; a cluster's observer behind it),
// RadialClassify (positive faces, footprint cones, the non-positive lists), RadialWinding (the
// observer check: each surface must wind exactly once around its observer at x0) and RadialFree
// (a positive face whose cone meets no non-positive cone of its observer, on a surface that winds
// once, is free). TriTri and the
// CCD at zero separation then leave out the pairs of a surface with a free face
// (common/radial_cull.glsl): by the decision's theorem such a pair cannot intersect, so culling
// changes the work, never the answers. CPU twin of the free set: cpu::radialFreeFaces.

#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "model/bone_clusters.hpp"
#include "model/flat_model.hpp"
#include "model/surface_clusters.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"
#include "passes/radial_classify.hpp"

#include <glcollide/scene.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

namespace glcollide::passes {

/// One observer's surface: its real faces (those whose RadialCullingConfig::faceObserver names it)
/// and its ghost faces [firstGhostFace, firstGhostFace + ghostFaceCount) (indices into the ghost
/// faces, 0-based). An object's observer is the centroid
/// of its real nodes [firstNode, firstNode + nodeCount); a cluster's (nodeCount 0) stands behind
/// the cluster, set back from the ghost node of its outer loop (RadialGhosts::observerOf).
struct RadialSurface {
    std::uint32_t firstNode = 0, nodeCount = 0;
    std::uint32_t firstGhostFace = 0, ghostFaceCount = 0;
    /// The surface's faces (real and ghost) wind inward: its signed volume is negative. The
    /// classification then turns every face round (decision 0025, "Orientation"); a wrong value
    /// frees nothing, never a face that may collide.
    bool inward = false;
    /// A user observer (Body::observer): Σ frameWeights[k]·x[frameNodes[k]] (model nodes) instead
    /// of the centroid of the surface's nodes.
    bool framed = false;
    std::array<std::uint32_t, 4> frameNodes{};
    std::array<float, 4> frameWeights{};
    /// A user segment observer (Body::observerEnd; decision 0025, "Segment observers"): the frame
    /// above is its first end, this one its second.
    bool segment = false;
    std::array<std::uint32_t, 4> segmentFrameNodes{};
    std::array<float, 4> segmentFrameWeights{};
};

/// One ghost node (docs/culling.md, "Ghost triangles" and "Clusters"; model::ClusterGhostNode):
/// placed each substep from its loop, loopNodes[loopFirst .. loopFirst + loopCount).
struct RadialGhostNode {
    std::uint32_t loopFirst = 0, loopCount = 0;
    model::GhostKind kind = model::GhostKind::LoopMean;
    std::uint32_t hang = 0; ///< Skirt: the model's node it hangs behind
    float depth = 0.0f;     ///< Apex, Skirt: in loop radii
    /// Apex of a cluster: the observer it places, observerDepth loop radii behind the loop's mean;
    /// else kNoRadialObserver.
    std::uint32_t observerOf = 0xffffffffu;
    float observerDepth = 0.0f;
};

/// Ghost nodes and faces that close the observed surfaces' holes and clusters (model::ghostTriangles
/// and model::closeCluster build them); a ghost face's node index >= the model's node count names
/// ghost node (index - node count).
struct RadialGhosts {
    std::uint32_t nodeCount = 0; ///< the model's nodes
    std::vector<std::uint32_t> loopNodes;
    std::vector<RadialGhostNode> nodes;
    std::vector<std::uint32_t> faces;        ///< 3 per ghost face
    std::vector<std::uint32_t> faceObserver; ///< per ghost face
};

/// RadialWinding's answer for one observer: the signed crossings of a ray from it with its
/// surface at x0 (the winding number), and whether some crossing could not be proven.
struct RadialWinding {
    std::int32_t number = 0;
    bool undecided = false;
    bool operator==(const RadialWinding&) const = default;
};

/// Which faces culling may consider: per face its observer's index or kNoRadialObserver, and per
/// observer its surface. The surface of an observer — its real faces and ghost faces — must be
/// closed, consistently oriented and connected (the theorem's premise).
struct RadialCullingConfig {
    std::vector<std::uint32_t> faceObserver;
    std::vector<RadialSurface> surfaces;
    RadialGhosts ghosts;
    /// Per node of the model: the observer of every face around it, kNoRadialObserver where they
    /// differ or where it has no face. A vertex-face pair is culled only when the vertex lies on
    /// the face's observer's surface; a node all of whose faces are that surface's does.
    std::vector<std::uint32_t> nodeObserver;
    std::uint32_t clusters = 0;     ///< observers that watch a cluster
    std::uint32_t openClusters = 0; ///< clusters left without one (a loop that cannot be filled)
};

/// Where the observers stand (CollisionSettings: ghost_max_perimeter, observers, cluster_max_angle).
struct RadialObserverSettings {
    double ghostMaxPerimeter = std::numeric_limits<double>::infinity();
    RadialObservers observers = RadialObservers::Auto;
    double clusterMaxAngle = std::numbers::pi / 4.0;
    std::uint32_t clusterMaxFaces = 64;
    /// Per object of the model (or empty: none): a user observer (Body::observer, m), which
    /// replaces that object's centroid. Its object must get an observer of its own (closed by
    /// itself or by ghost fans, not clustered) and span a volume (model::observerFrame).
    std::vector<std::optional<glm::dvec3>> objectObservers;
    /// Per object (or empty): the second end of a user segment observer (Body::observerEnd, m),
    /// whose first end is objectObservers' point.
    std::vector<std::optional<glm::dvec3>> objectObserverEnds = {};
    /// Per object (or empty): a skeleton (Body::skeleton, m; empty: none). Its object is cut into
    /// the pieces nearest each bone (model::boneClusters), each closed by ghost fans over all its
    /// loops and watched by its bone as a segment observer; a piece that cannot be closed gets none.
    std::vector<std::vector<model::Bone>> objectSkeletons = {};
};

/// The engine's observers (decision 0025): one per object of `model` whose surface is closed,
/// consistently oriented and connected (the theorem's premise) by itself, or — unless
/// settings.observers is Clusters — once fans of ghost triangles (model::ghostTriangles, at the
/// model's positions) close its boundary loops of perimeter <= settings.ghostMaxPerimeter m. The
/// other objects are split into clusters (model::surfaceClusters, closed by model::closeCluster),
/// each with an observer of its own — unless settings.observers is Objects: then their faces get no
/// observer and are never culled. An object with a skeleton (settings.objectSkeletons) is watched
/// by its bones instead (docs/culling.md, "Skeletons").
RadialCullingConfig radialCullingConfig(const model::FlatModel& model,
                                        const RadialObserverSettings& settings);
/// Objects only, ghosts up to `ghostMaxPerimeter`: radialCullingConfig with RadialObservers::Objects.
RadialCullingConfig radialCullingConfig(const model::FlatModel& model, double ghostMaxPerimeter);

class RadialCullingPass {
  public:
    static constexpr PassId kId = PassId::RadialCulling;
    static constexpr const char* kName = passName(kId);

    /// Throws Error for an observer index out of range, a node table that is not one entry per
    /// node (RadialGhosts::nodeCount), or a cluster surface (no nodes) that no ghost node watches.
    explicit RadialCullingPass(const RadialCullingConfig& config);

    /// Binds what the consumers read: the face → observer table, the surfaces' node ranges and
    /// the free mask (word 0: whether it holds for this substep).
    void bindForConsumers() const;
    /// Observers, ghost nodes, classification, violated surfaces and free faces over [positions,
    /// predictedPositions] (bound at GLC_BIND_NODE_POSITIONS, GLC_BIND_PREDICTED_POSITIONS,
    /// GLC_BIND_FACES); the free mask then holds for this substep. Counts in `lists`' statistics
    /// (GLC_STAT_RADIAL_*).
    void run(AppendLists& lists) const;
    /// This substep culls nothing: the mask's word 0 is cleared.
    void switchOff() const;
    /// Whether some node's position differs from the last substep's committed end (the
    /// predicted positions): the host moved nodes, and the start is no longer known to be
    /// intersection-free. Reads positions and predictedPositions of `buffers`; one read-back.
    [[nodiscard]] bool hostMovedNodes(const DeviceBuffers& buffers) const;

    /// Bit f % 32 of word f / 32: face f is free (as of the last run()).
    [[nodiscard]] std::vector<std::uint32_t> readFreeMask() const;
    /// The observers of the last run(): start and end of each.
    [[nodiscard]] std::vector<RadialObserver> readObservers() const;
    /// The ghost nodes of the last run(): start and end of each.
    [[nodiscard]] std::vector<RadialObserver> readGhostNodes() const;
    /// Per observer, the winding number of its surface around it at x0 of the last run()
    /// (RadialWinding); its faces are freed only when it is 1 and decided.
    [[nodiscard]] std::vector<RadialWinding> readWinding() const;
    [[nodiscard]] std::uint32_t observedFaces() const { return m_observedFaces; }
    [[nodiscard]] std::uint32_t ghostFaces() const { return m_ghostFaceCount; }

  private:
    std::uint32_t m_faceCount = 0, m_observerCount = 0, m_observedFaces = 0;
    std::uint32_t m_ghostNodeCount = 0, m_ghostFaceCount = 0;
    mutable RadialClassifyPass m_classify;
    gl::Buffer m_surfaces, m_ghostLoops, m_nodeObservers;
    mutable gl::Buffer m_free;    ///< word 0: the mask holds for this substep; then one bit per face
    mutable gl::Buffer m_moved;   ///< uint: RadialHostCheck's flag
    mutable gl::Buffer m_winding; ///< uint[2 * observers]: RadialWinding's crossings and undecided flags
    gl::ComputeProgram m_observers, m_windingProgram, m_freeProgram, m_hostCheck;
    std::optional<gl::ComputeProgram> m_ghostNodes; ///< only with ghosts
};

} // namespace glcollide::passes
