#include "engine/node_pull.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <cmath>
#include <string>

namespace glcollide::engine {

NodePullPass::NodePullPass() : m_program("node_pull") {}

void NodePullPass::dispatch(const passes::DeviceBuffers& b, const NodePull& pull, double h) const {
    passes::bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, "NodePull", "positions");
    passes::bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, "NodePull", "velocities");
    m_program.use();
    m_program.set("u_node", pull.globalNode);
    m_program.set("u_target", pull.target);
    m_program.set("u_stiffness", static_cast<float>(pull.stiffness));
    m_program.set("u_damping", static_cast<float>(pull.damping));
    m_program.set("u_h", static_cast<float>(h));
    gl::ComputeProgram::dispatch(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void validatePull(const NodePull& pull, std::uint32_t nodeCount) {
    if (pull.globalNode >= nodeCount)
        throw Error("setPull: node " + std::to_string(pull.globalNode) + " is out of range (the engine has " +
                    std::to_string(nodeCount) + " nodes)");
    if (!std::isfinite(pull.target.x) || !std::isfinite(pull.target.y) || !std::isfinite(pull.target.z))
        throw Error("setPull: the target is not finite");
    if (!(std::isfinite(pull.stiffness) && pull.stiffness >= 0.0))
        throw Error("setPull: the stiffness must be finite and >= 0 N/m");
    if (!(std::isfinite(pull.damping) && pull.damping >= 0.0))
        throw Error("setPull: the damping must be finite and >= 0 N s/m");
}

} // namespace glcollide::engine
