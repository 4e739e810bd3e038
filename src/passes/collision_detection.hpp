#pragma once
// Collision detection: the broad phase (AABB-octree of seeds/002: BBUpdate, BBCollision) and the
// narrow phase (TriTri) behind one object the engine calls once per substep. Three broad phases
// (CollisionSettings::broadPhase, docs/broad-phase.md):
//   Octree   BBUpdate -> BBCollision (box pairs -> candidate face pairs) -> TriTri per candidate
//   Masked   BBUpdate -> BBCollision (box-pair mask) -> TriTri over all face pairs, masked
//   AllPairs TriTri over all face pairs (the reference)
// All three produce the same candidate set (valid face pairs whose inflated face boxes overlap)
// and, with robust precision, the same intersection set. Robust TriTri is two kernels in the
// TriTri slot: the filtered test appends what it cannot decide to the undecided list, and
// TriTriExact (indirect dispatch from that count) decides those exactly (docs/narrow-phase.md). Lists never drop data: an overflowing
// list is grown to the next power of two >= its exact count and the stage is rerun.

#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "passes/device_buffers.hpp"

#include <glcollide/scene.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::passes {

struct CollisionConfig {
    bool betweenObjects = false; ///< effect `collisions`: faces of different objects
    bool selfCollisions = false; ///< effect `self_collisions`: faces of one object sharing no node
    CollisionSettings settings;
    /// First size of one pair list; 0 = settings.initialCapacity. Lets a test overflow one list
    /// at a time.
    std::uint32_t boxPairCapacity = 0, candidateCapacity = 0, intersectionCapacity = 0;
    /// Bytes one pair list may grow to; 0 = the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE. A list
    /// that must grow beyond it makes detect() throw instead of dropping pairs. Tests lower it.
    std::uint64_t listByteLimit = 0;
};

/// Exact sizes found by the last detect() (after any reruns).
struct CollisionCounts {
    std::uint32_t boxPairs = 0;       ///< overlapping leaf-box pairs (octree mode; 0 otherwise)
    std::uint32_t candidates = 0;     ///< valid face pairs whose face boxes overlap
    std::uint32_t intersections = 0;  ///< candidates (or valid pairs) whose triangles intersect
    std::uint32_t exactFallbacks = 0; ///< robust TriTri: predicates the exact pass evaluated in integers
    std::uint32_t undecided = 0;      ///< robust TriTri: candidates the filtered pass left to the exact pass
    std::uint32_t reruns = 0;         ///< stages rerun after a list overflowed and was grown
    /// Growths per list in this call (a rerun may grow two lists at once in masked/all-pairs mode).
    std::uint32_t boxPairGrowths = 0, candidateGrowths = 0, intersectionGrowths = 0;
};

class CollisionDetection {
public:
    static constexpr const char* kBBUpdate = "BBUpdate";
    static constexpr const char* kBBCollision = "BBCollision";
    static constexpr const char* kTriTri = "TriTri";

    /// Builds the octree layout from the rest pose `model.positions`, uploads it with the face
    /// info and object table, compiles the programs the mode needs and allocates every pair list
    /// with settings.initialCapacity (>= 1) entries. Needs a current GL 4.3 context; throws
    /// glcollide::Error on bad settings or shader errors.
    CollisionDetection(const CollisionConfig& config, const model::FlatModel& model);

    /// Pass names in dispatch order: {"BBUpdate","BBCollision","TriTri"}, or {"TriTri"} in
    /// all-pairs mode.
    [[nodiscard]] std::vector<std::string> passNames() const;

    /// Runs the passes on buffers.positions (binding 0) and buffers.faces (7); grows the lists and
    /// reruns stages on overflow; throws Error when a list would outgrow config.listByteLimit. Brackets pass k of passNames() with timer->begin/end(timerBase + k)
    /// when `timer` is not null (a rerun adds to its pass's time). Ends with a storage barrier, so
    /// later passes may read the lists. Reads the counters back once (one CPU-GPU sync per call,
    /// plus one per rerun).
    CollisionCounts detect(const DeviceBuffers& buffers, gl::GpuTimer* timer, std::size_t timerBase);

    /// uvec2 face pairs (lower, higher); the first lastCounts().candidates are valid.
    [[nodiscard]] const gl::Buffer& candidates() const { return m_candidates; }
    /// uvec2 face pairs (lower, higher); the first lastCounts().intersections are valid.
    [[nodiscard]] const gl::Buffer& intersections() const { return m_intersections; }
    [[nodiscard]] const gl::Buffer& faceInfo() const { return m_faceInfo; }
    [[nodiscard]] const gl::Buffer& objects() const { return m_objects; }
    [[nodiscard]] const gl::Buffer& counters() const { return m_counters; }
    /// GpuBox per leaf box (empty buffer in all-pairs mode).
    [[nodiscard]] const gl::Buffer& boxes() const { return m_boxes; }
    [[nodiscard]] const model::OctreeLayout& layout() const { return m_layout; }
    [[nodiscard]] const CollisionCounts& lastCounts() const { return m_counts; }
    /// Binds faceInfo (6), objects (8), candidates (10), intersections (5), counters (18) for a
    /// later pass (the contact response).
    void bindOutputs() const;

    /// Read-backs for tests and tools, sorted.
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readCandidates() const;
    [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> readIntersections() const;

    [[nodiscard]] std::vector<std::string> allocatedLabels() const;
    [[nodiscard]] std::size_t allocatedBytes() const;

private:
    void bindInputs(const DeviceBuffers& buffers) const;
    void resetCounts(bool boxPairs, bool candidates, bool intersections);
    void writeCapacities();
    void readCounters();
    void grow(gl::Buffer& list, std::uint32_t& capacity, std::uint32_t count, const char* label,
              std::uint32_t& growths);
    void runBBUpdate() const;
    void runBoxPairs() const;
    void runExpand() const;
    void runTriTriCandidates() const;
    void runTriTriAllPairs(std::uint32_t faceCount) const;
    void runTriTriExact() const;
    void writeDispatchArgs(std::uint32_t list, std::uint32_t itemsPerGroup, std::uint32_t zGroups) const;
    void dispatchIndirect(const gl::ComputeProgram& program, std::uint32_t list) const;
    template <typename F>
    void timed(gl::GpuTimer* timer, std::size_t section, const char* name, F&& work) const;

    CollisionConfig m_config;
    std::uint32_t m_pairRules = 0;
    float m_halfThickness = 0.0f;
    std::uint32_t m_faceCount = 0;
    model::OctreeLayout m_layout;

    gl::ComputeProgram m_bbUpdate, m_boxPairs, m_boxMask, m_expand, m_args, m_triTri, m_triTriExact;

    gl::Buffer m_faceInfo, m_objects, m_boxes, m_boxFaceOffsets, m_boxFaceList, m_boxMaskBuffer;
    gl::Buffer m_boxPairList, m_candidates, m_undecided, m_intersections, m_counters, m_dispatchArgs;
    std::uint32_t m_boxPairCapacity = 0, m_candidateCapacity = 0, m_intersectionCapacity = 0;
    std::uint64_t m_listByteLimit = 0;
    std::uint32_t m_expandSlices = 1; ///< z groups per box pair in the expansion (bb_collision.comp)
    std::array<std::uint32_t, 12> m_rawCounters{}; // GpuCollisionCounters
    CollisionCounts m_counts;
};

} // namespace glcollide::passes
