#include "cpu/radial_twin.hpp"

#include "cpu/radial_library.hpp"

namespace glcollide::cpu {

std::vector<std::uint32_t> radialPositiveMask(const std::vector<std::uint32_t>& faceIndices,
                                              const std::vector<glm::vec3>& x0,
                                              const std::vector<glm::vec3>& x1,
                                              const std::vector<std::uint32_t>& faceObserver,
                                              const std::vector<glm::vec3>& observers) {
    const std::size_t faces = faceObserver.size();
    std::vector<std::uint32_t> mask((faces + 31) / 32, 0u);
    for (std::size_t f = 0; f < faces; ++f) {
        const std::uint32_t o = faceObserver[f];
        if (o == 0xffffffffu) continue;
        const std::uint32_t a = faceIndices[3 * f], b = faceIndices[3 * f + 1], c = faceIndices[3 * f + 2];
        if (shader::glcRadialPositive(x0[a], x0[b], x0[c], observers[2 * std::size_t{o}], x1[a], x1[b], x1[c],
                                      observers[2 * std::size_t{o} + 1]))
            mask[f / 32] |= 1u << (f % 32);
    }
    return mask;
}

} // namespace glcollide::cpu
