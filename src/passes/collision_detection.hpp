#pragma once
// Collision detection for one substep: a broad phase (any kind behind the BroadPhase interface,
// made by createBroadPhase) appends candidate face pairs, the narrow phase (TriTri) tests them,
// both as stages of one chain over append lists that never drop data (docs/broad-phase.md,
// docs/narrow-phase.md); the last stage, FeaturePairs, expands the candidates into the
// vertex-face and edge-edge feature pairs the contact response reads (Representative Triangles,
// docs/design/decisions/0018-representative-triangles.md). Every kind yields the same candidate set (valid
// face pairs whose inflated face boxes overlap) and, with robust precision, the same intersection set.
//
// It also uploads the per-face and per-object tables (CollisionTables) the kernels and the
// contact response read.

#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/handles.hpp"
#include "passes/broad_phase/broad_phase.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/collision/feature_ccd.hpp"
#include "passes/collision/feature_pairs.hpp"
#include "passes/collision/narrow_phase.hpp"
#include "passes/collision/stage_chain.hpp"
#include "passes/device_buffers.hpp"
#include "passes/radial_culling.hpp"

#include <glcollide/scene.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace glcollide::passes {

/// Collision settings with discrete detection and the penalty response: the AABB-octree paper's
/// pipeline, the building blocks' plain use.
[[nodiscard]] inline CollisionSettings discreteSettings() {
    CollisionSettings s;
    s.response = ContactResponse::Penalty;
    s.detection = Detection::Discrete;
    return s;
}

struct CollisionConfig {
    bool betweenObjects = false; ///< effect `collisions`: faces of different objects
    bool selfCollisions = false; ///< effect `self_collisions`: faces of one object sharing no node
    /// The engine passes the scene's settings. Built alone, the pass detects discretely (the scene's
    /// default, continuous detection, needs predicted positions that only the engine allocates).
    CollisionSettings settings = discreteSettings();
    /// First size of one list; 0 = settings.initialCapacity. Lets a test overflow one list at a time.
    std::uint32_t boxPairCapacity = 0, candidateCapacity = 0, intersectionCapacity = 0;
    std::uint32_t vertexFaceCapacity = 0, edgeEdgeCapacity = 0;
    /// Bytes one list may grow to; 0 = the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE. A list
    /// that must grow beyond it makes detect() throw instead of dropping pairs. Tests lower it.
    std::uint64_t listByteLimit = 0;
    /// Substeps per frame, for the BVH's rebuild cadence in frames.
    std::uint32_t substepsPerFrame = 1;
    /// Radial view-based culling (decision 0025): which faces have which observer. Continuous
    /// detection only; it culls only while setRadialCulling(true).
    std::optional<RadialCullingConfig> radial;
};

/// Exact sizes found by the last detect() (after any reruns).
struct CollisionCounts {
    std::uint32_t boxPairs = 0;       ///< overlapping leaf-box pairs (octree broad phase; 0 otherwise)
    std::uint32_t candidates = 0;     ///< valid face pairs whose face boxes overlap
    std::uint32_t intersections = 0;  ///< candidates whose triangles intersect
    std::uint32_t exactFallbacks = 0; ///< robust TriTri: predicates the exact pass evaluated in integers
    std::uint32_t undecided = 0;      ///< robust TriTri: candidates the filtered pass left to the exact pass
    std::uint32_t reruns = 0;         ///< chain reruns after a list overflowed and was grown
    /// Growths per list in this call.
    std::uint32_t boxPairGrowths = 0, candidateGrowths = 0, intersectionGrowths = 0;
    /// BVH broad phase: the tree was rebuilt in this call (else only refit), the traversal's
    /// dispatches per run, and the nodes whose boxes it tested (the tree-quality figure: a refit
    /// tree that loosens costs more visits for the same candidates; modulo 2^32).
    bool bvhRebuilt = false;
    std::uint32_t bvhRounds = 0;
    std::uint32_t bvhNodeVisits = 0;
    /// Feature pairs the Representative-Triangle expansion produced: (vertex, face) and (edge, edge).
    std::uint32_t vertexFacePairs = 0, edgeEdgePairs = 0;
    std::uint32_t vertexFaceGrowths = 0, edgeEdgeGrowths = 0;
    /// What a face-pair expansion without ownership would test: 6 vertex-face and 9 edge-edge
    /// pairs per candidate.
    std::uint64_t vertexFacePairsWithoutOwnership = 0, edgeEdgePairsWithoutOwnership = 0;
    /// Continuous detection (the Ccd stage): feature pairs that may touch during the substep,
    /// pairs whose refinement ran out of budget, boxes evaluated (modulo 2^32) and the earliest
    /// time of impact in [0, 1] (+inf when none may touch).
    std::uint32_t ccdVertexFaceHits = 0, ccdEdgeEdgeHits = 0, ccdCapped = 0, ccdBoxes = 0;
    float ccdEarliestToi = 0.0f;
    std::uint32_t ccdTangled = 0; ///< safe step: feature pairs left out, their faces intersect at x0
    /// Radial culling (decision 0025): whether it culled in this call; observed faces, those not
    /// proven positive and the free ones; candidate pairs TriTri and feature pairs the CCD left out.
    bool radialOn = false;
    std::uint32_t radialObserved = 0, radialNonPositive = 0, radialFree = 0;
    std::uint32_t radialGhostFaces = 0, radialViolated = 0;
    std::uint32_t radialCulledTriTri = 0, radialCulledCcd = 0;
};

