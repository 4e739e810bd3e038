#pragma once
// The linear BVH broad phase (seeds/001, Kim 2024; Karras 2012; docs/broad-phase.md,
// docs/design/decisions/0017-gpu-linear-bvh.md): one tree over every face of the scene, each
// face a leaf.
//  * BvhBuild (when the rebuild cadence says so): centroid bounds, 30-bit Morton codes, a stable
//    GPU radix sort, and the Karras hierarchy with escape links.
//  * BvhRefit (every substep): node boxes bottom-up from the current positions.
//  * BvhTraverse: one stackless query per sorted leaf against the later leaves; appends the
//    candidate face pairs, resuming across dispatches so that no invocation loops past llvmpipe's
//    limit; reruns with more rounds when a query did not finish.
// Work ~ faces log faces + candidates; memory ~ 120 bytes per face (bvhBytesPerFace).

#include "passes/broad_phase/broad_phase.hpp"
#include "passes/broad_phase/radix_sort.hpp"

#include "gl/program.hpp"

#include <array>

namespace glcollide::passes {

class BvhBroadPhase final : public BroadPhase {
  public:
    static constexpr std::array kPasses = {PassId::BvhBuild, PassId::BvhRefit, PassId::BvhTraverse};

    explicit BvhBroadPhase(const BroadPhaseContext& context);
    [[nodiscard]] std::vector<PassId> passes() const override { return {kPasses.begin(), kPasses.end()}; }
    void prepare() override;
    void addStages(StageChain& chain, AppendLists& lists) override;
    void bind() const override;
    [[nodiscard]] std::vector<const gl::Buffer*> buffers() const override;
    [[nodiscard]] BroadPhaseStats stats() const override { return {m_rebuildDue, m_rounds}; }

  private:
    void build();
    void refit();
    void traverse(AppendLists& lists);

    std::uint32_t m_faceCount;
    std::uint32_t m_visitsPerRound;
    std::uint32_t m_rebuildPeriod; ///< detects between rebuilds; 0: only the first
    std::uint64_t m_detects = 0;
    bool m_rebuildDue = true;
    std::uint32_t m_rounds = 1; ///< traversal dispatches per run; doubled when a query did not finish
    RadixSort m_sort;
    gl::Buffer m_bounds, m_boxes, m_links, m_visits, m_resume;
    gl::ComputeProgram m_boundsProgram, m_morton, m_hierarchy, m_refit, m_traverse;
};

} // namespace glcollide::passes
