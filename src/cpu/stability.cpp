#include "cpu/stability.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>

namespace glcollide::cpu {

StabilityLimit stableSubstep(const model::FlatModel& model, bool springs, const NodeForceParams& forces,
                             double safety, const ContactParams* contacts) {
    StabilityLimit limit;
    limit.maxSubstep = std::numeric_limits<double>::infinity();
    for (std::uint32_t i = 0; i < model.nodeCount(); ++i) {
        const double w = model.inverseMasses[i];
        if (w <= 0.0) continue;
        double stiffness = 0.0, springDamping = 0.0;
        if (springs)
            for (std::uint32_t k = model.nodeSprings.offsets[i]; k < model.nodeSprings.offsets[i + 1]; ++k) {
                stiffness += model.springs[model.nodeSprings.items[k]].stiffness;
                springDamping += model.springs[model.nodeSprings.items[k]].damping;
            }
        if (contacts) {
            stiffness += kContactsPerNodeForStability * contacts->stiffness;
            springDamping += kContactsPerNodeForStability * contacts->damping;
        }
        double gamma = 2.0 * w * springDamping;
        if (forces.damping) gamma += forces.dampingCoefficient;
        if (forces.wind) {
            // The wind force on a node is linear in its velocity with rate ≤ drag·(area/3)/3 per face.
            double area = 0.0;
            for (std::uint32_t k = model.nodeFaces.offsets[i]; k < model.nodeFaces.offsets[i + 1]; ++k) {
                const std::uint32_t f = model.nodeFaces.items[k];
                const glm::dvec3 a = model.positions[model.faceIndices[3 * f]];
                const glm::dvec3 b = model.positions[model.faceIndices[3 * f + 1]];
                const glm::dvec3 c = model.positions[model.faceIndices[3 * f + 2]];
                area += 0.5 * glm::length(glm::cross(b - a, c - a));
            }
            gamma += w * forces.windDrag * area / 3.0;
        }
        const double omega2 = 2.0 * w * stiffness;
        double h = std::numeric_limits<double>::infinity();
        if (omega2 > 0.0)
            h = (-gamma + std::sqrt(gamma * gamma + 4.0 * omega2)) / omega2;
        else if (gamma > 0.0)
            h = 2.0 / gamma;
        h *= safety;
        if (h < limit.maxSubstep) {
            limit.maxSubstep = h;
            limit.node = i;
            limit.omega = std::sqrt(omega2);
            limit.gamma = gamma;
        }
    }
    return limit;
}

int substepsFor(double dt, const StabilityLimit& limit) {
    if (!std::isfinite(limit.maxSubstep) || limit.maxSubstep >= dt) return 1;
    const double n = std::ceil(dt / limit.maxSubstep);
    return n > kMaxSubsteps ? kMaxSubsteps + 1 : static_cast<int>(n);
}

} // namespace glcollide::cpu
