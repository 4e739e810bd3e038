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

std::vector<std::uint8_t> radialFreeFaces(const std::vector<std::uint32_t>& faceIndices,
                                          const std::vector<glm::vec3>& x0, const std::vector<glm::vec3>& x1,
                                          const std::vector<std::uint32_t>& faceObserver,
                                          const std::vector<glm::vec3>& observers) {
    const std::size_t faces = faceObserver.size();
    const std::vector<std::uint32_t> positive =
        radialPositiveMask(faceIndices, x0, x1, faceObserver, observers);
    const auto isPositive = [&](std::size_t f) { return (positive[f / 32] >> (f % 32) & 1u) != 0u; };
    std::vector<glm::vec4> cones(faces, shader::glcRadialEverywhere());
    for (std::size_t f = 0; f < faces; ++f) {
        const std::uint32_t o = faceObserver[f];
        if (o == 0xffffffffu) continue;
        const std::uint32_t a = faceIndices[3 * f], b = faceIndices[3 * f + 1], c = faceIndices[3 * f + 2];
        cones[f] = shader::glcRadialFootprint(x0[a], x0[b], x0[c], observers[2 * std::size_t{o}], x1[a],
                                              x1[b], x1[c], observers[2 * std::size_t{o} + 1]);
    }
    std::vector<std::uint8_t> free(faces, 0);
    for (std::size_t f = 0; f < faces; ++f) {
        if (!isPositive(f)) continue;
        bool meets = false;
        for (std::size_t g = 0; g < faces && !meets; ++g)
            meets = faceObserver[g] == faceObserver[f] && !isPositive(g) &&
                    shader::glcRadialFootprintsMeet(cones[f], cones[g]);
        free[f] = meets ? 0 : 1;
    }
    return free;
}

} // namespace glcollide::cpu
