#pragma once
// Untangle — the intersection-free response's recovery from intersections deeper than the contact
// thickness (decision 0024, "Deep intersections"; docs/collisions.md). Runs only in a substep whose
// start intersects (the detection's TriTri found face pairs intersecting at x0), after the energy
// guard and before the commit: every such pair pushes its two triangles so that their
// intersection segment shrinks (untangle_pairs.comp: along a closed object's outward normal, or,
// between open surfaces, the side that moves the segment's end towards its other end), the pushes
// are summed per node in fixed point, and each node's step x1 moves by at most `step` along its sum
// (untangle_apply.comp). The CCD leaves these nodes' pairs out while they are tangled (TangledMarks),
// so nothing else blocks the push; the velocities are not changed (no kinetic energy is added).
// CPU twin: cpu::untangleStep.

#include "passes/collision_detection.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"

#include <cstdint>

namespace glcollide::passes {

/// What one untangling step did.
struct UntangleCounts {
    std::uint32_t movedNodes = 0; ///< nodes whose step moved
    std::uint32_t unresolvedPairs =
        0; ///< intersecting pairs without two piercings (coplanar, touching): no push
};

/// The most a node moves per substep while untangling, in contact thicknesses: half keeps a push
/// from carrying a node through a face that lay beyond the thickness at x0 in one substep (such a
/// crossing would only make one more tangled pair, found at the next start).
inline constexpr double kUntangleStepPerThickness = 0.5;

class UntanglePass {
  public:
    static constexpr PassId kId = PassId::Untangle;
    static constexpr const char* kName = passName(kId);
    /// Fixed-point units per unit of push: a push part has length <= 1, so a node's sum stays in
    /// int32 for up to 32,767 parts; its resolution, 1.5·10⁻⁵ of `step`, is far below any length
    /// that matters here.
    static constexpr float kPushScale = 65536.0f;

    /// `step`: m, the most a node moves per substep (> 0).
    UntanglePass(std::uint32_t nodeCount, double step);
    /// The pairs of `collision`'s last detection (its GLC_LIST_INTERSECTIONS, at x0) push x1
    /// (predictedPositions). Reads its counts back (a sync: only in substeps that start tangled).
    UntangleCounts dispatch(const DeviceBuffers& buffers, const CollisionDetection& collision) const;

  private:
    mutable gl::Buffer m_push;   ///< ivec4 per node: the fixed-point sum of its pushes (w unused)
    mutable gl::Buffer m_counts; ///< uint[2]: moved nodes, unresolved pairs
    gl::ComputeProgram m_pairs;
    gl::ComputeProgram m_apply;
};

} // namespace glcollide::passes
