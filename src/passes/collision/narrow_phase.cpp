#include "passes/collision/narrow_phase.hpp"

#include "core/gpu_layout.hpp"

namespace glcollide::passes {

NarrowPhase::NarrowPhase(TriTriPrecision precision) {
    if (precision == TriTriPrecision::Robust) {
        m_test = gl::ComputeProgram("tri_tri_filtered");
        m_exact = gl::ComputeProgram("tri_tri_exact");
    } else {
        m_test = gl::ComputeProgram("tri_tri_fast");
    }
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
                   lists.dispatchOver(m_test, GLC_LIST_CANDIDATES, GLC_WORKGROUP_SIZE);
               }});
    chain.add({PassId::TriTri, {GLC_LIST_INTERSECTIONS}, [this, &lists] {
                   lists.dispatchOver(m_exact, GLC_LIST_UNDECIDED, GLC_WORKGROUP_SIZE);
               }});
}

} // namespace glcollide::passes
