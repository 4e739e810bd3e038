#include "passes/energy_guard.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace glcollide::passes {

namespace {
constexpr std::uint32_t kStride = GLC_ENERGY_GROUPS * GLC_WORKGROUP_SIZE; // invocations of the terms dispatch

std::uint64_t serialTerms(std::uint64_t items) {
    return (items + kStride - 1) / kStride;
}
} // namespace

double EnergyGuardPass::resolutionFactor(std::uint64_t terms) {
    // The chain: one invocation's serial sums over every domain (at most four of them, each
    // ⌈n/stride⌉ long), the group's tree, the decide group's serial part and its tree.
    const std::uint64_t log2Group = 7; // GLC_WORKGROUP_SIZE = 128
    static_assert(GLC_WORKGROUP_SIZE == 128);
    const std::uint64_t depth = serialTerms(terms) + 4 + log2Group +
                                (GLC_ENERGY_GROUPS + GLC_WORKGROUP_SIZE - 1) / GLC_WORKGROUP_SIZE + log2Group;
    return static_cast<double>(depth + 8) * std::ldexp(1.0, -24);
}

void setPotentialUniforms(const gl::ComputeProgram& program, const EnergyGuardParams& params,
                          std::uint32_t springCount) {
    program.set("u_springCount", springCount);
    program.set("u_contacts", params.contacts ? 1u : 0u);
    program.set("u_gravity", params.gravity);
    program.set("u_thickness", static_cast<float>(params.thickness));
    program.set("u_stiffness", static_cast<float>(params.stiffness));
    program.set("u_groundStiffness", static_cast<float>(params.groundStiffness));
    program.set("u_groundLevel", static_cast<float>(params.groundLevel));
}

std::uint64_t bindPotentialInputs(const DeviceBuffers& b, const ContactInputs* contacts,
                                  const EnergyGuardParams& params, std::uint32_t springCount,
                                  const char* pass) {
    if (springCount > 0) bindRequired(b.springs, GLC_BIND_SPRINGS, pass, "springs");
    std::uint64_t terms = std::uint64_t{b.nodeCount} + springCount;
    if (!params.contacts) return terms;
    if (!contacts) throw Error(std::string(pass) + ": collision buffers missing");
    bindRequired(b.faces, GLC_BIND_FACES, pass, "faces");
    bindContactInputs(*contacts, pass);
    return terms + contacts->lists->capacity(GLC_LIST_VERTEX_FACE) +
           contacts->lists->capacity(GLC_LIST_EDGE_EDGE);
}

EnergyGuardPass::EnergyGuardPass(const EnergyGuardParams& params, std::uint32_t springCount)
    : m_params(params), m_springCount(params.springs ? springCount : 0u),
      m_state(gl::makeBuffer("energyGuard", std::vector<gpu::GpuEnergyGuard>(1, gpu::GpuEnergyGuard{}))),
      m_program("energy_guard") {
    setPotentialUniforms(m_program, params, m_springCount);
}

void EnergyGuardPass::sumAndDecide(const DeviceBuffers& b, const ContactInputs* contacts, Decision d) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    // The candidate: SafeStep's cut x1, or at a frame's start the positions themselves.
    bindRequired(d.record ? b.positions : b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName,
                 "predictedPositions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    const std::uint64_t terms = bindPotentialInputs(b, contacts, m_params, m_springCount, kName);
    m_state.bindStorage(GLC_BIND_ENERGY_GUARD);
    m_program.use();
    m_program.set("u_nodeCount", b.nodeCount);
    m_program.set("u_resolution", static_cast<float>(resolutionFactor(terms)));
    m_program.set("u_record", d.record ? 1u : 0u);
    m_program.set("u_round", d.round);
    m_program.set("u_last", d.last ? 1u : 0u);
    m_program.set("u_mode", 0u);
    gl::ComputeProgram::dispatch(GLC_ENERGY_GROUPS, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_program.set("u_mode", 1u);
    gl::ComputeProgram::dispatch(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void EnergyGuardPass::pullBack(const DeviceBuffers& b, float alpha) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    m_state.bindStorage(GLC_BIND_ENERGY_GUARD);
    m_program.use();
    m_program.set("u_mode", 2u);
    m_program.set("u_alpha", alpha);
    m_program.dispatch1D(b.nodeCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

bool EnergyGuardPass::pullBackNeeded() const {
    std::uint32_t outcome = 0;
    m_state.download(offsetof(gpu::GpuEnergyGuard, outcome), sizeof outcome, &outcome);
    return outcome != 0;
}

void EnergyGuardPass::record(const DeviceBuffers& b, const ContactInputs* contacts) const {
    sumAndDecide(b, contacts, Decision{true, 0, false});
}

void EnergyGuardPass::dispatch(const DeviceBuffers& b, const ContactInputs* contacts,
                               CollisionDetection& collision) const {
    sumAndDecide(b, contacts, Decision{false, 0, false});
    // The rise is potential energy the kinetic cannot pay: halve the step and decide again; the
    // last round returns to x0 at rest, where the energy is at most the start's. The CCD checks
    // every pulled-back step as it is stored (the arithmetic rounds); a step it doubts is
    // halved again.
    std::uint32_t round = 0;
    while (pullBackNeeded()) {
        if (round == 0) ++m_pulledBack;
        bool last = false;
        do {
            ++round;
            last = round > static_cast<std::uint32_t>(kHalvingRounds);
            pullBack(b, last ? 0.0f : 0.5f);
        } while (!last && collision.recheckCcd(b) > 0);
        if (last) ++m_backToStart;
        sumAndDecide(b, contacts, Decision{false, round, last});
        if (last) break;
    }
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    m_state.bindStorage(GLC_BIND_ENERGY_GUARD);
    m_program.use();
    m_program.set("u_mode", 3u);
    m_program.dispatch1D(b.nodeCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

EnergyGuardCounts EnergyGuardPass::frameCounts() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gpu::GpuEnergyGuard s{};
    m_state.download(0, offsetof(gpu::GpuEnergyGuard, partials), &s);
    return EnergyGuardCounts{s.acted,         m_pulledBack, m_backToStart, s.removed,    s.unremoved,
                             s.largestExcess, s.lastTotal,  s.lastKinetic, s.lastContact};
}

void EnergyGuardPass::clearFrameCounts() const {
    // acted, removed, unremoved, largestExcess (0.0f is all-zero bits)
    const std::uint32_t zeros[4] = {0, 0, 0, 0};
    m_state.upload(offsetof(gpu::GpuEnergyGuard, acted), sizeof zeros, zeros);
    m_pulledBack = 0;
    m_backToStart = 0;
}

} // namespace glcollide::passes
