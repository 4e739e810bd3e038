#include "passes/radial_culling.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>
#include <glm/vec4.hpp>

#include <string>

namespace glcollide::passes {
namespace {
std::vector<std::uint32_t> surfaceRanges(const std::vector<RadialSurface>& surfaces) {
    std::vector<std::uint32_t> ranges;
    for (std::size_t o = 0; o < surfaces.size(); ++o) {
        if (surfaces[o].nodeCount == 0)
            throw Error(std::string(RadialCullingPass::kName) + ": observer " + std::to_string(o) +
                        " has a surface with no nodes");
        ranges.push_back(surfaces[o].firstNode);
        ranges.push_back(surfaces[o].nodeCount);
    }
    if (ranges.empty()) ranges = {0u, 0u}; // a buffer the consumers can bind
    return ranges;
}
} // namespace

RadialCullingPass::RadialCullingPass(const RadialCullingConfig& config)
    : m_faceCount(static_cast<std::uint32_t>(config.faceObserver.size())),
      m_observerCount(static_cast<std::uint32_t>(config.surfaces.size())),
      m_classify(config.faceObserver, m_observerCount),
      m_surfaces(gl::makeBuffer("radialSurfaces", surfaceRanges(config.surfaces))),
      m_free("radialFree", (1u + (m_faceCount + 31u) / 32u) * sizeof(std::uint32_t)),
      m_moved("radialMoved", sizeof(std::uint32_t)), m_observers("radial_observers"),
      m_freeProgram("radial_free"), m_hostCheck("radial_host_check") {
    for (std::uint32_t o : config.faceObserver) m_observedFaces += o != kNoRadialObserver ? 1u : 0u;
    m_freeProgram.set("u_faceCount", m_faceCount);
    m_free.fill32(0u);
}

void RadialCullingPass::bindForConsumers() const {
    m_classify.faceObserver().bindStorage(GLC_BIND_RADIAL_FACE_OBSERVER);
    m_surfaces.bindStorage(GLC_BIND_RADIAL_OBSERVER_NODES);
    m_free.bindStorage(GLC_BIND_RADIAL_FREE);
}

void RadialCullingPass::run(AppendLists& lists) const {
    lists.resetStats({GLC_STAT_RADIAL_NON_POSITIVE, GLC_STAT_RADIAL_FREE});
    bindForConsumers();
    m_classify.observers().bindStorage(GLC_BIND_RADIAL_OBSERVERS);
    m_observers.use();
    gl::ComputeProgram::dispatch(m_observerCount, 1, 1); // one work group per observer; counted
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_classify.dispatchOnBoundPositions();
    m_free.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_freeProgram.use();
    m_freeProgram.dispatch1D(std::max(m_faceCount, 1u), GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void RadialCullingPass::switchOff() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after the last substep's reads of the mask
    const std::uint32_t off = 0;
    m_free.upload(0, sizeof off, &off);
}

bool RadialCullingPass::hostMovedNodes(const DeviceBuffers& b) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, "RadialHostCheck", "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, "RadialHostCheck", "predictedPositions");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_moved.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_moved.bindStorage(GLC_BIND_RADIAL_MOVED);
    m_hostCheck.use();
    m_hostCheck.set("u_nodeCount", b.nodeCount);
    m_hostCheck.dispatch1D(std::max(b.nodeCount, 1u), GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t moved = 0;
    m_moved.download(0, sizeof moved, &moved);
    return moved != 0;
}

std::vector<std::uint32_t> RadialCullingPass::readFreeMask() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> words((m_faceCount + 31u) / 32u);
    if (!words.empty())
        m_free.download(sizeof(std::uint32_t), words.size() * sizeof(std::uint32_t), words.data());
    return words;
}

std::vector<RadialObserver> RadialCullingPass::readObservers() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> packed(2 * std::size_t{m_observerCount});
    if (!packed.empty()) m_classify.observers().download(0, packed.size() * sizeof(glm::vec4), packed.data());
    std::vector<RadialObserver> out;
    for (std::size_t o = 0; o < m_observerCount; ++o)
        out.push_back({glm::vec3(packed[2 * o]), glm::vec3(packed[2 * o + 1])});
    return out;
}

} // namespace glcollide::passes
