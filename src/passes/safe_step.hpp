#pragma once
// SafeStep — the intersection-free response's step (decision 0024, docs/collisions.md
// "Intersection-free response"). NodePredict has written the whole step x1 of every node and the
// continuous detection has tested every vertex-face and edge-edge pair of the swept candidates
// over [x0, x1]. While some pair with a moving node may touch, SafeStep cuts the steps of the
// objects of that pair's nodes (safe_step.comp: every node of the object to a fraction of the
// object's earliest time of impact in the first rounds, to nothing after) and runs the CCD again over the cut
// steps (the swept boxes of x0 and x1 still bound them, so the candidates stay valid). When no pair with a
// moving node may touch, x1 is committed (commit()) as the new positions: from an intersection-free state at
// x0 no face pair can have started to intersect, because a new intersection of two faces needs a vertex to
// cross a face or an edge to cross an edge, and the CCD, never late, saw none. The loop is bounded: after
// `maxRounds` every node stays where it is (counted, never silent).

#include "passes/collision_detection.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

#include <cstdint>

namespace glcollide::passes {

/// The safe step's settings, each with its meaning and range.
struct SafeStepSettings {
    /// Fraction (0, 1) of a node's earliest time of impact that its cut step reaches. Lower leaves
    /// more of the gap and cuts more often; 0.8 leaves a fifth of it (ipc-toolkit's collision-free
    /// step size uses the same kind of fraction).
    float fraction = 0.8f;
    /// Rounds that cut by `fraction`; the rounds after them freeze the objects of every pair that
    /// may still touch (each such round freezes at least one more object, so they end).
    std::uint32_t cutRounds = 2;
    /// Rounds in all (>= cutRounds); when pairs still may touch after them, every node stays at x0.
    std::uint32_t maxRounds = 16;
};

/// What one substep's safe step did.
struct SafeStepCounts {
    std::uint32_t rounds = 0;          ///< cut-and-check rounds (0: the detection's CCD found nothing)
    std::uint32_t cuts = 0;            ///< node steps cut, summed over the rounds
    std::uint32_t groundCrossings = 0; ///< nodes whose predicted step crossed the ground
    bool frozeAll = false;             ///< the last resort acted: every node stayed at x0
};

/// What one round reads besides the node buffers (the collision detection's).
struct SafeStepInputs {
    const gl::Buffer* nodeToi = nullptr;  ///< uint per node: bits of its earliest time of impact
    const gl::Buffer* objects = nullptr;  ///< GpuObject per object, ascending firstNode
    const gl::Buffer* counters = nullptr; ///< GpuCollisionCounters (GLC_STAT_SAFE_STEP_*)
};

class SafeStepPass {
  public:
    static constexpr PassId kId = PassId::SafeStep;
    static constexpr const char* kName = passName(kId);
    /// `ground`: the scene's ground plane is on at `groundHeight` (NodePredict does not clamp x1 to
    /// it: a crossing is an impact that cuts its object's step).
    SafeStepPass(const SafeStepSettings& settings, std::uint32_t objectCount, bool ground,
                 double groundHeight);
    /// `h`: the substep; `mayTouch`: pairs the detection's CCD found that may touch.
    SafeStepCounts dispatch(const DeviceBuffers& buffers, CollisionDetection& collision, double h,
                            std::uint32_t mayTouch) const;
    /// The checked step x1 (predictedPositions) becomes the positions: the substep's last stage,
    /// after the energy guard (PipelinePlan::safeStepStages).
    static void commit(const DeviceBuffers& buffers);

    /// One round on its own (tests; dispatch() runs them): the objects' earliest times (with the
    /// ground's crossings), then every node of an object with one advances to `fraction` of it
    /// (0: stays at x0; `everyNode`: every moving node stays). setSubstep() first. CPU twin:
    /// cpu::safeStepRound.
    void round(const DeviceBuffers& buffers, const SafeStepInputs& inputs, float fraction,
               bool everyNode) const;
    void setSubstep(double h) const;

  private:
    /// One safe_step.comp dispatch: nodes with a time of impact (every moving node when
    /// `everyNode`) advance to `fraction` of it (0: stay at x0).
    void cut(const DeviceBuffers& buffers, const CollisionDetection& collision, float fraction,
             bool everyNode) const;

    SafeStepSettings m_settings;
    std::uint32_t m_objectCount;
    bool m_ground;
    mutable gl::Buffer m_objectToi; ///< uint per object: the bits of its earliest time of impact this round
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