/// The per-face and per-object tables of the collision kernels and the contact response.
struct CollisionTables {
    /// `featureOrphans`: also upload the orphan table (continuous detection).
    CollisionTables(const model::FlatModel& model, const model::OctreeLayout& layout,
                    bool featureOrphans = false);
    void bind() const;
    gl::Buffer faceInfo; ///< GpuFaceInfo per face (object, leaf box, owned features)
    gl::Buffer objects;  ///< GpuObject per object
    /// The orphan feature pairs each face pair carries (model::orphanTable, GLC_BIND_FEATURE_ORPHANS):
    /// read by FeaturePairs under continuous detection only; none (no GL name) otherwise.
    gl::Buffer featureOrphans;
};

class CollisionDetection {
  public:
    /// Builds the octree layout from the rest pose `model.positions` (it assigns GpuFaceInfo.box),
    /// uploads the tables, makes the broad phase of config.settings.broadPhase and the narrow
    /// phase, and allocates every list with its first capacity. Needs a current GL 4.3 context;
    /// throws glcollide::Error on bad settings or shader errors.
    CollisionDetection(const CollisionConfig& config, const model::FlatModel& model);
    CollisionDetection(const CollisionDetection&) = delete; // the chain's stages point into it
    CollisionDetection& operator=(const CollisionDetection&) = delete;

    /// The passes of its stages in dispatch order: the broad phase's, TriTri, FeaturePairs.
    [[nodiscard]] std::vector<PassId> passes() const { return m_chain.passes(); }
    [[nodiscard]] std::vector<std::string> passNames() const;

    /// Runs the chain on buffers.positions (binding 0) and buffers.faces (7), and with continuous
    /// detection (settings.detection) on buffers.predictedPositions too; grows lists and
    /// reruns stages on overflow; throws Error when a list would outgrow config.listByteLimit.
    /// Brackets each stage with timer section passIndex(pass) when `timer` is not null. Ends with
    /// a storage barrier, so later passes may read the lists. One read-back per call, plus one
    /// per rerun.
    CollisionCounts detect(const DeviceBuffers& buffers, gl::GpuTimer* timer);

