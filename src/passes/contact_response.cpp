#include "passes/contact_response.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

namespace glcollide::passes {

ContactResponsePass::ContactResponsePass() : m_program("contact_response") {}

void ContactResponsePass::dispatch(const DeviceBuffers& b, const ContactInputs& in,
                                   const ContactParams& params) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    bindRequired(b.faces, GLC_BIND_FACES, kName, "faces");
    bindRequired(b.contactForces, GLC_BIND_CONTACT_FORCES, kName, "contactForces");
    if (!in.candidates || !in.faceInfo || !in.objects || !in.counters)
        throw Error(std::string(kName) + ": collision buffers missing");
    bindRequired(*in.candidates, GLC_BIND_FACE_PAIRS, kName, "candidates");
    bindRequired(*in.faceInfo, GLC_BIND_FACE_INFO, kName, "faceInfo");
    bindRequired(*in.objects, GLC_BIND_OBJECTS, kName, "objects");
    bindRequired(*in.counters, GLC_BIND_COLLISION_COUNTERS, kName, "counters");
    if (in.candidateCount == 0) return;
    m_program.use();
    m_program.set("u_candidateCount", in.candidateCount);
    m_program.set("u_thickness", static_cast<float>(params.thickness));
    m_program.set("u_stiffness", static_cast<float>(params.stiffness));
    m_program.set("u_damping", static_cast<float>(params.damping));
    m_program.set("u_forceCap", static_cast<float>(params.forceCap));
    m_program.set("u_forceScale", static_cast<float>(params.forceScale));
    m_program.dispatch1D(in.candidateCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace glcollide::passes
