#include "passes/radial_culling.hpp"

#include "core/gpu_layout.hpp"
#include "model/ghost_triangles.hpp"
#include "model/radial_surfaces.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <string>

namespace glcollide::passes {
namespace {
std::vector<std::uint32_t> surfaceRanges(const std::vector<RadialSurface>& surfaces) {
    std::vector<std::uint32_t> ranges;
    for (std::size_t o = 0; o < surfaces.size(); ++o) {
        if (surfaces[o].nodeCount == 0)
            throw Error(std::string(RadialCullingPass::kName) + ": observer " + std::to_string(o) +
                        " has a surface with no nodes");
        ranges.insert(ranges.end(),
                      {surfaces[o].firstNode, surfaces[o].nodeCount, surfaces[o].inward ? 1u : 0u, 0u});
    }
    if (ranges.empty()) ranges = {0u, 0u, 0u, 0u}; // a buffer the consumers can bind
    return ranges;
}

/// uvec4 per observer for RadialViolated: first real face, real faces, first ghost face as a
/// classified index (after the `realFaces`), ghost faces.
std::vector<std::uint32_t> observerFaceRanges(const RadialCullingConfig& config) {
    const auto realFaces = static_cast<std::uint32_t>(config.faceObserver.size());
    std::vector<std::uint32_t> ranges;
    for (const RadialSurface& s : config.surfaces)
        ranges.insert(ranges.end(),
                      {s.firstFace, s.faceCount, realFaces + s.firstGhostFace, s.ghostFaceCount});
    if (ranges.empty()) ranges = {0u, 0u, 0u, 0u};
    return ranges;
}

/// The classified faces' observers: the real faces', then the ghost faces'.
std::vector<std::uint32_t> classifiedFaceObservers(const RadialCullingConfig& config) {
    std::vector<std::uint32_t> all = config.faceObserver;
    all.insert(all.end(), config.ghosts.faceObserver.begin(), config.ghosts.faceObserver.end());
    return all;
}

/// RadialGhostNodes' table: the CSR offsets counted from the buffer's start, then the loop nodes.
std::vector<std::uint32_t> ghostLoopTable(const RadialGhosts& g) {
    if (g.loopOffsets.empty()) return {0u};
    const auto shift = static_cast<std::uint32_t>(g.loopOffsets.size());
    std::vector<std::uint32_t> table;
    for (std::uint32_t o : g.loopOffsets) table.push_back(shift + o);
    table.insert(table.end(), g.loopNodes.begin(), g.loopNodes.end());
    return table;
}

std::uint32_t ghostNodeCount(const RadialGhosts& g) {
    return g.loopOffsets.empty() ? 0u : static_cast<std::uint32_t>(g.loopOffsets.size() - 1);
}

/// Checks the ghosts' tables against each other and the surfaces; returns the ghost faces.
RadialGhostFaces checkedGhosts(const RadialCullingConfig& config) {
    const RadialGhosts& g = config.ghosts;
    const std::string name = RadialCullingPass::kName;
    const std::uint32_t nodes = ghostNodeCount(g);
    if (g.faces.size() != 3 * g.faceObserver.size())
        throw Error(name + ": " + std::to_string(g.faces.size()) + " ghost face indices for " +
                    std::to_string(g.faceObserver.size()) + " ghost faces");
    if (!g.loopOffsets.empty() && (g.loopOffsets.front() != 0 || g.loopOffsets.back() != g.loopNodes.size()))
        throw Error(name + ": the ghost loops' offsets do not span their " +
                    std::to_string(g.loopNodes.size()) + " nodes");
    for (std::size_t k = 1; k < g.loopOffsets.size(); ++k)
        if (g.loopOffsets[k] <= g.loopOffsets[k - 1])
            throw Error(name + ": ghost node " + std::to_string(k - 1) + " has an empty loop");
    for (std::uint32_t n : g.loopNodes)
        if (n >= g.nodeCount)
            throw Error(name + ": a ghost loop names node " + std::to_string(n) + " of " +
                        std::to_string(g.nodeCount));
    for (std::size_t o = 0; o < config.surfaces.size(); ++o) {
        const RadialSurface& s = config.surfaces[o];
        if (std::uint64_t{s.firstFace} + s.faceCount > config.faceObserver.size() ||
            std::uint64_t{s.firstGhostFace} + s.ghostFaceCount > g.faceObserver.size())
            throw Error(name + ": observer " + std::to_string(o) + "'s faces lie outside the faces");
    }
    return {g.nodeCount, nodes, g.faces};
}

/// Six times the volume a closed surface bounds, signed: positive when its faces wind outward
/// (faces[3k .. 3k + 2] index `positions`). Decides only which way the classification turns the
/// faces (decision 0025, "Orientation").
double signedVolume6(const std::vector<std::uint32_t>& faces, std::uint32_t firstFace,
                     std::uint32_t faceCount, const std::vector<glm::dvec3>& positions) {
    double sum = 0.0;
    for (std::size_t f = firstFace; f < std::size_t{firstFace} + faceCount; ++f)
        sum += glm::dot(positions[faces[3 * f]],
                        glm::cross(positions[faces[3 * f + 1]], positions[faces[3 * f + 2]]));
    return sum;
}

/// The ghost closure of one object (docs/culling.md, "Ghost triangles"), in the object's own node
/// indices (ghost node g is nodeCount + g); empty when no loop is filled or the closed surface is
/// not one closed, consistently oriented, connected surface. `inward`: the closed surface winds
/// inward at the model's positions.
model::GhostTriangles objectGhosts(const model::FlatModel& model, const model::ObjectRange& r,
                                   double maxPerimeter, bool& inward) {
    std::vector<model::Triangle> faces;
    for (std::uint32_t f = 0; f < r.faceCount; ++f) {
        const std::uint32_t* n = &model.faceIndices[3 * std::size_t{r.firstFace + f}];
        faces.push_back({n[0] - r.firstNode, n[1] - r.firstNode, n[2] - r.firstNode});
    }
    const std::vector<glm::dvec3> positions(model.positions.begin() + r.firstNode,
                                            model.positions.begin() + r.firstNode + r.nodeCount);
    model::GhostTriangles ghosts = model::ghostTriangles(faces, positions, {maxPerimeter});
    std::vector<std::uint32_t> closed;
    for (const model::Triangle& t : faces) closed.insert(closed.end(), t.begin(), t.end());
    for (const model::Triangle& t : ghosts.faces) closed.insert(closed.end(), t.begin(), t.end());
    const auto all = static_cast<std::uint32_t>(closed.size() / 3);
    if (ghosts.faces.empty() || !model::isClosedOrientedConnected(closed, 0, all)) return {};
    std::vector<glm::dvec3> withGhosts = positions;
    for (const glm::dvec3& p : model::ghostNodePositions(ghosts, positions)) withGhosts.push_back(p);
    inward = signedVolume6(closed, 0, all, withGhosts) < 0.0;
    return ghosts;
}

} // namespace

RadialCullingConfig radialCullingConfig(const model::FlatModel& model, double ghostMaxPerimeter) {
    RadialCullingConfig config;
    config.faceObserver.assign(model.faceCount(), kNoRadialObserver);
    RadialGhosts& g = config.ghosts;
    g.nodeCount = static_cast<std::uint32_t>(model.nodeCount());
    for (const model::ObjectRange& r : model.objects) {
        const auto observer = static_cast<std::uint32_t>(config.surfaces.size());
        RadialSurface surface{r.firstNode,
                              r.nodeCount,
                              r.firstFace,
                              r.faceCount,
                              static_cast<std::uint32_t>(g.faceObserver.size()),
                              0};
        if (!model::isClosedOrientedConnected(model.faceIndices, r.firstFace, r.faceCount)) {
            if (!(ghostMaxPerimeter > 0.0)) continue;
            const model::GhostTriangles ghosts = objectGhosts(model, r, ghostMaxPerimeter, surface.inward);
            if (ghosts.faces.empty()) continue;
            // Ghost node k of this object is ghost node `base + k` of the model.
            const auto base =
                static_cast<std::uint32_t>(g.loopOffsets.empty() ? 0 : g.loopOffsets.size() - 1);
            if (g.loopOffsets.empty()) g.loopOffsets.push_back(0);
            for (std::uint32_t loop : ghosts.ghostNodeLoop) {
                for (std::uint32_t n : ghosts.loops[loop].nodes) g.loopNodes.push_back(r.firstNode + n);
                g.loopOffsets.push_back(static_cast<std::uint32_t>(g.loopNodes.size()));
            }
            for (const model::Triangle& t : ghosts.faces) {
                for (std::uint32_t n : t)
                    g.faces.push_back(n < r.nodeCount ? r.firstNode + n
                                                      : g.nodeCount + base + (n - r.nodeCount));
                g.faceObserver.push_back(observer);
            }
            surface.ghostFaceCount = static_cast<std::uint32_t>(ghosts.faces.size());
        } else {
            surface.inward =
                signedVolume6(model.faceIndices, r.firstFace, r.faceCount, model.positions) < 0.0;
        }
        config.surfaces.push_back(surface);
        for (std::uint32_t f = 0; f < r.faceCount; ++f) config.faceObserver[r.firstFace + f] = observer;
    }
    return config;
}

RadialCullingPass::RadialCullingPass(const RadialCullingConfig& config)
    : m_faceCount(static_cast<std::uint32_t>(config.faceObserver.size())),
      m_observerCount(static_cast<std::uint32_t>(config.surfaces.size())),
      m_ghostNodeCount(ghostNodeCount(config.ghosts)),
      m_ghostFaceCount(static_cast<std::uint32_t>(config.ghosts.faceObserver.size())),
      m_classify(classifiedFaceObservers(config), m_observerCount, checkedGhosts(config)),
      m_surfaces(gl::makeBuffer("radialSurfaces", surfaceRanges(config.surfaces))),
      m_observerFaces(gl::makeBuffer("radialObserverFaces", observerFaceRanges(config))),
      m_ghostLoops(gl::makeBuffer("radialGhostLoops", ghostLoopTable(config.ghosts))),
      m_free("radialFree", (1u + (m_faceCount + 31u) / 32u) * sizeof(std::uint32_t)),
      m_moved("radialMoved", sizeof(std::uint32_t)),
      m_violated("radialViolated", std::max(m_observerCount, 1u) * sizeof(std::uint32_t)),
      m_observers("radial_observers"), m_freeProgram("radial_free"), m_hostCheck("radial_host_check") {
    for (std::uint32_t o : config.faceObserver) m_observedFaces += o != kNoRadialObserver ? 1u : 0u;
    for (const RadialSurface& s : config.surfaces)
        if (s.ghostFaceCount > 0)
            m_largestSurface = std::max(m_largestSurface, s.faceCount + s.ghostFaceCount);
    m_freeProgram.set("u_faceCount", m_faceCount);
    m_free.fill32(0u);
    m_violated.fill32(0u);
    if (m_ghostFaceCount > 0) { // compiled only for scenes with ghosts (start-up cost)
        m_ghostNodes.emplace("radial_ghost_nodes");
        m_ghostNodes->set("u_ghostNodeCount", m_ghostNodeCount);
        m_violatedProgram.emplace("radial_violated");
        m_violatedProgram->set("u_ghostFaceCount", m_ghostFaceCount);
        m_classify.setGhostUniforms(*m_violatedProgram);
        m_violatedExact.emplace("radial_violated_exact");
        m_classify.setGhostUniforms(*m_violatedExact);
        m_undecided = gl::Buffer("radialUndecided", (2 + 2 * std::size_t{GLC_RADIAL_UNDECIDED_CAPACITY}) *
                                                        sizeof(std::uint32_t));
    }
}

void RadialCullingPass::bindForConsumers() const {
    m_classify.faceObserver().bindStorage(GLC_BIND_RADIAL_FACE_OBSERVER);
    m_surfaces.bindStorage(GLC_BIND_RADIAL_OBSERVER_NODES);
    m_free.bindStorage(GLC_BIND_RADIAL_FREE);
}

void RadialCullingPass::run(AppendLists& lists) const {
    lists.resetStats({GLC_STAT_RADIAL_NON_POSITIVE, GLC_STAT_RADIAL_FREE, GLC_STAT_RADIAL_VIOLATED});
    bindForConsumers();
    m_classify.observers().bindStorage(GLC_BIND_RADIAL_OBSERVERS);
    m_observers.use();
    gl::ComputeProgram::dispatch(m_observerCount, 1, 1); // one work group per observer; counted
    m_violated.fill32(0u);
    if (m_ghostNodes) {
        m_ghostLoops.bindStorage(GLC_BIND_RADIAL_GHOST_LOOPS);
        m_classify.ghostPositions().bindStorage(GLC_BIND_RADIAL_GHOST_POSITIONS);
        m_ghostNodes->use();
        m_ghostNodes->dispatch1D(m_ghostNodeCount, GLC_WORKGROUP_SIZE);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_classify.dispatchOnBoundPositions();
    m_violated.bindStorage(GLC_BIND_RADIAL_VIOLATED);
    if (m_violatedProgram) { // the ghost faces and positions are still bound by the classification
        m_observerFaces.bindStorage(GLC_BIND_RADIAL_OBSERVER_FACES);
        m_violatedProgram->use();
        // One work-group row per ghost face, one invocation per face of its surface; at most
        // 65,535 rows per dispatch (GL's minimum).
        const std::uint32_t groups = (m_largestSurface + GLC_WORKGROUP_SIZE - 1) / GLC_WORKGROUP_SIZE;
        m_undecided.fill32(0u);
        m_undecided.bindStorage(GLC_BIND_RADIAL_UNDECIDED);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        for (std::uint32_t first = 0; first < m_ghostFaceCount; first += 65535u) {
            m_violatedProgram->set("u_firstGhostFace", first);
            gl::ComputeProgram::dispatch(groups, std::min(65535u, m_ghostFaceCount - first), 1);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        m_violatedExact->use();
        m_violatedExact->dispatch1D(GLC_RADIAL_UNDECIDED_CAPACITY, GLC_WORKGROUP_SIZE);
    }
    m_free.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_freeProgram.use();
    m_freeProgram.dispatch1D(std::max(m_faceCount, 1u), GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void RadialCullingPass::switchOff() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after the last substep's reads of the mask
    const std::uint32_t off = 0;
    m_free.upload(0, sizeof off, &off);
}

bool RadialCullingPass::hostMovedNodes(const DeviceBuffers& b) const {
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, "RadialHostCheck", "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, "RadialHostCheck", "predictedPositions");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_moved.fill32(0u);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_moved.bindStorage(GLC_BIND_RADIAL_MOVED);
    m_hostCheck.use();
    m_hostCheck.set("u_nodeCount", b.nodeCount);
    m_hostCheck.dispatch1D(std::max(b.nodeCount, 1u), GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t moved = 0;
    m_moved.download(0, sizeof moved, &moved);
    return moved != 0;
}

std::vector<std::uint32_t> RadialCullingPass::readFreeMask() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> words((m_faceCount + 31u) / 32u);
    if (!words.empty())
        m_free.download(sizeof(std::uint32_t), words.size() * sizeof(std::uint32_t), words.data());
    return words;
}

std::vector<RadialObserver> RadialCullingPass::readGhostNodes() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> packed(2 * std::size_t{m_ghostNodeCount});
    if (!packed.empty())
        m_classify.ghostPositions().download(0, packed.size() * sizeof(glm::vec4), packed.data());
    std::vector<RadialObserver> out;
    for (std::size_t g = 0; g < m_ghostNodeCount; ++g)
        out.push_back({glm::vec3(packed[2 * g]), glm::vec3(packed[2 * g + 1])});
    return out;
}

std::vector<std::uint32_t> RadialCullingPass::readViolated() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> flags(m_observerCount);
    if (!flags.empty()) m_violated.download(0, flags.size() * sizeof(std::uint32_t), flags.data());
    return flags;
}

std::vector<RadialObserver> RadialCullingPass::readObservers() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> packed(2 * std::size_t{m_observerCount});
    if (!packed.empty()) m_classify.observers().download(0, packed.size() * sizeof(glm::vec4), packed.data());
    std::vector<RadialObserver> out;
    for (std::size_t o = 0; o < m_observerCount; ++o)
        out.push_back({glm::vec3(packed[2 * o]), glm::vec3(packed[2 * o + 1])});
    return out;
}

} // namespace glcollide::passes
