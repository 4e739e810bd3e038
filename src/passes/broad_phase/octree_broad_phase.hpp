#pragma once
// The AABB-octree broad phase (seeds/002 Alg. 1-2, docs/broad-phase.md): BBUpdate refits the leaf
// boxes; BBCollision appends the overlapping leaf-box pairs whose objects may collide to the
// box-pair list (octree_box_pairs.comp), then expands each box pair's face pairs into candidates
// (octree_expand.comp, indirect dispatch from the box-pair count). Work ~ face pairs of
// overlapping boxes, never faces^2.

#include "passes/broad_phase/broad_phase.hpp"
#include "passes/broad_phase/leaf_boxes.hpp"

namespace glcollide::passes {

class OctreeBroadPhase final : public BroadPhase {
  public:
    static constexpr std::array kPasses = {PassId::BBUpdate, PassId::BBCollision};

    explicit OctreeBroadPhase(const BroadPhaseContext& context);
    [[nodiscard]] std::vector<PassId> passes() const override { return {kPasses.begin(), kPasses.end()}; }
    void addStages(StageChain& chain, AppendLists& lists) override;
    void bind() const override { m_leafBoxes.bind(); }
    [[nodiscard]] std::vector<const gl::Buffer*> buffers() const override { return m_leafBoxes.buffers(); }

  private:
    LeafBoxes m_leafBoxes;
    std::uint32_t m_boxPairCapacity;
    std::uint32_t m_expandSlices; ///< z groups per box pair in the expansion
    gl::ComputeProgram m_boxPairs, m_expand;
};

} // namespace glcollide::passes
