#pragma once
// CPU twin of one SafeStep round (shaders/passes/safe_step.comp, decision 0024), in float like the
// shader: the per-object earliest time of impact (the nodes' times and the ground's crossings),
// then the cut of every node of such an object to x0 + (fraction·T)·(x1 − x0), its velocity the
// displacement over the substep.

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace glcollide::cpu {

struct SafeStepRoundInput {
    std::vector<glm::vec3> start;           ///< x0 per node
    std::vector<float> inverseMass;         ///< per node (kept in x1's w)
    std::vector<std::uint32_t> nodeToi;     ///< bits of the node's earliest time (0x7F800000: none)
    std::vector<std::uint32_t> objectFirst; ///< first node of each object, ascending, objectFirst[0] = 0
    float fraction = 0.8f;                  ///< 0: freeze
    bool everyNode = false;                 ///< the last resort: every moving node stays at x0
    bool ground = false;
    float groundHeight = 0.0f;
    float h = 0.0f; ///< s
};

struct SafeStepRoundResult {
    std::uint32_t cuts = 0;            ///< nodes whose step was cut (GLC_STAT_SAFE_STEP_CUTS)
    std::uint32_t groundCrossings = 0; ///< GLC_STAT_SAFE_STEP_GROUND
};

/// One round on `end` (x1, changed in place) and `velocity` (changed for the cut nodes).
SafeStepRoundResult safeStepRound(const SafeStepRoundInput& in, std::vector<glm::vec3>& end,
                                  std::vector<glm::vec3>& velocity);

} // namespace glcollide::cpu
