#pragma once
// The broad-phase interface (after ipc-toolkit's broad_phase.hpp + create_broad_phase.hpp): every
// kind of broad phase is one class behind it, made by createBroadPhase() from the scene's
// collision settings, and the engine knows only this interface.
//
// The contract, the same for every kind (tests/gl/collision_detection_gl_test.cpp runs it over
// all kinds against the CPU brute force, cpu::twinCandidates): the stages a broad phase adds to
// the substep's chain append every valid face pair (pair rules of shaders/common/collision.glsl)
// whose inflated closed face boxes overlap, exactly once, as (lower, higher) face index, to the
// candidate list GLC_LIST_CANDIDATES; they may use lists of their own (declared in AppendLists,
// grown and rerun by the chain like any other).
//
// Continuous collision detection: a broad phase reads node positions from binding
// GLC_BIND_NODE_POSITIONS (x0, the start of the substep). With BroadPhaseContext::sweptBoxes it
// also reads the predicted end positions (GLC_BIND_PREDICTED_POSITIONS) and bounds each face over
// both (shaders/common/face_bounds.glsl, built with GLC_SWEPT: faceBoxDefines): every kind then
// yields the face pairs whose swept boxes overlap.

#include "gl/handles.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/collision/stage_chain.hpp"
#include "passes/pass_id.hpp"

#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"

#include <glcollide/scene.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace glcollide::passes {

/// What every broad phase is built from.
struct BroadPhaseContext {
    const model::FlatModel& model;
    /// The octree of settings.octreeDepth over the rest pose (face -> leaf box), built once by
    /// the collision detection: GpuFaceInfo.box comes from it.
    const model::OctreeLayout& layout;
    const CollisionSettings& settings;
    std::uint32_t pairRules = 0; ///< GLC_RULE_* bits of the scene's collision effects
    float halfThickness = 0.0f;  ///< face-box inflation, model::halfThicknessFloat(settings.thickness)
    /// First capacity of a list of the broad phase's own; 0 = settings.initialCapacity (tests
    /// overflow one list at a time).
    std::uint32_t boxPairCapacity = 0;
    bool sweptBoxes = false; ///< CCD: bound each face over the substep's start and end positions
    /// Substeps per frame, for cadences counted in frames (the BVH's rebuild).
    std::uint32_t substepsPerFrame = 1;
};

/// The defines of the kernels that bound faces (face_bounds.glsl): GLC_SWEPT for swept boxes.
inline std::vector<std::string> faceBoxDefines(const BroadPhaseContext& c) {
    return c.sweptBoxes ? std::vector<std::string>{"GLC_SWEPT"} : std::vector<std::string>{};
}

/// What a broad phase did in the last detect(), beyond the list counts.
struct BroadPhaseStats {
    bool rebuilt = false;     ///< BVH: the tree was rebuilt (not only refit)
    std::uint32_t rounds = 0; ///< BVH: traversal dispatches per run
};

class BroadPhase {
  public:
    virtual ~BroadPhase() = default;

    /// The passes its stages are timed under, in dispatch order.
    [[nodiscard]] virtual std::vector<PassId> passes() const = 0;
    /// Called once per detect(), before the chain runs: per-substep decisions (the BVH's rebuild
    /// cadence). Reruns of the chain within one detect() do not call it again.
    virtual void prepare() {}
    /// Declares its own lists in `lists` and adds its stages to `chain`; they append the candidate
    /// face pairs (the contract above). Called once, after the candidate list is declared.
    virtual void addStages(StageChain& chain, AppendLists& lists) = 0;
    /// Binds its own buffers (tables, boxes) before the chain runs; the lists are bound by the chain.
    virtual void bind() const = 0;
    /// Its own buffers, for Engine::allocatedBuffers().
    [[nodiscard]] virtual std::vector<const gl::Buffer*> buffers() const = 0;
    [[nodiscard]] virtual BroadPhaseStats stats() const { return {}; }
};

} // namespace glcollide::passes
