#include "cpu/safe_step_twin.hpp"

#include <algorithm>
#include <bit>

namespace glcollide::cpu {
namespace {
constexpr std::uint32_t kNoImpact = 0x7F800000u;

std::uint32_t objectOf(const std::vector<std::uint32_t>& first, std::uint32_t node) {
    return static_cast<std::uint32_t>(std::upper_bound(first.begin(), first.end(), node) - first.begin()) -
           1u;
}
} // namespace

SafeStepRoundResult safeStepRound(const SafeStepRoundInput& in, std::vector<glm::vec3>& end,
                                  std::vector<glm::vec3>& velocity) {
    SafeStepRoundResult result;
    const std::size_t nodes = in.start.size();
    // The objects' earliest times: a minimum, as the shader's atomicMin on the bits.
    std::vector<std::uint32_t> objectToi(in.objectFirst.size(), kNoImpact);
    for (std::uint32_t i = 0; i < nodes; ++i) {
        std::uint32_t toi = in.nodeToi[i];
        if (in.ground) {
            const float y0 = in.start[i].y, y1 = end[i].y;
            if (y0 >= in.groundHeight && y1 < in.groundHeight) {
                const float t = std::clamp((y0 - in.groundHeight) / (y0 - y1), 0.0f, 1.0f);
                toi = std::min(toi, std::bit_cast<std::uint32_t>(t));
                ++result.groundCrossings;
            }
        }
        std::uint32_t& o = objectToi[objectOf(in.objectFirst, i)];
        o = std::min(o, toi);
    }
    for (std::uint32_t i = 0; i < nodes; ++i) {
        const std::uint32_t toi = objectToi[objectOf(in.objectFirst, i)];
        if (toi == kNoImpact && !in.everyNode) continue;
        const glm::vec3 x0 = in.start[i], x1 = end[i];
        if (x0 == x1) continue;
        const float s = in.everyNode ? 0.0f : in.fraction * std::bit_cast<float>(toi);
        const glm::vec3 x = x0 + s * (x1 - x0);
        end[i] = x;
        velocity[i] = (x - x0) / in.h;
        ++result.cuts;
    }
    return result;
}

} // namespace glcollide::cpu
