#include "passes/broad_phase/masked_broad_phase.hpp"

#include "core/gpu_layout.hpp"
#include "passes/broad_phase/upper_triangle.hpp"

#include <glcollide/error.hpp>

namespace glcollide::passes {
namespace {

std::uint32_t checkedBoxCount(const model::OctreeLayout& layout) {
    if (layout.boxCount > 65535)
        throw Error("collision: masked broad phase supports at most 65535 leaf boxes (the mask is boxes^2)");
    return layout.boxCount;
}

} // namespace

MaskedBroadPhase::MaskedBroadPhase(const BroadPhaseContext& c)
    : m_leafBoxes(c), m_faceCount(static_cast<std::uint32_t>(c.model.faceCount())),
      m_mask("boxMask", std::size_t{checkedBoxCount(c.layout)} * c.layout.boxCount * sizeof(std::uint32_t)),
      m_boxMask("box_mask"), m_facePairs("masked_face_pairs", faceBoxDefines(c)) {
    for (const gl::ComputeProgram* p : {&m_boxMask, &m_facePairs}) {
        p->set("u_pairRules", c.pairRules);
        p->set("u_boxCount", c.layout.boxCount);
    }
    m_boxMask.set("u_boxesPerObject", c.layout.boxesPerObject);
    m_facePairs.set("u_faceCount", m_faceCount);
    m_facePairs.set("u_halfThickness", c.halfThickness);
}

void MaskedBroadPhase::addStages(StageChain& chain, AppendLists&) {
    chain.add(m_leafBoxes.refitStage());
    chain.add({PassId::BBCollision, {}, [this] {
                   dispatchUpperTriangle(m_boxMask, m_leafBoxes.boxCount(), GLC_BOX_PAIR_TILE);
               }});
    chain.add({PassId::BBCollision, {GLC_LIST_CANDIDATES}, [this] {
                   dispatchUpperTriangle(m_facePairs, m_faceCount, GLC_FACE_PAIR_TILE);
               }});
}

void MaskedBroadPhase::bind() const {
    m_leafBoxes.bind();
    m_mask.bindStorage(GLC_BIND_BOX_MASK);
}

std::vector<const gl::Buffer*> MaskedBroadPhase::buffers() const {
    std::vector<const gl::Buffer*> b = m_leafBoxes.buffers();
    b.push_back(&m_mask);
    return b;
}

} // namespace glcollide::passes
