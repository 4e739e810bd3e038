#include "passes/ground_impact.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <string>

namespace glcollide::passes {

GroundImpactPass::GroundImpactPass(std::uint32_t nodeCount, const GroundImpactParams& params)
    : m_nodeCount(nodeCount), m_program("ground_impact") {
    if (!(params.restitution > 0.0 && params.restitution <= 1.0))
        throw Error("GroundImpact: restitution must be in (0, 1], got " + std::to_string(params.restitution));
    if (!(params.friction >= 0.0) || !(params.restingSpeed >= 0.0))
        throw Error("GroundImpact: friction and resting speed must be >= 0");
    m_program.set("u_nodeCount", nodeCount);
    m_program.set("u_bandTop", static_cast<float>(params.bandTop));
    m_program.set("u_gravityY", static_cast<float>(params.gravityY));
    m_program.set("u_restitution", static_cast<float>(params.restitution));
    m_program.set("u_friction", static_cast<float>(params.friction));
    m_program.set("u_restingSpeed", static_cast<float>(params.restingSpeed));
}

void GroundImpactPass::dispatch(const DeviceBuffers& b, const gl::Buffer& start) const {
    if (m_nodeCount == 0) return;
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    bindRequired(start, GLC_BIND_START_VELOCITIES, kName, "startVelocities");
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_program.use();
    m_program.dispatch1D(m_nodeCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

} // namespace glcollide::passes
