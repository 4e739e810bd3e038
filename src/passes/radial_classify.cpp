#include "passes/radial_classify.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>
#include <glm/vec4.hpp>

#include <string>

namespace glcollide::passes {

RadialClassifyPass::RadialClassifyPass(const std::vector<std::uint32_t>& faceObserver,
                                       std::uint32_t observerCount)
    : m_faceCount(static_cast<std::uint32_t>(faceObserver.size())), m_observerCount(observerCount),
      m_faceObserver(gl::makeBuffer("radialFaceObserver", faceObserver)),
      m_observers("radialObservers", std::size_t{2} * observerCount * sizeof(glm::vec4)),
      m_mask("radialPositive", ((m_faceCount + 31u) / 32u) * sizeof(std::uint32_t)),
      m_cones("radialCones", std::size_t{m_faceCount} * sizeof(glm::vec4)),
      m_nonPositive("radialNonPositive", (std::size_t{m_faceCount} + 1) * sizeof(std::uint32_t)),
      m_program("radial_classify") {
    for (std::size_t f = 0; f < faceObserver.size(); ++f)
        if (faceObserver[f] != kNoRadialObserver && faceObserver[f] >= observerCount)
            throw Error(std::string(kName) + ": face " + std::to_string(f) + " names observer " +
                        std::to_string(faceObserver[f]) + " of " + std::to_string(observerCount));
    m_program.set("u_faceCount", m_faceCount);
}

void RadialClassifyPass::setObservers(const std::vector<RadialObserver>& observers) {
    if (observers.size() != m_observerCount)
        throw Error(std::string(kName) + ": " + std::to_string(observers.size()) + " observers given, " +
                    std::to_string(m_observerCount) + " expected");
    std::vector<glm::vec4> packed;
    for (const RadialObserver& o : observers) {
        packed.emplace_back(o.start, 1.0f);
        packed.emplace_back(o.end, 1.0f);
    }
    m_observers.upload(0, packed.size() * sizeof(glm::vec4), packed.data());
}

void RadialClassifyPass::dispatch(const DeviceBuffers& b) {
    if (b.faceCount != m_faceCount)
        throw Error(std::string(kName) + ": built for " + std::to_string(m_faceCount) + " faces, given " +
                    std::to_string(b.faceCount));
    bindRequired(b.positions, GLC_BIND_NODE_POSITIONS, kName, "positions");
    bindRequired(b.predictedPositions, GLC_BIND_PREDICTED_POSITIONS, kName, "predictedPositions");
    bindRequired(b.faces, GLC_BIND_FACES, kName, "faces");
    dispatchOnBoundPositions();
}

void RadialClassifyPass::dispatchOnBoundPositions() {
    m_faceObserver.bindStorage(GLC_BIND_RADIAL_FACE_OBSERVER);
    m_observers.bindStorage(GLC_BIND_RADIAL_OBSERVERS);
    m_mask.fill32(0u);
    const std::uint32_t zero = 0;
    m_nonPositive.upload(0, sizeof zero, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    m_mask.bindStorage(GLC_BIND_RADIAL_POSITIVE);
    m_cones.bindStorage(GLC_BIND_RADIAL_CONES);
    m_nonPositive.bindStorage(GLC_BIND_RADIAL_NONPOSITIVE);
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
