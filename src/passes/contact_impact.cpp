#include "passes/contact_impact.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <string>

namespace glcollide::passes {

namespace {
constexpr std::size_t kImpulseHeaderWords = 2; // contact_impact.comp's kImpulseHeader
} // namespace

ContactImpactPass::ContactImpactPass(std::uint32_t nodeCount, const ContactImpactParams& params,
                                     const ContactParams& contact)
    : m_nodeCount(nodeCount), m_params(params), m_contact(contact), m_program("contact_impact") {
    if (!(params.restitution > 0.0 && params.restitution <= 1.0))
        throw Error("ContactImpact: restitution must be in (0, 1], got " +
                    std::to_string(params.restitution));
    if (!(params.restingSpeed >= 0.0) || params.iterations < 1)
        throw Error("ContactImpact: the resting speed must be >= 0 and the iterations >= 1");
    if (!(contact.substep > 0.0) || !(contact.thickness > 0.0))
        throw Error("ContactImpact: the substep and the thickness must be > 0");
    const gl::ComputeProgram& p = m_program;
    p.set("u_nodeCount", nodeCount);
    // The band searched: twice the thickness (a landing pair left on the band's edge); beyond the
    // thickness only pairs that still approach take part (contact_impact.comp).
    p.set("u_thickness", static_cast<float>(2.0 * contact.thickness));
    p.set("u_band", static_cast<float>(contact.thickness));
    p.set("u_restitution", static_cast<float>(params.restitution));
    p.set("u_restingSpeed", static_cast<float>(params.restingSpeed));
    p.set("u_gravity", params.gravity);
    p.set("u_substep", static_cast<float>(contact.substep));
    p.set("u_forceCap", static_cast<float>(contact.forceCap));
}

void ContactImpactPass::dispatch(const DeviceBuffers& b, const ContactInputs& in,
                                 const gl::Buffer& start) const {
    if (m_nodeCount == 0) return;
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    bindRequired(b.faces, GLC_BIND_FACES, kName, "faces");
    bindRequired(b.contactForces, GLC_BIND_CONTACT_FORCES, kName, "contactForces");
    bindRequired(start, GLC_BIND_START_VELOCITIES, kName, "startVelocities");
    bindContactInputs(in, kName);
    // Two words per list slot (the edge-edge slots after the vertex-face capacity) after a header.
    const std::uint32_t edgeEdgeBase = in.lists->capacity(GLC_LIST_VERTEX_FACE);
    const std::size_t words =
        kImpulseHeaderWords + 2 * (std::size_t{edgeEdgeBase} + in.lists->capacity(GLC_LIST_EDGE_EDGE));
    if (m_impulses.bytes() < words * sizeof(std::uint32_t))
        m_impulses =
            gl::Buffer("contactImpactImpulses", std::max<std::size_t>(words, 1024) * sizeof(std::uint32_t));
    const std::uint32_t noLargest = 0; // word 0: the largest change, found again by mode 0
    m_impulses.upload(0, sizeof noLargest, &noLargest);
    m_impulses.bindStorage(GLC_BIND_IMPACT_IMPULSES);
    const gl::ComputeProgram& p = m_program;
    bindTangled(p, in, b.nodeCount);
    p.set("u_edgeEdgeBase", edgeEdgeBase);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const auto overLists = [&](std::uint32_t mode) {
        p.set("u_mode", mode);
        for (const std::uint32_t list : {GLC_LIST_VERTEX_FACE, GLC_LIST_EDGE_EDGE}) {
            p.set("u_list", list);
            // The lists do not change within the pass: their dispatch sizes are computed once.
            if (mode == 0u)
                in.lists->dispatchOver(p, list, GLC_WORKGROUP_SIZE);
            else
                in.lists->dispatchAgainOver(p, list);
        }
    };
    overLists(0u); // the impact pairs on each node, complete before any impulse reads them
    p.set("u_mode", 4u);
    p.use();
    gl::ComputeProgram::dispatch(1, 1, 1); // the fixed-point scale
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const auto apply = [&](bool last) {
        p.set("u_mode", 2u);
        p.set("u_clearCounts", last ? 1u : 0u);
        p.use();
        p.dispatch1D(m_nodeCount, GLC_WORKGROUP_SIZE);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    };
    const bool friction = m_contact.friction > 0.0;
    for (int round = 0; round < m_params.iterations; ++round) {
        overLists(1u);
        apply(!friction && round + 1 == m_params.iterations);
    }
    if (friction) { // once, from the final impulses
        p.set("u_friction", static_cast<float>(m_contact.friction));
        overLists(3u);
        apply(true);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

} // namespace glcollide::passes
