#include "passes/broad_phase/bvh_broad_phase.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <string>

namespace glcollide::passes {
namespace {

std::uint32_t checkedFaceCount(const model::FlatModel& model) {
    // Node indices 0 .. 2n-2 and GLC_BVH_NONE must fit a uint; the sort takes up to 2^28 keys.
    if (model.faceCount() > (std::size_t{1} << 28))
        throw Error("collision: the bvh broad phase supports at most 2^28 faces, the scene has " +
                    std::to_string(model.faceCount()));
    return static_cast<std::uint32_t>(model.faceCount());
}

std::uint32_t rebuildPeriod(const BvhSettings& s, std::uint32_t substepsPerFrame) {
    switch (s.rebuild) {
    case BvhRebuild::EverySubstep:
        return 1;
    case BvhRebuild::EveryFrame:
        return substepsPerFrame;
    case BvhRebuild::EveryNFrames:
        return static_cast<std::uint32_t>(s.rebuildFrames) * substepsPerFrame;
    case BvhRebuild::Never:
        return 0;
    }
    return 1;
}

std::size_t nodeCount(std::uint32_t faces) {
    return faces == 0 ? 0 : 2 * std::size_t{faces} - 1;
}

/// The empty box as order-preserving uints (bvh.glsl orderedBits): lo = +max, hi = -max.
constexpr std::array<std::uint32_t, 8> kEmptyBounds = {0xffffffffu, 0xffffffffu, 0xffffffffu, 0u,
                                                       0u,          0u,          0u,          0u};

} // namespace

BvhBroadPhase::BvhBroadPhase(const BroadPhaseContext& c)
    : m_faceCount(checkedFaceCount(c.model)), m_visitsPerRound(c.settings.bvh.visitsPerRound),
      m_rebuildPeriod(rebuildPeriod(c.settings.bvh, std::max<std::uint32_t>(1, c.substepsPerFrame))),
      m_sort(std::max<std::uint32_t>(1, m_faceCount)),
      m_bounds("bvhBounds", sizeof kEmptyBounds, kEmptyBounds.data()),
      m_boxes("bvhBoxes", nodeCount(m_faceCount) * sizeof(gpu::GpuBox)),
      m_links("bvhLinks", nodeCount(m_faceCount) * 4 * sizeof(std::uint32_t)),
      // Zero: the refit's counters start (and end) at 0.
      m_visits(gl::makeBuffer("bvhVisits",
                              std::vector<std::uint32_t>(std::max<std::uint32_t>(1, m_faceCount) - 1))),
      m_resume("bvhResume", std::size_t{m_faceCount} * sizeof(std::uint32_t)), m_boundsProgram("bvh_bounds"),
      m_morton("bvh_morton"), m_hierarchy("bvh_hierarchy"), m_refit("bvh_refit", faceBoxDefines(c)),
      m_traverse("bvh_traverse") {
    if (m_visitsPerRound < 1 || m_visitsPerRound > 65534)
        throw Error("collision: bvh visits_per_round must be in 1 ... 65534 (llvmpipe ends a loop after "
                    "65535 iterations)");
    for (const gl::ComputeProgram* p : {&m_boundsProgram, &m_morton, &m_hierarchy, &m_refit, &m_traverse})
        p->set("u_faceCount", m_faceCount);
    m_refit.set("u_halfThickness", c.halfThickness);
    m_traverse.set("u_pairRules", c.pairRules);
    m_traverse.set("u_visitsPerRound", m_visitsPerRound);
}

void BvhBroadPhase::prepare() {
    m_rebuildDue = m_detects == 0 || (m_rebuildPeriod != 0 && m_detects % m_rebuildPeriod == 0);
    ++m_detects;
}

void BvhBroadPhase::addStages(StageChain& chain, AppendLists& lists) {
    chain.add({PassId::BvhBuild, {}, [this] {
                   if (m_rebuildDue) build();
               }});
    chain.add({PassId::BvhRefit, {}, [this] { refit(); }});
    // A query that used up its rounds: twice the rounds, and the chain reruns the traversal.
    chain.add({PassId::BvhTraverse,
               {GLC_LIST_CANDIDATES},
               [this, &lists] { traverse(lists); },
               [this, &lists] {
                   const std::uint32_t unfinished = lists.stat(GLC_STAT_BVH_UNFINISHED);
                   if (unfinished == 0) return false;
                   // A stackless traversal of a valid tree visits each of its 2n - 1 nodes at
                   // most once per query: a query unfinished after that many visits is walking a
                   // malformed tree (links with a cycle) and would rerun for ever.
                   const std::uint64_t nodes = 2ull * m_faceCount - 1ull;
                   if (std::uint64_t(m_rounds) * m_visitsPerRound >= nodes)
                       throw Error("collision: bvh traversal: " + std::to_string(unfinished) +
                                   " queries unfinished after " +
                                   std::to_string(std::uint64_t(m_rounds) * m_visitsPerRound) +
                                   " node visits each, more than the tree's " + std::to_string(nodes) +
                                   " nodes: the hierarchy's links are malformed (a driver or engine bug)");
                   m_rounds *= 2;
                   return true;
               }});
}

void BvhBroadPhase::build() {
    if (m_faceCount == 0) return;
    m_bounds.upload(0, sizeof kEmptyBounds, kEmptyBounds.data());
    m_boundsProgram.use();
    m_boundsProgram.dispatch1D(m_faceCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_sort.bindForWriting();
    m_morton.use();
    m_morton.dispatch1D(m_faceCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_sort.sort(m_faceCount, 30);
    m_sort.bindForReading();
    m_hierarchy.use();
    m_hierarchy.dispatch1D(m_faceCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void BvhBroadPhase::refit() {
    m_refit.use();
    m_refit.dispatch1D(m_faceCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void BvhBroadPhase::traverse(AppendLists& lists) {
    lists.resetStats({GLC_STAT_BVH_UNFINISHED, GLC_STAT_BVH_NODE_VISITS});
    m_traverse.use();
    for (std::uint32_t round = 0; round < m_rounds; ++round) {
        m_traverse.set("u_firstRound", round == 0 ? 1u : 0u);
        m_traverse.set("u_lastRound", round + 1 == m_rounds ? 1u : 0u);
        m_traverse.dispatch1D(m_faceCount, GLC_WORKGROUP_SIZE);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

void BvhBroadPhase::bind() const {
    m_bounds.bindStorage(GLC_BIND_BVH_BOUNDS);
    m_boxes.bindStorage(GLC_BIND_BVH_BOXES);
    m_links.bindStorage(GLC_BIND_BVH_LINKS);
    m_visits.bindStorage(GLC_BIND_BVH_VISITS);
    m_resume.bindStorage(GLC_BIND_BVH_RESUME);
}

std::vector<const gl::Buffer*> BvhBroadPhase::buffers() const {
    std::vector<const gl::Buffer*> b = {&m_bounds, &m_boxes, &m_links, &m_visits, &m_resume};
    for (const gl::Buffer* s : m_sort.buffers()) b.push_back(s);
    return b;
}

} // namespace glcollide::passes
