#include "passes/broad_phase/octree_broad_phase.hpp"

#include "core/gpu_layout.hpp"
#include "passes/broad_phase/upper_triangle.hpp"

#include <glcollide/error.hpp>

#include <algorithm>
#include <string>

namespace glcollide::passes {
namespace {

/// z slices per box pair so that no expansion invocation loops more than 2^15 times: llvmpipe
/// stops an invocation after 65535 loop iterations. The flat index needs nA x nB < 2^32.
std::uint32_t expandSlices(const model::OctreeLayout& layout) {
    std::uint64_t largest = 0;
    for (std::size_t b = 0; b + 1 < layout.boxFaces.offsets.size(); ++b)
        largest =
            std::max<std::uint64_t>(largest, layout.boxFaces.offsets[b + 1] - layout.boxFaces.offsets[b]);
    if (largest >= 65536)
        throw Error("collision octree: a leaf box holds " + std::to_string(largest) +
                    " faces (at most 65535); raise /collision/octree_depth");
    constexpr std::uint64_t perSlice = std::uint64_t{GLC_EXPAND_GROUP} * 32768;
    return static_cast<std::uint32_t>(
        std::max<std::uint64_t>(1, (largest * largest + perSlice - 1) / perSlice));
}

} // namespace

OctreeBroadPhase::OctreeBroadPhase(const BroadPhaseContext& c)
    : m_leafBoxes(c), m_boxPairCapacity(c.boxPairCapacity ? c.boxPairCapacity : c.settings.initialCapacity),
      m_expandSlices(expandSlices(c.layout)), m_boxPairs("octree_box_pairs"),
      m_expand("octree_expand", faceBoxDefines(c)) {
    for (const gl::ComputeProgram* p : {&m_boxPairs, &m_expand}) {
        p->set("u_pairRules", c.pairRules);
        p->set("u_boxCount", c.layout.boxCount);
        p->set("u_boxesPerObject", c.layout.boxesPerObject);
        p->set("u_halfThickness", c.halfThickness);
    }
}

void OctreeBroadPhase::addStages(StageChain& chain, AppendLists& lists) {
    lists.declare(GLC_LIST_BOX_PAIRS,
                  {"boxPairs", "pairs", 2 * sizeof(std::uint32_t), GLC_BIND_BOX_PAIRS, m_boxPairCapacity});
    chain.add(m_leafBoxes.refitStage());
    chain.add({PassId::BBCollision, {GLC_LIST_BOX_PAIRS}, [this] {
                   dispatchUpperTriangle(m_boxPairs, m_leafBoxes.boxCount(), GLC_BOX_PAIR_TILE);
               }});
    // One work group (x m_expandSlices in z) per stored box pair.
    chain.add({PassId::BBCollision, {GLC_LIST_CANDIDATES}, [this, &lists] {
                   lists.dispatchOver(m_expand, GLC_LIST_BOX_PAIRS, 1u, m_expandSlices);
               }});
}

} // namespace glcollide::passes
