#include "passes/collision/narrow_phase.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <string>
#include <utility>

namespace glcollide::passes {

NarrowPhase::NarrowPhase(TriTriPrecision precision) {
    if (precision == TriTriPrecision::Robust) {
        m_test = gl::ComputeProgram("tri_tri_filtered");
        m_exact = gl::ComputeProgram("tri_tri_exact");
    } else {
        m_test = gl::ComputeProgram("tri_tri_fast");
    }
}

NarrowPhase::NarrowPhase(gl::ComputeProgram filtered, gl::ComputeProgram exact)
    : m_test(std::move(filtered)), m_exact(std::move(exact)) {}

void NarrowPhase::throwIfExactPassFailed(const AppendLists& lists) {
    if (lists.stat(GLC_STAT_EXACT_ERRORS) == 0) return;
    throw Error("TriTri: the exact pass could not finish " +
                std::to_string(lists.stat(GLC_STAT_EXACT_ERRORS)) +
                " candidate pairs (more signs to record than GLC_MAX_EXACT, or a predicate on a point "
                "that is not an input corner: a broken assumption of shaders/common/tri_tri_robust.glsl); "
                "their answers would not be exact");
}

void NarrowPhase::addStages(StageChain& chain, AppendLists& lists) {
    if (m_exact.name() == 0) {
        chain.add({PassId::TriTri, {GLC_LIST_INTERSECTIONS}, [this, &lists] {
                       lists.dispatchOver(m_test, GLC_LIST_CANDIDATES, GLC_WORKGROUP_SIZE);
                   }});
        return;
    }
    // Candidate indices: a subset of the candidates, so it keeps their capacity and never
    // overflows on its own.
    lists.declare(GLC_LIST_UNDECIDED, {"undecided", "indices", sizeof(std::uint32_t), GLC_BIND_UNDECIDED, 1,
                                       static_cast<int>(GLC_LIST_CANDIDATES)});
    chain.add({PassId::TriTri, {GLC_LIST_UNDECIDED, GLC_LIST_INTERSECTIONS}, [this, &lists] {
                   lists.resetStats({GLC_STAT_RADIAL_CULLED_TRI_TRI}); // a rerun counts again
                   lists.dispatchOver(m_test, GLC_LIST_CANDIDATES, GLC_WORKGROUP_SIZE);
               }});
    chain.add({PassId::TriTri, {GLC_LIST_INTERSECTIONS}, [this, &lists] {
                   lists.dispatchOver(m_exact, GLC_LIST_UNDECIDED, GLC_WORKGROUP_SIZE);
               }});
}

} // namespace glcollide::passes
