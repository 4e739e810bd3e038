#pragma once
// The host's pull on one node (Engine::setPull): shaders/passes/node_pull.comp, dispatched once
// per substep while a pull is set. Built on the first setPull, so an engine that is never pulled
// compiles and runs nothing of it.

#include "gl/program.hpp"
#include "passes/device_buffers.hpp"

#include <glcollide/engine.hpp>

namespace glcollide::engine {

class NodePullPass {
  public:
    NodePullPass();
    /// v += h·w·(k·(target − x) − c·v) for the pulled node; followed by a storage barrier.
    void dispatch(const passes::DeviceBuffers& buffers, const NodePull& pull, double h) const;

  private:
    gl::ComputeProgram m_program;
};

/// Throws Error when the pull cannot be applied to an engine of `nodeCount` nodes: a node out of
/// range, a non-finite target, a negative or non-finite stiffness or damping.
void validatePull(const NodePull& pull, std::uint32_t nodeCount);

} // namespace glcollide::engine
