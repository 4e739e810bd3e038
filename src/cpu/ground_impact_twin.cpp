#include "cpu/ground_impact_twin.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace glcollide::cpu {

std::size_t groundImpact(const GroundImpactParams& params, const GroundImpactInput& in,
                         std::vector<glm::vec3>& velocity) {
    const auto bandTop = static_cast<float>(params.bandTop);
    const auto gravityY = static_cast<float>(params.gravityY);
    const auto restitution = static_cast<float>(params.restitution);
    const auto friction = static_cast<float>(params.friction);
    const auto restingSpeed = static_cast<float>(params.restingSpeed);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < velocity.size(); ++i) {
        if (in.inverseMass[i] <= 0.0f) continue; // pinned
        const float y0 = in.start[i].y;
        const float y1 = in.end[i].y;
        if (!(y0 > bandTop && y1 <= bandTop)) continue; // not come down into the band this substep
        const float v0y = in.startVelocity[i].y;
        if (!(v0y < 0.0f || gravityY < 0.0f)) continue;
        const float impactSpeed = std::sqrt(std::max(v0y * v0y - 2.0f * gravityY * (y0 - bandTop), 0.0f));
        if (!(impactSpeed > restingSpeed)) continue;
        glm::vec3& v = velocity[i];
        if (!(v.y < restitution * impactSpeed)) continue; // already leaving faster
        // The ground's response (common/ground_response.glsl) to the velocity it hit the ground with.
        v.y = restitution * impactSpeed;
        const float tangentialSpeed = std::sqrt(v.x * v.x + v.z * v.z);
        if (tangentialSpeed > 0.0f) {
            const float scale =
                std::max(0.0f, 1.0f - friction * (1.0f + restitution) * impactSpeed / tangentialSpeed);
            v.x *= scale;
            v.z *= scale;
        }
        ++changed;
    }
    return changed;
}

} // namespace glcollide::cpu
