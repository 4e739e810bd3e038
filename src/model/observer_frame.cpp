#include "model/observer_frame.hpp"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace glcollide::model {
namespace {

/// Four nodes of `candidates` (indices into positions) spread as far as they allow — the one
/// farthest from their mean, the one farthest from it, the one farthest from the line through
/// both, the one farthest from the plane through the three — with 6 times their tetrahedron's
/// volume and the candidates' largest extent.
struct Spread {
    std::array<std::uint32_t, 4> nodes{};
    glm::dmat3 edges{0.0}; ///< columns: nodes 1..3 minus node 0
    double volume6 = 0.0, size = 0.0;
};

Spread spread(const std::vector<glm::dvec3>& positions, const std::vector<std::uint32_t>& candidates) {
    glm::dvec3 mean(0.0), lo = positions[candidates[0]], hi = lo;
    for (const std::uint32_t i : candidates) {
        mean += positions[i];
        lo = glm::min(lo, positions[i]);
        hi = glm::max(hi, positions[i]);
    }
    mean /= static_cast<double>(candidates.size());
    const auto farthest = [&](auto score) {
        std::uint32_t best = candidates[0];
        double bestScore = -1.0;
        for (const std::uint32_t i : candidates)
            if (const double sc = score(positions[i]); sc > bestScore) {
                best = i;
                bestScore = sc;
            }
        return best;
    };
    Spread out;
    const std::uint32_t a = farthest([&](const glm::dvec3& x) { return glm::length(x - mean); });
    const glm::dvec3 xa = positions[a];
    const std::uint32_t b = farthest([&](const glm::dvec3& x) { return glm::length(x - xa); });
    const glm::dvec3 ab = positions[b] - xa;
    const std::uint32_t c =
        farthest([&](const glm::dvec3& x) { return glm::length(glm::cross(ab, x - xa)); });
    const glm::dvec3 normal = glm::cross(ab, positions[c] - xa);
    const std::uint32_t d = farthest([&](const glm::dvec3& x) { return std::abs(glm::dot(normal, x - xa)); });
    out.nodes = {a, b, c, d};
    out.edges = glm::dmat3(ab, positions[c] - xa, positions[d] - xa);
    out.volume6 = glm::determinant(out.edges);
    const glm::dvec3 extent = hi - lo;
    out.size = std::max({extent.x, extent.y, extent.z});
    return out;
}

ObserverFrame frameOf(const Spread& s, const std::vector<glm::dvec3>& positions, const glm::dvec3& point) {
    const glm::dvec3 w = glm::inverse(s.edges) * (point - positions[s.nodes[0]]);
    return {s.nodes, {1.0 - w.x - w.y - w.z, w.x, w.y, w.z}};
}

} // namespace

ObserverFrame observerFrame(const std::vector<glm::dvec3>& positions, const glm::dvec3& point) {
    if (positions.size() < 4) throw std::invalid_argument("an observer frame needs four nodes");
    // Nearest nodes first (ties: the lower index), so that the frame is local where it can be.
    std::vector<std::uint32_t> order(positions.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
        return glm::length(positions[i] - point) < glm::length(positions[j] - point);
    });
    for (std::size_t n = kLocalFrameNodes; n < positions.size(); n *= 2) {
        const Spread local = spread(positions, std::vector<std::uint32_t>(order.begin(), order.begin() + n));
        if (!(std::abs(local.volume6) > kLocalFrameShape * local.size * local.size * local.size)) continue;
        const ObserverFrame frame = frameOf(local, positions, point);
        if (std::all_of(frame.weights.begin(), frame.weights.end(),
                        [](double w) { return std::abs(w) <= kLocalFrameWeight; }))
            return frame;
    }
    const Spread all = spread(positions, order);
    if (!(std::abs(all.volume6) > 1e-6 * all.size * all.size * all.size))
        throw std::invalid_argument("the object's nodes span no volume: an observer cannot be tied to them");
    return frameOf(all, positions, point);
}

} // namespace glcollide::model
