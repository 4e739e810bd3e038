#include "passes/newton_line_search.hpp"

#include "core/gpu_layout.hpp"
#include "passes/energy_guard.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

namespace glcollide::passes {
namespace {
constexpr std::size_t kVec4 = 4 * sizeof(float);
}

NewtonLineSearchPass::NewtonLineSearchPass(const LineSearchParams& params, std::uint32_t nodeCount,
                                           std::uint32_t springCount)
    : m_params(params), m_nodeCount(nodeCount), m_springCount(params.potentials.springs ? springCount : 0u),
      m_state(gl::makeBuffer("lineSearch", std::vector<gpu::GpuLineSearch>(1, gpu::GpuLineSearch{}))),
      m_velocities("lineSearchVelocities", std::size_t{3} * nodeCount * kVec4),
      m_program("newton_line_search") {
    setPotentialUniforms(m_program, params.potentials, m_springCount);
    m_program.set("u_airDamping", static_cast<float>(params.airDamping));
    m_program.set("u_nodeCount", nodeCount);
}

void NewtonLineSearchPass::bindState(const DeviceBuffers& b, const ContactInputs* contacts) const {
    if (b.nodeCount != m_nodeCount) throw Error(std::string(kName) + ": built for another node count");
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    m_terms = bindPotentialInputs(b, contacts, m_params.potentials, m_springCount, kName);
    m_state.bindStorage(GLC_BIND_LINE_SEARCH);
    m_velocities.bindStorage(GLC_BIND_LINE_SEARCH_VELOCITIES);
    m_program.use();
}

void NewtonLineSearchPass::copyVelocities(const DeviceBuffers& b, const gl::Buffer& startVelocities,
                                          const gl::Buffer& stepStart) const {
    const std::size_t bytes = std::size_t{m_nodeCount} * kVec4;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::copyBufferData(startVelocities, m_velocities, bytes, 0);
    gl::copyBufferData(stepStart, m_velocities, bytes, bytes);
    gl::copyBufferData(b.velocities, m_velocities, bytes, 2 * bytes);
    // The candidates' largest |δ| is a maximum over this step's candidates only.
    const std::uint32_t zero = 0;
    m_state.upload(offsetof(gpu::GpuLineSearch, largestChange), sizeof zero, &zero);
}

void NewtonLineSearchPass::writeCandidate(const DeviceBuffers& b, float alpha, double h) const {
    m_program.set("u_mode", 2u);
    m_program.set("u_alpha", alpha);
    m_program.set("u_h", static_cast<float>(h));
    m_program.dispatch1D(b.nodeCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

PotentialSum NewtonLineSearchPass::sum(double h) const {
    m_program.set("u_h", static_cast<float>(h));
    m_program.set("u_mode", 0u);
    gl::ComputeProgram::dispatch(GLC_ENERGY_GROUPS, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_program.set("u_mode", 1u);
    gl::ComputeProgram::dispatch(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    struct {
        float total, magnitude;
        std::uint32_t largestChange;
    } read{};
    static_assert(offsetof(gpu::GpuLineSearch, largestChange) == 8);
    m_state.download(0, 12, &read);
    std::memcpy(&m_largestChange, &read.largestChange, sizeof m_largestChange);
    return PotentialSum{read.total, read.magnitude};
}

PotentialSum NewtonLineSearchPass::evaluate(const DeviceBuffers& b, const ContactInputs* contacts,
                                            float alpha, double h) const {
    bindState(b, contacts);
    writeCandidate(b, alpha, h);
    return sum(h);
}

LineSearchStep NewtonLineSearchPass::dispatch(const DeviceBuffers& b, const ContactInputs* contacts,
                                              const gl::Buffer& startVelocities, const gl::Buffer& stepStart,
                                              double h) const {
    if (m_nodeCount == 0) return {};
    copyVelocities(b, startVelocities, stepStart);
    ++m_counts.steps;
    const PotentialSum start = evaluate(b, contacts, 0.0f, h);
    const double resolution = this->resolution(); // of the terms evaluate() bound
    for (const float alpha : kFractions) {
        const PotentialSum candidate = evaluate(b, contacts, alpha, h);
        if (candidate.total <= start.total + resolution * (start.magnitude + candidate.magnitude)) {
            if (alpha < 1.0f) ++m_counts.shortened;
            return {alpha, static_cast<double>(alpha) * h * static_cast<double>(m_largestChange)};
        }
    }
    // No fraction lowers Φ: the Newton step's start stays.
    ++m_counts.shortened;
    ++m_counts.rejected;
    writeCandidate(b, 0.0f, h);
    return {0.0f, 0.0};
}

} // namespace glcollide::passes
