// Lumped (diagonal) mass: each element's measure shared equally by its nodes.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <glm/geometric.hpp>

#include <cmath>

namespace glcollide::detail {

std::vector<double> lumpedMeasure(const std::vector<glm::dvec3>& positions, const std::vector<Face>& faces,
                                  const std::vector<Tet>& tets, const std::string& what) {
    std::vector<double> lump(positions.size(), 0.0);
    double total = 0.0;
    if (tets.empty()) {
        for (const Face& f : faces) {
            const double area = 0.5 * glm::length(glm::cross(positions[f[1]] - positions[f[0]],
                                                             positions[f[2]] - positions[f[0]]));
            for (std::uint32_t v : f) lump[v] += area / 3.0;
            total += area;
        }
    } else {
        for (const Tet& t : tets) {
            const double volume =
                std::abs(tetDet(positions[t[0]], positions[t[1]], positions[t[2]], positions[t[3]])) / 6.0;
            for (std::uint32_t v : t) lump[v] += volume / 4.0;
            total += volume;
        }
    }
    const char* measure = tets.empty() ? "area" : "volume";
    if (!(total > 0.0) || !std::isfinite(total))
        throw Error(what + ": total " + measure + " is zero, so mass cannot be distributed");
    for (std::size_t v = 0; v < lump.size(); ++v)
        if (!(lump[v] > 0.0))
            throw Error(what + ": vertex " + std::to_string(v) + " belongs to no " +
                        (tets.empty() ? "triangle" : "tetrahedron") + " of non-zero " + measure +
                        ", so it would get no mass (remove isolated or degenerate vertices)");
    return lump;
}

} // namespace glcollide::detail
