#include "passes/broad_phase/all_pairs_broad_phase.hpp"

#include "core/gpu_layout.hpp"
#include "passes/broad_phase/upper_triangle.hpp"

namespace glcollide::passes {

AllPairsBroadPhase::AllPairsBroadPhase(const BroadPhaseContext& c)
    : m_faceCount(static_cast<std::uint32_t>(c.model.faceCount())),
      m_facePairs("all_face_pairs", faceBoxDefines(c)) {
    m_facePairs.set("u_pairRules", c.pairRules);
    m_facePairs.set("u_faceCount", m_faceCount);
    m_facePairs.set("u_halfThickness", c.halfThickness);
}

void AllPairsBroadPhase::addStages(StageChain& chain, AppendLists&) {
    chain.add({PassId::BBCollision, {GLC_LIST_CANDIDATES}, [this] {
                   dispatchUpperTriangle(m_facePairs, m_faceCount, GLC_FACE_PAIR_TILE);
               }});
}

} // namespace glcollide::passes
