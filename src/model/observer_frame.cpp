#include "model/observer_frame.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace glcollide::model {
namespace {

/// The index of the node with the largest score (the first of equal ones).
template <typename Score> std::uint32_t farthest(const std::vector<glm::dvec3>& positions, Score score) {
    std::uint32_t best = 0;
    double bestScore = -1.0;
    for (std::uint32_t i = 0; i < positions.size(); ++i)
        if (const double s = score(positions[i]); s > bestScore) {
            best = i;
            bestScore = s;
        }
    return best;
}

} // namespace

ObserverFrame observerFrame(const std::vector<glm::dvec3>& positions, const glm::dvec3& point) {
    if (positions.size() < 4) throw std::invalid_argument("an observer frame needs four nodes");
    glm::dvec3 mean(0.0), lo = positions[0], hi = positions[0];
    for (const glm::dvec3& x : positions) {
        mean += x;
        lo = glm::min(lo, x);
        hi = glm::max(hi, x);
    }
    mean /= static_cast<double>(positions.size());
    const std::uint32_t a = farthest(positions, [&](const glm::dvec3& x) { return glm::length(x - mean); });
    const glm::dvec3 xa = positions[a];
    const std::uint32_t b = farthest(positions, [&](const glm::dvec3& x) { return glm::length(x - xa); });
    const glm::dvec3 ab = positions[b] - xa;
    const std::uint32_t c =
        farthest(positions, [&](const glm::dvec3& x) { return glm::length(glm::cross(ab, x - xa)); });
    const glm::dvec3 normal = glm::cross(ab, positions[c] - xa);
    const std::uint32_t d =
        farthest(positions, [&](const glm::dvec3& x) { return std::abs(glm::dot(normal, x - xa)); });
    const glm::dmat3 edges(ab, positions[c] - xa, positions[d] - xa); // columns
    const double volume6 = glm::determinant(edges);
    const glm::dvec3 extent = hi - lo;
    const double size = std::max({extent.x, extent.y, extent.z});
    if (!(std::abs(volume6) > 1e-6 * size * size * size))
        throw std::invalid_argument("the object's nodes span no volume: an observer cannot be tied to them");
    const glm::dvec3 w = glm::inverse(edges) * (point - xa);
    return {{a, b, c, d}, {1.0 - w.x - w.y - w.z, w.x, w.y, w.z}};
}

} // namespace glcollide::model
