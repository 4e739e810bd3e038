#pragma once
// The work-group layout of the passes that gather each node's spring row (shaders/common/
// row_gather.glsl): ⌈nodes / GLC_WORKGROUP_SIZE⌉ groups of one node per invocation, then one group
// per heavy node (more than kHeavyRow springs). Used by SpringUpdate and the implicit solver.

#include "gl/program.hpp"
#include "passes/device_buffers.hpp"

#include <cstdint>
#include <vector>

namespace glcollide::passes {

/// Nodes whose spring row is longer than kHeavyRow, ascending (DeviceBuffers::heavyNodes).
std::vector<std::uint32_t> heavyRowNodes(const std::vector<std::uint32_t>& rowOffsets);

class RowLayout {
  public:
    RowLayout(std::uint32_t nodeCount, std::uint32_t heavyCount);
    /// The layout of `buffers` (its node count and heavy-node list).
    static RowLayout of(const DeviceBuffers& buffers);

    /// Groups of a dispatch: one partial sum each in the solver.
    [[nodiscard]] std::uint32_t groups() const { return m_lightGroups + m_heavyCount; }

    /// Binds the row offsets and the heavy-node list, uses `program` and sets its layout uniforms.
    void bind(const gl::ComputeProgram& program, const DeviceBuffers& buffers, const char* pass) const;
    /// Dispatches `program` over the layout, then a storage barrier.
    void dispatch(const gl::ComputeProgram& program) const;

  private:
    std::uint32_t m_nodeCount;
    std::uint32_t m_lightGroups;
    std::uint32_t m_heavyCount;
};

} // namespace glcollide::passes
