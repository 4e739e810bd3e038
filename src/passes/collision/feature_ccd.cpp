#include "passes/collision/feature_ccd.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <string>
#include <vector>

namespace glcollide::passes {
namespace {
constexpr std::uint32_t kNoImpact = 0x7F800000u; // bits of +inf: above every time in [0, 1]
constexpr std::uint32_t kMaxBudget = 21844;      // llvmpipe: 65,535 loop iterations, 3 per box
} // namespace

FeatureCcd::FeatureCcd(std::uint32_t nodeCount, std::uint32_t faceCount, std::uint32_t budget,
                       float minSeparation)
    : m_nodeToi(gl::makeBuffer("nodeToi", std::vector<std::uint32_t>(nodeCount, kNoImpact))),
      m_tangled(
          gl::makeBuffer("tangled", std::vector<std::uint32_t>(std::size_t{nodeCount} + faceCount, 0u))),
      m_program("feature_ccd"), m_marks("tangled_marks") {
    if (budget < 1 || budget > kMaxBudget)
        throw Error("collision: ccd budget must be in 1 ... 21844 (llvmpipe ends a shader loop after 65,535 "
                    "iterations; a box costs three), got " +
                    std::to_string(budget));
    if (!(minSeparation >= 0.0f)) throw Error("collision: ccd min_separation must be >= 0");
    m_program.set("u_budget", budget);
    m_program.set("u_minSeparation", minSeparation);
    skipStillPairs(false);
    relativeSeparation(false, minSeparation);
    skipTangledPairs(false);
    m_program.set("u_nodeCount", nodeCount);
    m_marks.set("u_nodeCount", nodeCount);
}

void FeatureCcd::skipTangledPairs(bool skip) {
    m_skipTangled = skip;
    m_program.set("u_skipTangled", skip ? 1u : 0u);
}

void FeatureCcd::bind() const {
    m_nodeToi.bindStorage(GLC_BIND_NODE_TOI);
    m_tangled.bindStorage(GLC_BIND_TANGLED);
}

void FeatureCcd::addStages(StageChain& chain, AppendLists& lists) {
    chain.add({PassId::Ccd, {}, [this, &lists] { run(lists); }});
}

void FeatureCcd::run(AppendLists& lists, bool mark) {
    lists.resetStats({GLC_STAT_CCD_VERTEX_FACE_HITS, GLC_STAT_CCD_EDGE_EDGE_HITS, GLC_STAT_CCD_CAPPED,
                      GLC_STAT_CCD_BOXES, GLC_STAT_CCD_EARLIEST_TOI, GLC_STAT_CCD_TANGLED,
                      GLC_STAT_RADIAL_CULLED_CCD});
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after the last substep's reads of the times
    m_nodeToi.fill32(kNoImpact);
    if (m_skipTangled && mark) {
        m_tangled.fill32(0u);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        lists.dispatchOver(m_marks, GLC_LIST_INTERSECTIONS, GLC_WORKGROUP_SIZE);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_program.set("u_edgeEdge", 0u);
    lists.dispatchOver(m_program, GLC_LIST_VERTEX_FACE, GLC_WORKGROUP_SIZE);
    m_program.set("u_edgeEdge", 1u);
    lists.dispatchOver(m_program, GLC_LIST_EDGE_EDGE, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

} // namespace glcollide::passes