    /// Continuous detection: the Ccd stage again, on the lists of the last detect(), over
    /// buffers.positions and the (since changed) buffers.predictedPositions. Returns the pairs that
    /// may touch (vertex-face and edge-edge); one read-back. The safe step's check (decision 0024).
    std::uint32_t recheckCcd(const DeviceBuffers& buffers);
    /// Radial culling: whether the next detect() culls (the caller vouches that the positions it
    /// starts from are intersection-free: the theorem's premise). Ignored without
    /// CollisionConfig::radial.
    void setRadialCulling(bool on) { m_radialOn = on && m_radial.has_value(); }
    /// Empties every list the detection fills, as before the first detect(): what the passes that
    /// read the last detection's lists (the implicit solve's contacts, the velocity filters) then
    /// see. Capacities stay.
    void forgetLists() { m_lists->resetCounts(m_chain.outputsFrom(0)); }
    [[nodiscard]] bool radialCullingConfigured() const { return m_radial.has_value(); }
    /// The radial culling pass (tests read its free mask); null without CollisionConfig::radial.
    [[nodiscard]] const RadialCullingPass* radialCulling() const { return m_radial ? &*m_radial : nullptr; }
    /// The counter block's statistic `id` (GLC_STAT_*), read back now.
    std::uint32_t readStat(std::uint32_t id);
    /// The safe step's marks of the faces (and nodes) that intersect at the start of the last
    /// substep (FeatureCcd); an empty buffer without the intersection-free response.
    [[nodiscard]] const gl::Buffer& tangled() const;

    /// uvec2 face pairs (lower, higher); the first lastCounts().candidates are valid.
    [[nodiscard]] const gl::Buffer& candidates() const { return m_lists->storage(GLC_LIST_CANDIDATES); }
    /// uvec2 face pairs (lower, higher); the first lastCounts().intersections are valid.
    [[nodiscard]] const gl::Buffer& intersections() const { return m_lists->storage(GLC_LIST_INTERSECTIONS); }
    /// Every list and the counters: the contact response dispatches over the feature-pair lists.
    [[nodiscard]] const AppendLists& lists() const { return *m_lists; }
    [[nodiscard]] const CollisionTables& tables() const { return m_tables; }
    [[nodiscard]] const gl::Buffer& faceInfo() const { return m_tables.faceInfo; }
    [[nodiscard]] const gl::Buffer& objects() const { return m_tables.objects; }
    [[nodiscard]] const gl::Buffer& counters() const { return m_lists->counters(); }
    /// The broad phase's buffer labelled `label` (e.g. "boxes": GpuBox per leaf box); an empty
    /// buffer when it has none.
    [[nodiscard]] const gl::Buffer& broadPhaseBuffer(const std::string& label) const;
    [[nodiscard]] const gl::Buffer& boxes() const { return broadPhaseBuffer("boxes"); }
    [[nodiscard]] const model::OctreeLayout& layout() const { return m_layout; }
    [[nodiscard]] const CollisionCounts& lastCounts() const { return m_counts; }
    /// Continuous detection: uint per node, the bits of its earliest time of impact in the last
    /// detect() (+inf bits: none); an empty buffer under discrete detection.
    [[nodiscard]] const gl::Buffer& nodeToi() const;
    [[nodiscard]] bool continuous() const { return m_ccd.has_value(); }

    /// Read-backs for tests and tools, sorted.
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readCandidates() const;
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readIntersections() const;
    /// (node, face) pairs and (3*face+edge, 3*face+edge) pairs of the expansion.
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readVertexFacePairs() const;
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readEdgeEdgePairs() const;

    /// Bytes of the broad phase's own buffers (its tree, sort buffers, traversal state; the
    /// lists aside).
    [[nodiscard]] std::size_t broadPhaseBytes() const;
    [[nodiscard]] std::vector<std::string> allocatedLabels() const;
    [[nodiscard]] std::size_t allocatedBytes() const;

  private:
    [[nodiscard]] std::vector<const gl::Buffer*> allBuffers() const;

    std::uint32_t m_faceCount = 0;
    model::OctreeLayout m_layout;
    CollisionTables m_tables;
    std::unique_ptr<AppendLists> m_lists;
    std::unique_ptr<BroadPhase> m_broadPhase;
    NarrowPhase m_narrowPhase;
    FeaturePairs m_featurePairs;
    std::optional<FeatureCcd> m_ccd;           ///< continuous detection only
    std::optional<RadialCullingPass> m_radial; ///< CollisionConfig::radial only
    bool m_radialOn = false;
    gl::Buffer m_radialNone; ///< bound for the consumers without culling: word 0 = 0, no observer
    StageChain m_chain;
    CollisionCounts m_counts;
};

} // namespace glcollide::passes
