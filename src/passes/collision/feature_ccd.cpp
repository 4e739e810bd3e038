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
      m_program("feature_ccd"), m_filter("feature_ccd_filter"), m_marks("tangled_marks") {
    if (budget < 1 || budget > kMaxBudget)
        throw Error("collision: ccd budget must be in 1 ... 21844 (llvmpipe ends a shader loop after 65,535 "
                    "iterations; a box costs three), got " +
                    std::to_string(budget));
    if (!(minSeparation >= 0.0f)) throw Error("collision: ccd min_separation must be >= 0");
    m_program.set("u_budget", budget);
    setSelection("u_minSeparation", minSeparation);
    skipStillPairs(false);
    relativeSeparation(false, minSeparation);
    skipTangledPairs(false);
    setSelection("u_nodeCount", nodeCount);
    m_program.set("u_compacted", 0u);
    m_marks.set("u_nodeCount", nodeCount);
}

void FeatureCcd::skipTangledPairs(bool skip) {
    m_skipTangled = skip;
    setSelection("u_skipTangled", skip ? 1u : 0u);
}

void FeatureCcd::bind() const {
    m_nodeToi.bindStorage(GLC_BIND_NODE_TOI);
    m_tangled.bindStorage(GLC_BIND_TANGLED);
    if (!m_compact) { // the kernel declares the filter's lists; it reads them only when compacted
        m_tangled.bindStorage(GLC_BIND_CCD_VERTEX_FACE_TESTS);
        m_tangled.bindStorage(GLC_BIND_CCD_EDGE_EDGE_TESTS);
    }
}

void FeatureCcd::addStages(StageChain& chain, AppendLists& lists) {
    if (!m_compact) {
        chain.add({PassId::Ccd, {}, [this, &lists] { run(lists); }});
        return;
    }
    // Indices into the feature lists: subsets of them, so they keep their capacities and never
    // overflow on their own.
    lists.declare(GLC_LIST_CCD_VERTEX_FACE_TESTS,
                  {"ccdVertexFaceTests", "indices", sizeof(std::uint32_t), GLC_BIND_CCD_VERTEX_FACE_TESTS, 1,
                   static_cast<int>(GLC_LIST_VERTEX_FACE)});
    lists.declare(GLC_LIST_CCD_EDGE_EDGE_TESTS,
                  {"ccdEdgeEdgeTests", "indices", sizeof(std::uint32_t), GLC_BIND_CCD_EDGE_EDGE_TESTS, 1,
                   static_cast<int>(GLC_LIST_EDGE_EDGE)});
    chain.add({PassId::Ccd, {GLC_LIST_CCD_VERTEX_FACE_TESTS, GLC_LIST_CCD_EDGE_EDGE_TESTS}, [this, &lists] {
                   run(lists);
               }});
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
    if (m_compact) {
        lists.zeroCounts({GLC_LIST_CCD_VERTEX_FACE_TESTS, GLC_LIST_CCD_EDGE_EDGE_TESTS});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        for (std::uint32_t edgeEdge : {0u, 1u}) {
            m_filter.set("u_edgeEdge", edgeEdge);
            lists.dispatchOver(m_filter, edgeEdge ? GLC_LIST_EDGE_EDGE : GLC_LIST_VERTEX_FACE,
                               GLC_WORKGROUP_SIZE);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    m_program.set("u_compacted", m_compact ? 1u : 0u);
    m_program.set("u_edgeEdge", 0u);
    lists.dispatchOver(m_program, m_compact ? GLC_LIST_CCD_VERTEX_FACE_TESTS : GLC_LIST_VERTEX_FACE,
                       GLC_WORKGROUP_SIZE);
    m_program.set("u_edgeEdge", 1u);
    lists.dispatchOver(m_program, m_compact ? GLC_LIST_CCD_EDGE_EDGE_TESTS : GLC_LIST_EDGE_EDGE,
                       GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

} // namespace glcollide::passes
