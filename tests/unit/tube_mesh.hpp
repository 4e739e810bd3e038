#pragma once
// A tube (a cylinder without caps) for the unit tests of ghost triangles and of the culling's
// violated pairs: two boundary loops, one at each end.

#include "scene/scene_detail.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>

namespace glcollide::test {

/// A tube around +Z: `ring` nodes per ring, `rings` rings from z = 0 to `length`, radius
/// `radius`; node (i, j) = j · ring + i. Faces outward (or inward when `inward`).
inline detail::SurfaceMesh tube(std::uint32_t ring, std::uint32_t rings, double radius, double length,
                                bool inward = false) {
    detail::SurfaceMesh m;
    for (std::uint32_t j = 0; j < rings; ++j)
        for (std::uint32_t i = 0; i < ring; ++i) {
            const double angle = 2.0 * std::numbers::pi * i / ring;
            m.positions.emplace_back(radius * std::cos(angle), radius * std::sin(angle),
                                     length * j / (rings - 1));
        }
    for (std::uint32_t j = 0; j + 1 < rings; ++j)
        for (std::uint32_t i = 0; i < ring; ++i) {
            // (i, j) -> (i + 1, j) runs along +angle, (i, j) -> (i, j + 1) along +Z: their cross
            // product points away from the axis.
            const std::uint32_t a = j * ring + i, b = j * ring + (i + 1) % ring;
            const std::uint32_t c = b + ring, d = a + ring;
            if (inward) {
                m.faces.push_back({a, c, b});
                m.faces.push_back({a, d, c});
            } else {
                m.faces.push_back({a, b, c});
                m.faces.push_back({a, c, d});
            }
        }
    return m;
}

} // namespace glcollide::test
