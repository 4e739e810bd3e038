#include "passes/dynamics_passes.hpp"

#include "core/gpu_layout.hpp"
#include "passes/row_layout.hpp"

#include <epoxy/gl.h>

#include <algorithm>

namespace glcollide::passes {
namespace {

std::vector<std::string> nodeUpdateDefines(const NodeUpdateParams& c) {
    std::vector<std::string> d;
    if (c.forces) d.emplace_back("GLC_FORCES");
    if (c.ground) d.emplace_back("GLC_GROUND");
    if (c.ground && c.groundBand > 0.0) d.emplace_back("GLC_GROUND_BAND");
    if (c.contacts) d.emplace_back("GLC_CONTACTS");
    if (c.checkFinite) d.emplace_back("GLC_CHECK_FINITE");
    return d;
}

void finish(const gl::ComputeProgram& program, std::uint32_t nodeCount) {
    program.use();
    program.set("u_nodeCount", nodeCount);
    program.dispatch1D(nodeCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace

std::vector<std::string> externalForceDefines(const NodeForceParams& c) {
    std::vector<std::string> d;
    if (c.gravity) d.emplace_back("GLC_GRAVITY");
    if (c.damping) d.emplace_back("GLC_DAMPING");
    if (c.wind) d.emplace_back("GLC_WIND");
    return d;
}

void bindExternalForce(const gl::ComputeProgram& program, const DeviceBuffers& b,
                       const NodeForceParams& params, const NodeForceParams& compiled, const char* pass) {
    if (compiled.wind) {
        bindRequired(b.faces, GLC_BIND_FACES, pass, "faces");
        bindRequired(b.nodeFaceOffsets, GLC_BIND_NODE_FACE_OFFSETS, pass, "nodeFaceOffsets");
        bindRequired(b.nodeFaceList, GLC_BIND_NODE_FACE_LIST, pass, "nodeFaceList");
        program.set("u_windVelocity", params.windVelocity);
        program.set("u_windDrag", static_cast<float>(params.windDrag));
    }
    program.set("u_gravity", params.gravityAcceleration);
    program.set("u_damping", static_cast<float>(params.dampingCoefficient));
}

NodeForcePass::NodeForcePass(const NodeForceParams& config)
    : m_config(config), m_program("node_force", externalForceDefines(config)) {}

void NodeForcePass::dispatch(const DeviceBuffers& b, const NodeForceParams& params) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    bindRequired(b.forces, GLC_BIND_NODE_FORCES, kName, "forces");
    bindExternalForce(m_program, b, params, m_config, kName);
    finish(m_program, b.nodeCount);
}

SpringUpdatePass::SpringUpdatePass(const SpringUpdateParams& config)
    : m_config(config), m_program("spring_update", externalForceDefines(config.external)) {}

void SpringUpdatePass::dispatch(const DeviceBuffers& b, const SpringUpdateParams& params) const {
    bindExternalForce(m_program, b, params.external, m_config.external, kName);
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    bindRequired(b.springs, GLC_BIND_SPRINGS, kName, "springs");
    bindRequired(b.forces, GLC_BIND_NODE_FORCES, kName, "forces");
    bindRequired(b.nodeSpringList, GLC_BIND_NODE_SPRING_LIST, kName, "nodeSpringList");
    const RowLayout layout = RowLayout::of(b);
    layout.bind(m_program, b, kName);
    layout.dispatch(m_program);
}

namespace {
// NodeUpdate's and NodePredict's buffers and uniforms (one shader, node_update.comp).
void bindNodeUpdate(const gl::ComputeProgram& program, const DeviceBuffers& b, const NodeUpdateParams& config,
                    const NodeUpdateParams& params, std::uint32_t substep, const char* name) {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, name, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, name, "velocities");
    if (config.forces) bindRequired(b.forces, GLC_BIND_NODE_FORCES, name, "forces");
    if (config.contacts) {
        bindRequired(b.contactForces, GLC_BIND_CONTACT_FORCES, name, "contactForces");
        program.set("u_contactForceScale", static_cast<float>(params.contactForceScale));
    }
    if (config.checkFinite) {
        bindRequired(b.health, GLC_BIND_HEALTH, name, "health");
        program.set("u_substep", substep);
    }
    program.set("u_h", static_cast<float>(params.h));
    if (config.ground) {
        program.set("u_groundHeight", static_cast<float>(params.groundHeight));
        program.set("u_restitution", static_cast<float>(params.restitution));
        program.set("u_friction", static_cast<float>(params.friction));
        if (config.groundBand > 0.0) {
            program.set("u_groundBand", static_cast<float>(params.groundBand));
            program.set("u_restingSpeed", static_cast<float>(params.restingSpeed));
            program.set("u_bandResponse", params.bandResponse ? 1u : 0u);
            program.set("u_groundStiffness", static_cast<float>(params.groundStiffness));
            program.set("u_predictedAcceleration", params.predictedAcceleration);
        }
    }
}

std::vector<std::string> nodePredictDefines(const NodeUpdateParams& config) {
    std::vector<std::string> d = nodeUpdateDefines(config);
    d.emplace_back("GLC_PREDICT");
    return d;
}
} // namespace

NodeUpdatePass::NodeUpdatePass(const NodeUpdateParams& config)
    : m_config(config), m_program("node_update", nodeUpdateDefines(config)) {}

void NodeUpdatePass::dispatch(const DeviceBuffers& b, const NodeUpdateParams& params,
                              std::uint32_t substep) const {
    bindNodeUpdate(m_program, b, m_config, params, substep, kName);
    finish(m_program, b.nodeCount);
}

NodePredictPass::NodePredictPass(const NodeUpdateParams& config)
    : m_config(config), m_program("node_update", nodePredictDefines(config)) {}

void NodePredictPass::dispatch(const DeviceBuffers& b, const NodeUpdateParams& params,
                               std::uint32_t substep) const {
    bindNodeUpdate(m_program, b, m_config, params, substep, kName);
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    finish(m_program, b.nodeCount);
}

namespace {
std::vector<std::string> frameStepDefines(const FrameStepParams& c) {
    std::vector<std::string> d = externalForceDefines(c.external);
    if (c.springs) d.emplace_back("GLC_SPRINGS");
    if (c.update.ground) d.emplace_back("GLC_GROUND");
    if (c.update.checkFinite) d.emplace_back("GLC_CHECK_FINITE");
    return d;
}
} // namespace

std::uint32_t frameStepSubstepsPerDispatch(std::uint32_t nodeCount, const model::Csr* nodeSprings,
                                           const model::Csr* nodeFaces) {
    constexpr std::uint64_t kLoopBudget = 32768; // half of llvmpipe's 65,535: how it counts may differ
    const auto rowLength = [](const model::Csr* rows, std::uint32_t i) -> std::uint64_t {
        return rows ? rows->offsets[i + 1] - rows->offsets[i] : 0u;
    };
    std::uint64_t busiest = 0; // loop iterations per substep of the busiest invocation
    for (std::uint32_t lane = 0; lane < GLC_FRAME_STEP_GROUP && lane < nodeCount; ++lane) {
        std::uint64_t iterations = 1 + 2; // the substep loop; the two node loops' last tests
        for (std::uint32_t i = lane; i < nodeCount; i += GLC_FRAME_STEP_GROUP)
            iterations += 2 + (rowLength(nodeSprings, i) + 1) + (rowLength(nodeFaces, i) + 1);
        busiest = std::max(busiest, iterations);
    }
    const std::uint64_t fits = busiest == 0 ? kFrameStepSubstepsPerDispatch : kLoopBudget / busiest;
    return static_cast<std::uint32_t>(std::clamp<std::uint64_t>(fits, 1, kFrameStepSubstepsPerDispatch));
}

FrameStepPass::FrameStepPass(const FrameStepParams& config)
    : m_config(config), m_program("frame_step", frameStepDefines(config)) {}

void FrameStepPass::dispatch(const DeviceBuffers& b, const FrameStepParams& params) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    bindRequired(b.forces, GLC_BIND_NODE_FORCES, kName, "forces");
    if (m_config.springs) {
        bindRequired(b.springs, GLC_BIND_SPRINGS, kName, "springs");
        bindRequired(b.nodeSpringOffsets, GLC_BIND_NODE_SPRING_OFFSETS, kName, "nodeSpringOffsets");
        bindRequired(b.nodeSpringList, GLC_BIND_NODE_SPRING_LIST, kName, "nodeSpringList");
    }
    if (m_config.update.checkFinite) bindRequired(b.health, GLC_BIND_HEALTH, kName, "health");
    bindExternalForce(m_program, b, params.external, m_config.external, kName);
    m_program.use();
    m_program.set("u_nodeCount", b.nodeCount);
    m_program.set("u_h", static_cast<float>(params.update.h));
    if (m_config.update.ground) {
        m_program.set("u_groundHeight", static_cast<float>(params.update.groundHeight));
        m_program.set("u_restitution", static_cast<float>(params.update.restitution));
        m_program.set("u_friction", static_cast<float>(params.update.friction));
    }
    // At most kFrameStepSubstepsPerDispatch substeps per dispatch, so no single dispatch runs long
    // enough to meet a display driver's watchdog, and fewer where llvmpipe's loop limiter would
    // end the invocations early (frameStepSubstepsPerDispatch).
    const std::uint32_t perDispatch = std::max(1u, params.substepsPerDispatch);
    for (std::uint32_t first = 0; first < params.substeps; first += perDispatch) {
        m_program.set("u_firstSubstep", first);
        m_program.set("u_substeps", std::min(perDispatch, params.substeps - first));
        gl::ComputeProgram::dispatch(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

} // namespace glcollide::passes
