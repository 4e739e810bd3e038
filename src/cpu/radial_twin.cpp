#include "cpu/radial_twin.hpp"

#include "cpu/radial_library.hpp"

#include <glcollide/error.hpp>

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <utility>
#include <string>

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

std::vector<RadialWindingNumber> radialWindingNumbers(const std::vector<std::uint32_t>& faceIndices,
                                                      const std::vector<glm::vec3>& x0,
                                                      const std::vector<std::uint32_t>& faceObserver,
                                                      const std::vector<glm::vec3>& observers,
                                                      const std::vector<bool>& inward) {
    std::vector<RadialWindingNumber> out(observers.size());
    for (std::size_t f = 0; f < faceObserver.size(); ++f) {
        const std::uint32_t o = faceObserver[f];
        if (o == 0xffffffffu) continue;
        const glm::vec3 p0 = x0[faceIndices[3 * f]];
        glm::vec3 p1 = x0[faceIndices[3 * f + 1]], p2 = x0[faceIndices[3 * f + 2]];
        if (inward.at(o)) std::swap(p1, p2);
        const int crossing =
            shader::glcRadialRayCrossing(p0, p1, p2, observers.at(o), shader::GLC_RADIAL_RAY);
        if (crossing == shader::GLC_RADIAL_RAY_UNDECIDED)
            out[o].undecided = true;
        else
            out[o].number += crossing;
    }
    return out;
}

std::vector<RadialFacePair> radialViolatedPairs(const std::vector<std::uint32_t>& faceIndices,
                                                std::size_t realFaces,
                                                const std::vector<glm::vec3>& positions) {
    const std::size_t faces = faceIndices.size() / 3;
    const auto corner = [&](std::size_t f, int k) {
        return faceIndices[3 * f + static_cast<std::size_t>(k)];
    };
    const auto sharesNode = [&](std::size_t f, std::size_t g) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (corner(f, i) == corner(g, j)) return true;
        return false;
    };
    // Closed boxes: a pair whose boxes do not touch cannot intersect (touching counts).
    std::vector<glm::vec3> lo(faces), hi(faces);
    for (std::size_t f = 0; f < faces; ++f) {
        lo[f] = hi[f] = positions[corner(f, 0)];
        for (int k = 1; k < 3; ++k) {
            lo[f] = glm::min(lo[f], positions[corner(f, k)]);
            hi[f] = glm::max(hi[f], positions[corner(f, k)]);
        }
    }
    std::vector<RadialFacePair> violated;
    for (std::size_t g = realFaces; g < faces; ++g) // a ghost face against every face before it
        for (std::size_t f = 0; f < g; ++f) {
            if (glm::any(glm::lessThan(hi[f], lo[g])) || glm::any(glm::lessThan(hi[g], lo[f]))) continue;
            if (sharesNode(f, g)) continue;
            const bool hit = shader::glcTriTriExact(positions[corner(f, 0)], positions[corner(f, 1)],
                                                    positions[corner(f, 2)], positions[corner(g, 0)],
                                                    positions[corner(g, 1)], positions[corner(g, 2)]);
            if (shader::glcExactFailed)
                throw Error("radialViolatedPairs: the exact test could not decide faces " +
                            std::to_string(f) + " and " + std::to_string(g));
            if (hit) violated.push_back({static_cast<std::uint32_t>(f), static_cast<std::uint32_t>(g)});
        }
    std::sort(violated.begin(), violated.end());
    return violated;
}

} // namespace glcollide::cpu
