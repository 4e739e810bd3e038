#pragma once
// The all-pairs broad phase, the reference: BBCollision visits every face pair f < g and appends
// the valid pairs whose face boxes overlap as candidates (all_face_pairs.comp). O(faces^2).

#include "passes/broad_phase/broad_phase.hpp"

namespace glcollide::passes {

class AllPairsBroadPhase final : public BroadPhase {
  public:
    static constexpr std::array kPasses = {PassId::BBCollision};

    explicit AllPairsBroadPhase(const BroadPhaseContext& context);
    [[nodiscard]] std::vector<PassId> passes() const override { return {kPasses.begin(), kPasses.end()}; }
    void addStages(StageChain& chain, AppendLists& lists) override;
    void bind() const override {}
    [[nodiscard]] std::vector<const gl::Buffer*> buffers() const override { return {}; }

  private:
    std::uint32_t m_faceCount;
    gl::ComputeProgram m_facePairs;
};

} // namespace glcollide::passes
