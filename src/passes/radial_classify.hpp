#pragma once
// RadialClassify — radial view-based culling's triangle classification (issue 24; docs/culling.md,
// "Classification"): every face whose observer sees it positive over the whole substep, from the
// positions x0 to the predicted positions x1, gets its bit in a mask (radial_classify.comp); every
// observed face also gets its footprint cone, and those not proven positive go to a list, for
// RadialFree (RadialCullingPass). C++ twins: cpu::radialPositiveMask, glcRadialFootprint (the same
// GLSL compiled as C++).

#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "passes/device_buffers.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace glcollide::passes {

/// An observer point at both ends of the substep (it moves linearly between them); for a segment
/// observer (decision 0025, "Segment observers") that is its first end, and `segment` holds its
/// second end at both ends of the substep.
struct RadialObserver {
    glm::vec3 start{0.0f}, end{0.0f};
    std::optional<std::array<glm::vec3, 2>> segment = std::nullopt;
};

/// A face that no observer classifies (never positive): GLC_RADIAL_NO_OBSERVER.
inline constexpr std::uint32_t kNoRadialObserver = 0xffffffffu;

/// Ghost triangles classified after the real faces (docs/culling.md, "Ghost triangles"): the
/// classified faces are the model's faces, then these. A node index >= `nodeCount` names ghost node
/// (index - nodeCount), whose positions RadialGhostNodes writes into ghostPositions().
struct RadialGhostFaces {
    std::uint32_t nodeCount = 0;      ///< nodes of the model
    std::uint32_t ghostNodeCount = 0; ///< ghost nodes
    std::vector<std::uint32_t> faces; ///< 3 node indices per ghost face, in winding order
};

class RadialClassifyPass {
  public:
    static constexpr const char* kName = "RadialClassify";
    /// `faceObserver`: per classified face (the model's faces, then the ghost faces), the index of
    /// its observer among `observerCount`, or kNoRadialObserver. Throws Error for an index out of
    /// range, fewer entries than ghost faces, or a ghost face naming a node past the ghost nodes.
    RadialClassifyPass(const std::vector<std::uint32_t>& faceObserver, std::uint32_t observerCount,
                       const RadialGhostFaces& ghosts = {});

    /// The observers' positions for the next dispatch (exactly `observerCount` of them).
    void setObservers(const std::vector<RadialObserver>& observers);
    /// Clears the mask and classifies every face over [positions, predictedPositions].
    void dispatch(const DeviceBuffers& buffers);
    /// The same over the positions, predicted positions and faces bound now (and the ghost
    /// positions RadialGhostNodes wrote).
    void dispatchOnBoundPositions();
    /// Bit f % 32 of word f / 32: classified face f is proven positive.
    [[nodiscard]] std::vector<std::uint32_t> readMask() const;
    [[nodiscard]] const gl::Buffer& mask() const { return m_mask; }
    /// vec4 per face: the footprint cone (valid for observed faces).
    [[nodiscard]] const gl::Buffer& cones() const { return m_cones; }
    /// uint[1 + faces]: the count, then the observed faces not proven positive (any order).
    [[nodiscard]] const gl::Buffer& nonPositive() const { return m_nonPositive; }
    /// uint[GLC_RADIAL_CELL_WORDS * observers]: the footprint cells the non-positive faces marked
    /// (common/radial_cells.glsl); RadialFree reads them.
    [[nodiscard]] const gl::Buffer& cells() const { return m_cells; }
    /// vec4[2 * observers]: start and end of each observer (setObservers or a GPU pass writes it).
    [[nodiscard]] const gl::Buffer& observers() const { return m_observers; }
    /// vec4[2 * observers]: a segment observer's second end at start and end, w = 1 (0: a point).
    [[nodiscard]] const gl::Buffer& segments() const { return m_segments; }
    /// vec2 per face: the feet interval (valid for observed faces; [0, 1] for point observers).
    [[nodiscard]] const gl::Buffer& feet() const { return m_feet; }
    [[nodiscard]] const gl::Buffer& faceObserver() const { return m_faceObserver; }
    /// uint[3 * ghost faces] (GLC_BIND_RADIAL_GHOST_FACES).
    [[nodiscard]] const gl::Buffer& ghostFaces() const { return m_ghostFaces; }
    /// vec4[2 * ghost nodes]: each ghost node at t = 0 and t = 1 (RadialGhostNodes writes it).
    [[nodiscard]] const gl::Buffer& ghostPositions() const { return m_ghostPositions; }
    /// Classified faces: the model's, then the ghosts.
    [[nodiscard]] std::uint32_t faceCount() const { return m_faceCount; }
    [[nodiscard]] std::uint32_t realFaceCount() const { return m_realFaceCount; }
    /// The uniforms of common/radial_ghost.glsl for `program`.
    void setGhostUniforms(const gl::ComputeProgram& program) const;

  private:
    std::uint32_t m_faceCount = 0, m_realFaceCount = 0, m_observerCount = 0, m_nodeLimit = 0;
    std::vector<std::uint32_t> m_nonPositiveHeader; ///< uploaded before each classification: counts 0
    gl::Buffer m_faceObserver, m_observers, m_segments, m_mask, m_cones, m_feet, m_nonPositive, m_cells,
        m_ghostFaces, m_ghostPositions;
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
