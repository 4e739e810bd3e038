#include "passes/contact_response.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

namespace glcollide::passes {

void bindTangled(const gl::ComputeProgram& program, const ContactInputs& inputs, std::uint32_t nodeCount) {
    if (inputs.tangled && *inputs.tangled) {
        inputs.tangled->bindStorage(GLC_BIND_TANGLED);
        program.set("u_tangledFaces", nodeCount);
    } else {
        program.set("u_tangledFaces", 0xFFFFFFFFu); // no marks: the block is never read
    }
}

void bindContactInputs(const ContactInputs& in, const char* pass) {
    if (!in.lists || !in.faceInfo || !in.objects)
        throw Error(std::string(pass) + ": collision buffers missing");
    if (!in.lists->declared(GLC_LIST_VERTEX_FACE) || !in.lists->declared(GLC_LIST_EDGE_EDGE))
        throw Error(std::string(pass) + ": the vertex-face and edge-edge lists are not declared");
    bindRequired(*in.faceInfo, GLC_BIND_FACE_INFO, pass, "faceInfo");
    bindRequired(*in.objects, GLC_BIND_OBJECTS, pass, "objects");
    in.lists->bind(); // the counters, the dispatch arguments and every list
}

namespace {
std::vector<std::string> contactDefines(const ContactParams& config) {
    if (config.predictedForces) return {"GLC_PREDICTED_FORCES"};
    return {};
}
} // namespace

ContactResponsePass::ContactResponsePass(const ContactParams& config)
    : m_config(config), m_vertexFace("contact_vertex_face", contactDefines(config)),
      m_edgeEdge("contact_edge_edge", contactDefines(config)) {}

void ContactResponsePass::dispatch(const DeviceBuffers& b, const ContactInputs& in,
                                   const ContactParams& params) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    bindRequired(b.faces, GLC_BIND_FACES, kName, "faces");
    bindRequired(b.contactForces, GLC_BIND_CONTACT_FORCES, kName, "contactForces");
    if (m_config.predictedForces) bindRequired(b.forces, GLC_BIND_NODE_FORCES, kName, "forces");
    bindContactInputs(in, kName);
    for (const gl::ComputeProgram* p : {&m_vertexFace, &m_edgeEdge}) {
        p->set("u_thickness", static_cast<float>(params.thickness));
        p->set("u_stiffness", static_cast<float>(params.stiffness));
        p->set("u_damping", static_cast<float>(params.damping));
        p->set("u_forceCap", static_cast<float>(params.forceCap));
        p->set("u_forceScale", static_cast<float>(params.forceScale));
        p->set("u_substep", static_cast<float>(params.substep));
        p->set("u_velocityResponse", params.velocityResponse ? 1u : 0u);
        p->set("u_relaxationTime", static_cast<float>(params.relaxationTime));
        p->set("u_repulsion", params.repulsion ? 1u : 0u);
        p->set("u_previousSides", params.sidesFromPrevious ? 1u : 0u);
        if (p == &m_edgeEdge) bindTangled(*p, in, b.nodeCount);
        p->set("u_friction", static_cast<float>(params.friction));
        p->set("u_leavingStep", static_cast<float>(params.leavingStep));
        p->set("u_leavingSpeed", static_cast<float>(params.leavingSpeed));
    }
    // Sized on the GPU from each list's count; each dispatch ends with a storage barrier. First
    // both kernels count the acting contacts per node (Bridson's; with the penalty and friction,
    // the pushing ones), every count complete before any force reads it, then both add their
    // forces (decision 0019).
    for (const std::uint32_t countPass : {1u, 0u}) {
        m_vertexFace.set("u_countPass", countPass);
        m_edgeEdge.set("u_countPass", countPass);
        in.lists->dispatchOver(m_vertexFace, GLC_LIST_VERTEX_FACE, GLC_WORKGROUP_SIZE);
        in.lists->dispatchOver(m_edgeEdge, GLC_LIST_EDGE_EDGE, GLC_WORKGROUP_SIZE);
    }
}

} // namespace glcollide::passes
