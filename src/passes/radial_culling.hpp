#pragma once
// RadialCulling — radial view-based culling (issue 24, decision 0025, docs/culling.md "Culling"):
// the first stage of a substep's collision detection when the scene asks for it. Three
// dispatches: RadialObservers (each observer is the centroid of its surface's nodes at x0 and at
// x1), RadialClassify (positive faces, footprint cones, the non-positive list) and RadialFree (a
// positive face whose cone meets no non-positive cone of its observer is free). TriTri and the
// CCD at zero separation then leave out the pairs of a surface with a free face
// (common/radial_cull.glsl): by the decision's theorem such a pair cannot intersect, so culling
// changes the work, never the answers. CPU twin of the free set: cpu::radialFreeFaces.

#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/device_buffers.hpp"
#include "passes/pass_id.hpp"
#include "passes/radial_classify.hpp"

#include <cstdint>
#include <vector>

namespace glcollide::passes {

/// The nodes of one observer's surface: [firstNode, firstNode + nodeCount).
struct RadialSurface {
    std::uint32_t firstNode = 0, nodeCount = 0;
};

/// Which faces culling may consider: per face its observer's index or kNoRadialObserver, and per
/// observer its surface's nodes. The surface of an observer must be closed and consistently
/// oriented (the theorem's premise); the engine gives one observer to each closed object.
struct RadialCullingConfig {
    std::vector<std::uint32_t> faceObserver;
    std::vector<RadialSurface> surfaces;
};

class RadialCullingPass {
  public:
    static constexpr PassId kId = PassId::RadialCulling;
    static constexpr const char* kName = passName(kId);

    /// Throws Error for an observer index out of range or a surface with no nodes.
    explicit RadialCullingPass(const RadialCullingConfig& config);

    /// Binds what the consumers read: the face → observer table, the surfaces' node ranges and
    /// the free mask (word 0: whether it holds for this substep).
    void bindForConsumers() const;
    /// Observers, classification and free faces over [positions, predictedPositions] (bound at
    /// GLC_BIND_NODE_POSITIONS, GLC_BIND_PREDICTED_POSITIONS, GLC_BIND_FACES); the free mask then
    /// holds for this substep. Counts in `lists`' statistics (GLC_STAT_RADIAL_*).
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
    [[nodiscard]] std::uint32_t observedFaces() const { return m_observedFaces; }

  private:
    std::uint32_t m_faceCount = 0, m_observerCount = 0, m_observedFaces = 0;
    mutable RadialClassifyPass m_classify;
    gl::Buffer m_surfaces;
    mutable gl::Buffer m_free;  ///< word 0: the mask holds for this substep; then one bit per face
    mutable gl::Buffer m_moved; ///< uint: RadialHostCheck's flag
    gl::ComputeProgram m_observers, m_freeProgram, m_hostCheck;
};

} // namespace glcollide::passes
