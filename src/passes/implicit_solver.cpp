#include "passes/implicit_solver.hpp"

#include "core/gpu_layout.hpp"
#include "passes/dynamics_passes.hpp"

#include <epoxy/gl.h>

#include <cstddef>
#include <cstring>

namespace glcollide::passes {
namespace {

std::vector<std::string> solverDefines(const ImplicitParams& c, bool setup) {
    std::vector<std::string> d = setup ? externalForceDefines(c.external) : std::vector<std::string>{};
    if (c.springs) d.emplace_back("GLC_SPRINGS");
    return d;
}

constexpr std::size_t kVec4 = 4 * sizeof(float);

} // namespace

ImplicitSolverPass::ImplicitSolverPass(const ImplicitParams& config, std::uint32_t nodeCount,
                                       std::uint32_t heavyCount)
    : m_config(config), m_nodeCount(nodeCount), m_layout(nodeCount, heavyCount),
      m_setup("implicit_setup", solverDefines(config, true)),
      m_direction("implicit_cg_direction", solverDefines(config, false)), m_update("implicit_cg_update", {}),
      m_residual("solverResidual", nodeCount * kVec4),
      m_preconditioned("solverPreconditioned", nodeCount * kVec4),
      m_direction0("solverDirection0", nodeCount * kVec4),
      m_direction1("solverDirection1", nodeCount * kVec4), m_product("solverProduct", nodeCount * kVec4),
      m_blockInverse("solverBlockInverse", std::size_t{6} * nodeCount * sizeof(float)),
      m_partialsR("solverPartialsR", std::size_t{m_layout.groups()} * 2 * sizeof(float)),
      m_partialsPq("solverPartialsPq", std::size_t{m_layout.groups()} * sizeof(float)),
      m_state("solverState", sizeof(gpu::GpuSolverState)) {
    resetStatistics();
}

void ImplicitSolverPass::bindLayout(const gl::ComputeProgram& program, const DeviceBuffers& b) const {
    m_partialsR.bindStorage(GLC_BIND_SOLVER_PARTIALS_R);
    m_partialsPq.bindStorage(GLC_BIND_SOLVER_PARTIALS_PQ);
    m_state.bindStorage(GLC_BIND_SOLVER_STATE);
    m_layout.bind(program, b, kName);
}

void ImplicitSolverPass::dispatch(const DeviceBuffers& b, const ImplicitParams& params) const {
    if (m_nodeCount == 0) return;
    const float h = static_cast<float>(params.h);
    const float massFactor = static_cast<float>(1.0 + params.h * params.airDamping);
    const gl::Buffer* directions[2] = {&m_direction0, &m_direction1};

    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    if (m_config.springs) {
        bindRequired(b.springs, GLC_BIND_SPRINGS, kName, "springs");
        bindRequired(b.nodeSpringList, GLC_BIND_NODE_SPRING_LIST, kName, "nodeSpringList");
    }
    m_residual.bindStorage(GLC_BIND_SOLVER_RESIDUAL);
    m_preconditioned.bindStorage(GLC_BIND_SOLVER_PRECONDITIONED);
    m_product.bindStorage(GLC_BIND_SOLVER_PRODUCT);
    m_blockInverse.bindStorage(GLC_BIND_SOLVER_BLOCK_INVERSE);

    bindLayout(m_setup, b);
    bindExternalForce(m_setup, b, params.external, m_config.external, kName);
    directions[0]->bindStorage(GLC_BIND_SOLVER_DIRECTION_OUT);
    m_setup.set("u_h", h);
    m_setup.set("u_massFactor", massFactor);
    m_layout.dispatch(m_setup);

    const auto maxIterations = static_cast<std::uint32_t>(params.maxIterations);
    const float tolerance2 = static_cast<float>(params.tolerance * params.tolerance);
    for (std::uint32_t k = 0; k <= maxIterations; ++k) {
        // Direction k reads p from buffer k % 2 and writes the new p into the other one.
        bindLayout(m_direction, b);
        directions[k % 2]->bindStorage(GLC_BIND_SOLVER_DIRECTION_IN);
        directions[(k + 1) % 2]->bindStorage(GLC_BIND_SOLVER_DIRECTION_OUT);
        m_direction.set("u_h", h);
        m_direction.set("u_massFactor", massFactor);
        m_direction.set("u_iteration", k);
        m_direction.set("u_maxIterations", maxIterations);
        m_direction.set("u_tolerance2", tolerance2);
        m_layout.dispatch(m_direction);
        if (k == maxIterations) break; // that dispatch only checked the residual
        bindLayout(m_update, b);
        m_update.set("u_iteration", k);
        m_layout.dispatch(m_update);
    }
}

void ImplicitSolverPass::resetStatistics() {
    gpu::GpuSolverState state{};
    state.doneAt = GLC_SOLVER_RUNNING;
    m_state.upload(0, sizeof state, &state);
}

ImplicitSolverCounts ImplicitSolverPass::readStatistics() const {
    gpu::GpuSolverState state{};
    m_state.download(0, sizeof state, &state);
    ImplicitSolverCounts c;
    c.maxIterations = state.maxIterations;
    float residual = 0.0f;
    std::memcpy(&residual, &state.maxResidualBits, sizeof residual);
    c.maxRelativeResidual = residual;
    c.totalIterations = state.totalIterations;
    c.unconvergedSubsteps = state.unconvergedSubsteps;
    return c;
}

std::vector<std::string> ImplicitSolverPass::allocatedLabels() const {
    std::vector<std::string> labels;
    for (const gl::Buffer* buffer : {&m_residual, &m_preconditioned, &m_direction0, &m_direction1, &m_product,
                                     &m_blockInverse, &m_partialsR, &m_partialsPq, &m_state})
        labels.push_back(buffer->label());
    return labels;
}

std::size_t ImplicitSolverPass::allocatedBytes() const {
    std::size_t bytes = 0;
    for (const gl::Buffer* buffer : {&m_residual, &m_preconditioned, &m_direction0, &m_direction1, &m_product,
                                     &m_blockInverse, &m_partialsR, &m_partialsPq, &m_state})
        bytes += buffer->bytes();
    return bytes;
}

std::uint32_t ImplicitSolverPass::dispatchesPerSubstep() const {
    return 2u + 2u * static_cast<std::uint32_t>(m_config.maxIterations);
}

} // namespace glcollide::passes
