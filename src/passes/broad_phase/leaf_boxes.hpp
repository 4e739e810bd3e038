#pragma once
// The AABB-octree's leaf boxes on the GPU (seeds/002, Alg. 1 BBUpdate): the face -> leaf-box
// assignment of the rest pose (model::OctreeLayout) uploaded once, the boxes refit every substep.
// Shared by the octree and masked broad phases.

#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "passes/broad_phase/broad_phase.hpp"

namespace glcollide::passes {

class LeafBoxes {
  public:
    explicit LeafBoxes(const BroadPhaseContext& context);
    /// The BBUpdate stage: refits every leaf box to the current positions.
    [[nodiscard]] Stage refitStage() const;
    void bind() const;
    [[nodiscard]] std::vector<const gl::Buffer*> buffers() const {
        return {&m_boxes, &m_boxFaceOffsets, &m_boxFaceList};
    }
    [[nodiscard]] std::uint32_t boxCount() const { return m_boxCount; }

  private:
    std::uint32_t m_boxCount;
    gl::Buffer m_boxes, m_boxFaceOffsets, m_boxFaceList;
    gl::ComputeProgram m_refit;
};

} // namespace glcollide::passes
