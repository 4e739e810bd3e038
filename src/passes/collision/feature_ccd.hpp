#pragma once
// The Ccd stage of continuous detection (docs/ccd.md, "In the engine"): after FeaturePairs, one
// kernel (feature_ccd.comp) runs the conservative float CCD of shaders/common/ccd.glsl on every
// vertex-face and edge-edge pair of the swept candidates, over [x0, x1] of the substep, and
// lowers each node's earliest time of impact (a buffer of float bits, one per node) and the
// substep's (GLC_STAT_CCD_EARLIEST_TOI) with atomicMin: deterministic, no float atomics. It
// appends to no list, so an overflow elsewhere reruns it with the stages before it; it resets
// its statistics and the times of impact each time it runs. CPU twin: cpu::featureCcd.

#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/collision/stage_chain.hpp"

#include <cstdint>

namespace glcollide::passes {

class FeatureCcd {
  public:
    /// `budget`: boxes per pair (1 ... 21844, CcdSettings::budget); `minSeparation` in metres.
    FeatureCcd(std::uint32_t nodeCount, std::uint32_t faceCount, std::uint32_t budget, float minSeparation);
    /// Adds the Ccd stage to `chain`; call after FeaturePairs::addStages.
    void addStages(StageChain& chain, AppendLists& lists);
    /// Binds the per-node times of impact (GLC_BIND_NODE_TOI).
    void bind() const;
    /// uint per node: the bits of its earliest time of impact in [0, 1], +inf bits when none.
    [[nodiscard]] const gl::Buffer& nodeToi() const { return m_nodeToi; }
    /// Pairs whose four nodes do not move are not tested (the safe step, decision 0024).
    void skipStillPairs(bool skip) { setSelection("u_skipStill", skip ? 1u : 0u); }
    /// A pair touches when it comes within min(minSeparation, half its distance at x0) (the safe
    /// step, decision 0024) instead of within minSeparation.
    void relativeSeparation(bool relative, float minSeparation) {
        setSelection("u_gapRelative", relative ? 1u : 0u);
        setSelection("u_minSeparation", minSeparation);
    }
    /// Radial culling leaves most pairs out: a filter kernel first compacts the pairs to test
    /// (feature_ccd_filter.comp), so the CCD kernel runs only on those. Call before addStages.
    void compactPairs(bool compact) { m_compact = compact; }
    /// Pairs between faces that intersect at x0 are left out (the safe step's recovery from
    /// intersecting input, decision 0024): run() first marks them from the intersection list.
    void skipTangledPairs(bool skip);
    [[nodiscard]] bool skipsTangledPairs() const { return m_skipTangled; }
    /// uint per node, then per face: the marks of the last run() (TangledMarks).
    [[nodiscard]] const gl::Buffer& tangled() const { return m_tangled; }
    /// The stage itself: resets the times of impact and the CCD statistics, (re)marks the tangled
    /// faces when `mark` and skipTangledPairs is on, tests every pair. Expects the positions, the
    /// predicted positions, the lists and bind() bound.
    void run(AppendLists& lists, bool mark = true);

  private:
    /// A uniform of the pair selection (common/ccd_pair_selection.glsl): the CCD kernel's and
    /// the filter's, which must decide alike.
    template <typename T> void setSelection(const char* uniform, T value) {
        m_program.set(uniform, value);
        m_filter.set(uniform, value);
    }

    gl::Buffer m_nodeToi;
    gl::Buffer m_tangled; ///< uint per node, then per face: 1 where a face pair intersects at x0
    bool m_skipTangled = false;
    bool m_compact = false;
    gl::ComputeProgram m_program;
    gl::ComputeProgram m_filter; ///< feature_ccd_filter.comp (compactPairs)
    gl::ComputeProgram m_marks;  ///< tangled_marks.comp
};

} // namespace glcollide::passes
