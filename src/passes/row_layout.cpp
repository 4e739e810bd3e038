#include "passes/row_layout.hpp"

#include "core/dynamics_params.hpp"
#include "core/gpu_layout.hpp"

#include <epoxy/gl.h>

namespace glcollide::passes {

std::vector<std::uint32_t> heavyRowNodes(const std::vector<std::uint32_t>& rowOffsets) {
    std::vector<std::uint32_t> heavy;
    for (std::size_t i = 0; i + 1 < rowOffsets.size(); ++i)
        if (rowOffsets[i + 1] - rowOffsets[i] > kHeavyRow) heavy.push_back(static_cast<std::uint32_t>(i));
    return heavy;
}

RowLayout::RowLayout(std::uint32_t nodeCount, std::uint32_t heavyCount)
    : m_nodeCount(nodeCount), m_lightGroups((nodeCount + GLC_WORKGROUP_SIZE - 1) / GLC_WORKGROUP_SIZE),
      m_heavyCount(heavyCount) {}

RowLayout RowLayout::of(const DeviceBuffers& b) {
    return {b.nodeCount, static_cast<std::uint32_t>(b.heavyNodes.bytes() / sizeof(std::uint32_t))};
}

void RowLayout::bind(const gl::ComputeProgram& program, const DeviceBuffers& b, const char* pass) const {
    bindRequired(b.nodeSpringOffsets, GLC_BIND_NODE_SPRING_OFFSETS, pass, "nodeSpringOffsets");
    bindRequired(b.heavyNodes, GLC_BIND_HEAVY_NODES, pass, "heavyNodes");
    program.use();
    program.set("u_nodeCount", m_nodeCount);
    program.set("u_lightGroups", m_lightGroups);
    program.set("u_heavyCount", m_heavyCount);
}

void RowLayout::dispatch(const gl::ComputeProgram& program) const {
    program.dispatch1D(groups() * GLC_WORKGROUP_SIZE, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace glcollide::passes
