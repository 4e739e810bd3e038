#pragma once
// TriTri, the narrow phase (seeds/002 Alg. 3): tests every candidate face pair and appends the
// pairs whose closed triangles intersect to GLC_LIST_INTERSECTIONS. Fast precision is one kernel
// (tri_tri_fast.comp). Robust precision is two stages of the TriTri pass: the filtered test
// (tri_tri_filtered.comp) decides what its certified float filters can and appends the rest to
// GLC_LIST_UNDECIDED; TriTriExact (tri_tri_exact.comp) decides those in integer arithmetic
// (docs/narrow-phase.md). Both are dispatched indirectly from their list's count.

#include "gl/program.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/collision/stage_chain.hpp"

#include <glcollide/scene.hpp>

namespace glcollide::passes {

class NarrowPhase {
  public:
    explicit NarrowPhase(TriTriPrecision precision);
    /// Test hook: robust precision with the given filtered and exact programs (e.g. an exact
    /// kernel built from modified source, tests/gl/tri_tri_gl_test.cpp).
    NarrowPhase(gl::ComputeProgram filtered, gl::ComputeProgram exact);
    /// Declares the undecided list (robust; it keeps the candidates' capacity) and adds the TriTri
    /// stages to `chain`. Call after the candidate and intersection lists are declared.
    void addStages(StageChain& chain, AppendLists& lists);
    /// After the chain's read-back: throws Error when the exact pass could not finish a pair
    /// (GpuCollisionCounters.exactErrorCount; never, by the argument of tri_tri_robust.glsl), so
    /// that no answer of a voided run is used.
    static void throwIfExactPassFailed(const AppendLists& lists);

  private:
    gl::ComputeProgram m_test;  ///< fast, or the robust filtered test
    gl::ComputeProgram m_exact; ///< robust only
};

} // namespace glcollide::passes
