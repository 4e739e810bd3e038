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

#include <cstdint>
#include <vector>

namespace glcollide::passes {

/// An observer point at both ends of the substep (it moves linearly between them).
struct RadialObserver {
    glm::vec3 start{0.0f}, end{0.0f};
};

/// A face that no observer classifies (never positive): GLC_RADIAL_NO_OBSERVER.
inline constexpr std::uint32_t kNoRadialObserver = 0xffffffffu;

class RadialClassifyPass {
  public:
    static constexpr const char* kName = "RadialClassify";
    /// `faceObserver`: per face, the index of its observer among `observerCount`, or
    /// kNoRadialObserver. Throws Error for an index out of range.
    RadialClassifyPass(const std::vector<std::uint32_t>& faceObserver, std::uint32_t observerCount);

    /// The observers' positions for the next dispatch (exactly `observerCount` of them).
    void setObservers(const std::vector<RadialObserver>& observers);
    /// Clears the mask and classifies every face over [positions, predictedPositions].
    void dispatch(const DeviceBuffers& buffers);
    /// The same over the positions, predicted positions and faces bound now.
    void dispatchOnBoundPositions();
    /// Bit f % 32 of word f / 32: face f is proven positive.
    [[nodiscard]] std::vector<std::uint32_t> readMask() const;
    [[nodiscard]] const gl::Buffer& mask() const { return m_mask; }
    /// vec4 per face: the footprint cone (valid for observed faces).
    [[nodiscard]] const gl::Buffer& cones() const { return m_cones; }
    /// uint[1 + faces]: the count, then the observed faces not proven positive (any order).
    [[nodiscard]] const gl::Buffer& nonPositive() const { return m_nonPositive; }
    /// vec4[2 * observers]: start and end of each observer (setObservers or a GPU pass writes it).
    [[nodiscard]] const gl::Buffer& observers() const { return m_observers; }
    [[nodiscard]] const gl::Buffer& faceObserver() const { return m_faceObserver; }
    [[nodiscard]] std::uint32_t faceCount() const { return m_faceCount; }

  private:
    std::uint32_t m_faceCount = 0, m_observerCount = 0;
    gl::Buffer m_faceObserver, m_observers, m_mask, m_cones, m_nonPositive;
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
