#pragma once
// The paper's masked broad phase (seeds/002 Alg. 2-3): BBUpdate refits the leaf boxes;
// BBCollision writes the boxes x boxes overlap mask (box_mask.comp), then visits every face pair
// and appends, as candidates, the valid pairs of overlapping boxes whose face boxes overlap
// (masked_face_pairs.comp). O(faces^2) invocations: kept so the paper's experiment can be
// reproduced; its fused TriTri lives in the benchmark kit (src/benchkit/paper_fused_tri_tri.*).

#include "passes/broad_phase/broad_phase.hpp"
#include "passes/broad_phase/leaf_boxes.hpp"

namespace glcollide::passes {

class MaskedBroadPhase final : public BroadPhase {
  public:
    static constexpr std::array kPasses = {PassId::BBUpdate, PassId::BBCollision};

    explicit MaskedBroadPhase(const BroadPhaseContext& context);
    [[nodiscard]] std::vector<PassId> passes() const override { return {kPasses.begin(), kPasses.end()}; }
    void addStages(StageChain& chain, AppendLists& lists) override;
    void bind() const override;
    [[nodiscard]] std::vector<const gl::Buffer*> buffers() const override;

  private:
    LeafBoxes m_leafBoxes;
    std::uint32_t m_faceCount;
    gl::Buffer m_mask;
    gl::ComputeProgram m_boxMask, m_facePairs;
};

} // namespace glcollide::passes
