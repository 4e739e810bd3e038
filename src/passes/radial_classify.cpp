#include "passes/radial_classify.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>

#include <string>

namespace glcollide::passes {

namespace {
/// The ghost faces, checked against the classified faces and the ghost nodes.
const std::vector<std::uint32_t>& checkedGhostFaces(const std::vector<std::uint32_t>& faceObserver,
                                                    const RadialGhostFaces& ghosts) {
    const std::string kName = RadialClassifyPass::kName;
    if (ghosts.faces.size() % 3 != 0 || ghosts.faces.size() / 3 > faceObserver.size())
        throw Error(kName + ": " + std::to_string(ghosts.faces.size()) + " ghost face indices for " +
                    std::to_string(faceObserver.size()) + " classified faces");
    const std::uint64_t nodes = std::uint64_t{ghosts.nodeCount} + ghosts.ghostNodeCount;
    for (std::size_t i = 0; i < ghosts.faces.size(); ++i)
        if (ghosts.faces[i] >= nodes)
            throw Error(kName + ": ghost face " + std::to_string(i / 3) + " names node " +
                        std::to_string(ghosts.faces[i]) + " of " + std::to_string(nodes));
    return ghosts.faces;
}

/// The non-positive lists' header (layout.glsl, GLC_BIND_RADIAL_NONPOSITIVE): the total, then per
/// observer its count (0) and where its bucket starts; a bucket holds every classified face of its
/// observer, so no append can overflow it.
std::vector<std::uint32_t> nonPositiveHeader(const std::vector<std::uint32_t>& faceObserver,
                                             std::uint32_t observerCount) {
    std::vector<std::uint32_t> faces(observerCount, 0);
    for (std::uint32_t o : faceObserver)
        if (o < observerCount) ++faces[o];
    std::vector<std::uint32_t> header{0u};
    std::uint32_t start = 1 + 2 * observerCount;
    for (std::uint32_t o = 0; o < observerCount; ++o) {
        header.insert(header.end(), {0u, start});
        start += faces[o];
    }
    return header;
}
} // namespace

RadialClassifyPass::RadialClassifyPass(const std::vector<std::uint32_t>& faceObserver,
                                       std::uint32_t observerCount, const RadialGhostFaces& ghosts)
    : m_faceCount(static_cast<std::uint32_t>(faceObserver.size())),
      m_realFaceCount(static_cast<std::uint32_t>(faceObserver.size() -
                                                 checkedGhostFaces(faceObserver, ghosts).size() / 3)),
      m_observerCount(observerCount),
      // Without ghosts no node index may read the ghost positions, whatever the node count.
      m_nodeLimit(ghosts.faces.empty() ? 0xffffffffu : ghosts.nodeCount),
      m_nonPositiveHeader(nonPositiveHeader(faceObserver, observerCount)),
      m_faceObserver(gl::makeBuffer("radialFaceObserver", faceObserver)),
      m_observers("radialObservers", std::size_t{2} * observerCount * sizeof(glm::vec4)),
      m_segments("radialSegments", std::size_t{2} * std::max(observerCount, 1u) * sizeof(glm::vec4)),
      m_mask("radialPositive", ((m_faceCount + 31u) / 32u) * sizeof(std::uint32_t)),
      m_cones("radialCones", std::size_t{m_faceCount} * sizeof(glm::vec4)),
      m_feet("radialFeet", std::size_t{std::max(m_faceCount, 1u)} * sizeof(glm::vec2)),
      m_nonPositive("radialNonPositive",
                    (m_nonPositiveHeader.size() + std::size_t{m_faceCount}) * sizeof(std::uint32_t)),
      m_cells("radialCells",
              std::size_t{GLC_RADIAL_CELL_WORDS} * std::max(observerCount, 1u) * sizeof(std::uint32_t)),
      m_ghostFaces(gl::makeBuffer("radialGhostFaces", ghosts.faces)),
      m_ghostPositions("radialGhostPositions", std::size_t{2} * ghosts.ghostNodeCount * sizeof(glm::vec4)),
      m_program("radial_classify") {
    for (std::size_t f = 0; f < faceObserver.size(); ++f)
        if (faceObserver[f] != kNoRadialObserver && faceObserver[f] >= observerCount)
            throw Error(std::string(kName) + ": face " + std::to_string(f) + " names observer " +
                        std::to_string(faceObserver[f]) + " of " + std::to_string(observerCount));
    m_program.set("u_faceCount", m_faceCount);
    setGhostUniforms(m_program);
    m_segments.fill32(0u); // point observers until a pass or setObservers says otherwise
}

void RadialClassifyPass::setGhostUniforms(const gl::ComputeProgram& program) const {
    program.set("u_realFaceCount", m_realFaceCount);
    program.set("u_nodeCount", m_nodeLimit);
}

void RadialClassifyPass::setObservers(const std::vector<RadialObserver>& observers) {
    if (observers.size() != m_observerCount)
        throw Error(std::string(kName) + ": " + std::to_string(observers.size()) + " observers given, " +
                    std::to_string(m_observerCount) + " expected");
    std::vector<glm::vec4> packed, segments;
    for (const RadialObserver& o : observers) {
        packed.emplace_back(o.start, 1.0f);
        packed.emplace_back(o.end, 1.0f);
        const float segment = o.segment ? 1.0f : 0.0f;
        segments.emplace_back(o.segment ? (*o.segment)[0] : glm::vec3(0.0f), segment);
        segments.emplace_back(o.segment ? (*o.segment)[1] : glm::vec3(0.0f), segment);
    }
    m_observers.upload(0, packed.size() * sizeof(glm::vec4), packed.data());
    m_segments.upload(0, segments.size() * sizeof(glm::vec4), segments.data());
}

void RadialClassifyPass::dispatch(const DeviceBuffers& b) {
    if (b.faceCount != m_realFaceCount)
        throw Error(std::string(kName) + ": built for " + std::to_string(m_realFaceCount) + " faces, given " +
                    std::to_string(b.faceCount));
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.faces, GLC_BIND_FACES, kName, "faces");
    dispatchOnBoundPositions();
}

void RadialClassifyPass::dispatchOnBoundPositions() {
    m_faceObserver.bindStorage(GLC_BIND_RADIAL_FACE_OBSERVER);
    m_observers.bindStorage(GLC_BIND_RADIAL_OBSERVERS);
    m_segments.bindStorage(GLC_BIND_RADIAL_SEGMENTS);
    m_ghostFaces.bindStorage(GLC_BIND_RADIAL_GHOST_FACES);
    m_ghostPositions.bindStorage(GLC_BIND_RADIAL_GHOST_POSITIONS);
    m_mask.fill32(0u);
    m_cells.fill32(0u);
    m_nonPositive.upload(0, m_nonPositiveHeader.size() * sizeof(std::uint32_t), m_nonPositiveHeader.data());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_mask.bindStorage(GLC_BIND_RADIAL_POSITIVE);
    m_cones.bindStorage(GLC_BIND_RADIAL_CONES);
    m_feet.bindStorage(GLC_BIND_RADIAL_FEET);
    m_nonPositive.bindStorage(GLC_BIND_RADIAL_NONPOSITIVE);
    m_cells.bindStorage(GLC_BIND_RADIAL_CELLS);
    m_program.use();
    m_program.dispatch1D(m_faceCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::vector<std::uint32_t> RadialClassifyPass::readMask() const {
    std::vector<std::uint32_t> words((m_faceCount + 31u) / 32u);
    m_mask.download(0, words.size() * sizeof(std::uint32_t), words.data());
    return words;
}

} // namespace glcollide::passes
