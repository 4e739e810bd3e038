#include "passes/implicit_solver.hpp"

#include "core/gpu_layout.hpp"
#include "passes/dynamics_passes.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <cstddef>
#include <cstring>

namespace glcollide::passes {
namespace {

std::vector<std::string> solverDefines(const ImplicitParams& c, bool setup, bool contacts = false) {
    std::vector<std::string> d = setup ? externalForceDefines(c.external) : std::vector<std::string>{};
    if (c.springs) d.emplace_back("GLC_SPRINGS");
    if (contacts) d.emplace_back("GLC_IMPLICIT_CONTACTS");
    if (c.groundStiffness > 0.0) d.emplace_back("GLC_IMPLICIT_GROUND");
    return d;
}

/// A program only when the pass is built with contacts (an empty one otherwise: nothing compiled).
gl::ComputeProgram contactProgram(bool contacts, const char* shader,
                                  const std::vector<std::string>& defines = {}) {
    return contacts ? gl::ComputeProgram(shader, defines) : gl::ComputeProgram();
}

/// Incidence entries are 4·slot + corner in a uint.
constexpr std::uint64_t kMaxContactRecords = std::uint64_t{1} << 27;
constexpr std::size_t kRecordWords = sizeof(gpu::GpuImplicitContact) / sizeof(std::uint32_t);

constexpr std::size_t kVec4 = 4 * sizeof(float);
// Every this many CG iterations the host reads whether the solve has converged and stops
// dispatching if so (a 4-byte read-back, which waits for the GPU). Without it every solve ran
// all maxIterations (two dispatches each, the later ones returning at once), so a cap high
// enough for the hard substeps cost every substep that much. 16: at most 32 idle dispatches
// per solve, at most maxIterations / 16 waits.
constexpr std::uint32_t kConvergenceCheckInterval = 16;

} // namespace

ImplicitSolverPass::ImplicitSolverPass(const ImplicitParams& config, std::uint32_t nodeCount,
                                       std::uint32_t heavyCount, bool contacts)
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
      m_state("solverState", sizeof(gpu::GpuSolverState)), m_contacts(contacts),
      m_setupContacts(contactProgram(contacts, "implicit_setup", solverDefines(config, true, true))),
      m_directionContacts(
          contactProgram(contacts, "implicit_cg_direction", solverDefines(config, false, true))),
      m_newton(contacts && config.newtonSteps > 1),
      m_setupNewton(contactProgram(contacts && config.newtonSteps > 1, "implicit_newton_setup",
                                   solverDefines(config, true))),
      m_startVelocities("solverStartVelocities", contacts && config.newtonSteps > 1 ? nodeCount * kVec4 : 0),
      m_newtonStart("solverNewtonStart", contacts && config.newtonSteps > 1 ? nodeCount * kVec4 : 0),
      m_contactFind(contactProgram(contacts, "implicit_contact_find")),
      m_contactScan(contactProgram(contacts, "implicit_contact_scan")),
      m_contactScatter(contactProgram(contacts, "implicit_contact_scatter")),
      m_contactSort(contactProgram(contacts, "implicit_contact_sort")),
      m_nodeContactCounts("solverNodeContactCounts", contacts ? nodeCount * sizeof(std::uint32_t) : 0) {
    resetStatistics();
}

void ImplicitSolverPass::reserveContacts(std::uint64_t records) const {
    // Words are indexed by 32-bit uniforms: 17 words per record and the rows must stay below 2^32.
    if (records > kMaxContactRecords)
        throw Error(std::string(kName) + ": " + std::to_string(records) + " contacts, more than the " +
                    std::to_string(kMaxContactRecords) + " the contact term can index");
    if (records <= m_recordCapacity && m_contactData) return;
    m_recordCapacity = static_cast<std::uint32_t>(std::min<std::uint64_t>(
        std::max<std::uint64_t>(records, 2ull * m_recordCapacity), kMaxContactRecords));
    m_contactData = gl::Buffer("solverContactData",
                               (contactRecordsWord() + std::size_t{m_recordCapacity} * kRecordWords) *
                                   sizeof(std::uint32_t));
}

void ImplicitSolverPass::setContactWords(const gl::ComputeProgram& program) const {
    program.set("u_contactCount", contactCountWord());
    program.set("u_contactEntries", contactEntriesWord());
    program.set("u_contactSlots", static_cast<std::uint32_t>(contactSlotsWord()));
    program.set("u_contactRecords", static_cast<std::uint32_t>(contactRecordsWord()));
}

namespace {
/// `count` items of type T from word `word` of the contact data.
template <typename T>
std::vector<T> downloadItems(const gl::Buffer& data, std::size_t word, std::size_t count) {
    std::vector<T> items(count);
    if (!items.empty()) data.download(word * sizeof(std::uint32_t), items.size() * sizeof(T), items.data());
    return items;
}
} // namespace

std::vector<gpu::GpuImplicitContact> ImplicitSolverPass::downloadContactRecords() const {
    return downloadItems<gpu::GpuImplicitContact>(m_contactData, contactRecordsWord(), m_records);
}

std::vector<std::uint32_t> ImplicitSolverPass::downloadContactRecordSlots() const {
    return downloadItems<std::uint32_t>(m_contactData, contactSlotsWord(), m_records);
}

std::vector<std::uint32_t> ImplicitSolverPass::downloadNodeContactOffsets() const {
    return downloadItems<std::uint32_t>(m_contactData, 0, std::size_t{m_nodeCount} + 1);
}

std::vector<std::uint32_t> ImplicitSolverPass::downloadNodeContactList() const {
    return downloadItems<std::uint32_t>(m_contactData, contactEntriesWord(),
                                        downloadNodeContactOffsets().back());
}

void ImplicitSolverPass::buildContactRows(const DeviceBuffers& b, const ImplicitContacts& contacts) const {
    const ContactInputs& in = contacts.inputs;
    if (!in.lists || !in.faceInfo || !in.objects)
        throw Error(std::string(kName) + ": collision buffers missing for the contact term");
    if (!in.lists->declared(GLC_LIST_VERTEX_FACE) || !in.lists->declared(GLC_LIST_EDGE_EDGE))
        throw Error(std::string(kName) + ": the vertex-face and edge-edge lists are not declared");
    // The vertex-face list's capacity is where the edge-edge list's slots begin in the records' keys.
    m_contactEdgeEdgeBase = in.lists->capacity(GLC_LIST_VERTEX_FACE);
    if (std::uint64_t{m_contactEdgeEdgeBase} + in.lists->capacity(GLC_LIST_EDGE_EDGE) > 0xFFFFFFFFull)
        throw Error(std::string(kName) + ": the feature-pair lists hold more slots than 32 bits index");
    reserveContacts(std::max<std::uint64_t>(m_nodeCount, 1024));
    bindRequired(b.faces, GLC_BIND_FACES, kName, "faces");
    bindRequired(*in.faceInfo, GLC_BIND_FACE_INFO, kName, "faceInfo");
    bindRequired(*in.objects, GLC_BIND_OBJECTS, kName, "objects");
    in.lists->bind(); // the counters, the dispatch arguments and both lists
    m_nodeContactCounts.bindStorage(GLC_BIND_NODE_CONTACT_COUNTS);

    // The band searched: the thickness plus the margin, which the shader takes off the depth again.
    m_contactFind.set("u_thickness",
                      static_cast<float>(contacts.params.thickness + contacts.params.solveMargin));
    m_contactFind.set("u_margin", static_cast<float>(contacts.params.solveMargin));
    m_contactFind.set("u_substep", static_cast<float>(contacts.params.substep));
    m_contactFind.set("u_leavingStep", static_cast<float>(contacts.params.leavingStep));
    m_contactFind.set("u_leavingSpeed", static_cast<float>(contacts.params.leavingSpeed));
    m_contactFind.set("u_contactStiffness", static_cast<float>(contacts.params.stiffness));
    bindTangled(m_contactFind, contacts.inputs, b.nodeCount);
    for (const gl::ComputeProgram* p : {&m_contactFind, &m_contactSort})
        p->set("u_edgeEdgeBase", m_contactEdgeEdgeBase);
    // Every count is complete (both finds) before the scan, every entry written (the scatter)
    // before the sort. A find that counted more contacts than the records hold runs again on
    // grown records (one read-back of the count per substep).
    std::uint32_t found = findContacts(*in.lists);
    if (found > m_recordCapacity) {
        reserveContacts(found);
        found = findContacts(*in.lists);
    }
    m_records = found;
    for (const gl::ComputeProgram* p : {&m_contactScan, &m_contactScatter, &m_contactSort})
        setContactWords(*p);
    m_contactScan.use();
    m_contactScan.set("u_nodeCount", m_nodeCount);
    gl::ComputeProgram::dispatch(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_contactScatter.use();
    m_contactScatter.set("u_records", m_records);
    m_contactScatter.dispatch1D(m_records, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_contactSort.use();
    m_contactSort.set("u_nodeCount", m_nodeCount);
    m_contactSort.dispatch1D(m_nodeCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

std::uint32_t ImplicitSolverPass::findContacts(const AppendLists& lists) const {
    m_contactData.bindStorage(GLC_BIND_IMPLICIT_CONTACTS);
    m_nodeContactCounts.fill32(0u);
    const std::uint32_t zero = 0;
    m_contactData.upload(std::size_t{contactCountWord()} * sizeof(std::uint32_t), sizeof zero, &zero);
    setContactWords(m_contactFind);
    m_contactFind.set("u_recordCapacity", m_recordCapacity);
    for (const std::uint32_t list : {GLC_LIST_VERTEX_FACE, GLC_LIST_EDGE_EDGE}) {
        m_contactFind.set("u_edgeEdge", list == GLC_LIST_EDGE_EDGE ? 1u : 0u);
        lists.dispatchOver(m_contactFind, list, GLC_WORKGROUP_SIZE);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t found = 0;
    m_contactData.download(std::size_t{contactCountWord()} * sizeof(std::uint32_t), sizeof found, &found);
    return found;
}

void ImplicitSolverPass::bindLayout(const gl::ComputeProgram& program, const DeviceBuffers& b) const {
    m_partialsR.bindStorage(GLC_BIND_SOLVER_PARTIALS_R);
    m_partialsPq.bindStorage(GLC_BIND_SOLVER_PARTIALS_PQ);
    m_state.bindStorage(GLC_BIND_SOLVER_STATE);
    m_layout.bind(program, b, kName);
}

void ImplicitSolverPass::dispatch(const DeviceBuffers& b, const ImplicitParams& params,
                                  const ImplicitContacts* contacts) const {
    if (contacts && !m_contacts)
        throw Error(std::string(kName) + ": dispatched with contacts, but built without the contact term");
    if (m_nodeCount == 0) return;
    // v0 for the Newton step's right-hand side (after the shader writes of the velocities).
    if (m_newton) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        gl::copyBufferData(b.velocities, m_startVelocities, m_startVelocities.bytes());
    }
    solve(b, params, contacts, b.positions, contacts ? m_setupContacts : m_setup);
}

void ImplicitSolverPass::dispatchNewton(const DeviceBuffers& b, const ImplicitParams& params,
                                        const ImplicitContacts& contacts) const {
    if (!m_newton) throw Error(std::string(kName) + ": a Newton step, but the pass was built without it");
    if (m_nodeCount == 0) return;
    // ImplicitNewtonSetup reads v0 from the residual buffer (then writes r over it), after the
    // last solve's writes of r.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl::copyBufferData(m_startVelocities, m_residual, m_startVelocities.bytes());
    gl::copyBufferData(b.velocities, m_newtonStart, m_newtonStart.bytes()); // v1, for the line search
    solve(b, params, &contacts, b.predictedPositions, m_setupNewton);
}

void ImplicitSolverPass::solve(const DeviceBuffers& b, const ImplicitParams& params,
                               const ImplicitContacts* contacts, const gl::Buffer& positions,
                               const gl::ComputeProgram& setup) const {
    const gl::ComputeProgram& direction = contacts ? m_directionContacts : m_direction;
    const float h = static_cast<float>(params.h);
    const float massFactor = static_cast<float>(1.0 + params.h * params.airDamping);
    const gl::Buffer* directions[2] = {&m_direction0, &m_direction1};

    bindRequired(positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.velocities, GLC_BIND_NODE_VELOCITIES, kName, "velocities");
    if (contacts) {
        buildContactRows(b, *contacts); // reads the positions and velocities bound above
        for (const gl::ComputeProgram* p : {&setup, &direction}) {
            p->set("u_contactStiffness", static_cast<float>(contacts->params.stiffness));
            setContactWords(*p); // after buildContactRows: it sizes the data
        }
    }
    if (m_config.springs) {
        bindRequired(b.springs, GLC_BIND_SPRINGS, kName, "springs");
        bindRequired(b.nodeSpringList, GLC_BIND_NODE_SPRING_LIST, kName, "nodeSpringList");
    }
    m_residual.bindStorage(GLC_BIND_SOLVER_RESIDUAL);
    m_preconditioned.bindStorage(GLC_BIND_SOLVER_PRECONDITIONED);
    m_product.bindStorage(GLC_BIND_SOLVER_PRODUCT);
    m_blockInverse.bindStorage(GLC_BIND_SOLVER_BLOCK_INVERSE);

    bindLayout(setup, b);
    bindExternalForce(setup, b, params.external, m_config.external, kName);
    directions[0]->bindStorage(GLC_BIND_SOLVER_DIRECTION_OUT);
    setup.set("u_h", h);
    setup.set("u_massFactor", massFactor);
    if (m_config.groundStiffness > 0.0)
        for (const gl::ComputeProgram* p : {&setup, &direction}) {
            p->set("u_groundStiffness", static_cast<float>(params.groundStiffness));
            p->set("u_groundLevel", static_cast<float>(params.groundHeight + params.groundBand));
        }
    m_layout.dispatch(setup);

    const auto maxIterations = static_cast<std::uint32_t>(params.maxIterations);
    const float inverseTolerance2 = static_cast<float>(1.0 / (params.tolerance * params.tolerance));
    for (std::uint32_t k = 0; k <= maxIterations; ++k) {
        // Direction k reads p from buffer k % 2 and writes the new p into the other one.
        bindLayout(direction, b);
        directions[k % 2]->bindStorage(GLC_BIND_SOLVER_DIRECTION_IN);
        directions[(k + 1) % 2]->bindStorage(GLC_BIND_SOLVER_DIRECTION_OUT);
        direction.set("u_h", h);
        direction.set("u_massFactor", massFactor);
        direction.set("u_iteration", k);
        direction.set("u_maxIterations", maxIterations);
        direction.set("u_inverseTolerance2", inverseTolerance2);
        m_layout.dispatch(direction);
        if (k == maxIterations) break; // that dispatch only checked the residual
        if (k % kConvergenceCheckInterval == kConvergenceCheckInterval - 1 && converged()) break;
        bindLayout(m_update, b);
        m_update.set("u_iteration", k);
        m_layout.dispatch(m_update);
    }
}

bool ImplicitSolverPass::converged() const {
    // The direction pass that found ‖r‖ small enough (or the cap) set doneAt: every later
    // dispatch of this solve would return at once, so stopping here changes no bit.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t doneAt = GLC_SOLVER_RUNNING;
    m_state.download(offsetof(gpu::GpuSolverState, doneAt), sizeof doneAt, &doneAt);
    return doneAt != GLC_SOLVER_RUNNING;
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
    if (m_contacts)
        for (const gl::Buffer* buffer : std::initializer_list<const gl::Buffer*>{
                 &m_nodeContactCounts, &m_contactData, &m_startVelocities, &m_newtonStart})
            if (*buffer && ((buffer != &m_startVelocities && buffer != &m_newtonStart) || m_newton))
                labels.push_back(buffer->label());
    return labels;
}

std::size_t ImplicitSolverPass::allocatedBytes() const {
    std::size_t bytes = 0;
    for (const gl::Buffer* buffer : {&m_residual, &m_preconditioned, &m_direction0, &m_direction1, &m_product,
                                     &m_blockInverse, &m_partialsR, &m_partialsPq, &m_state})
        bytes += buffer->bytes();
    if (m_contacts)
        for (const gl::Buffer* buffer : std::initializer_list<const gl::Buffer*>{
                 &m_nodeContactCounts, &m_contactData, &m_startVelocities, &m_newtonStart})
            if ((buffer != &m_startVelocities && buffer != &m_newtonStart) || m_newton)
                bytes += buffer->bytes();
    return bytes;
}

std::uint32_t ImplicitSolverPass::dispatchesPerSubstep() const {
    return 2u + 2u * static_cast<std::uint32_t>(m_config.maxIterations);
}

} // namespace glcollide::passes
