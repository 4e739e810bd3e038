#include "passes/broad_phase/create_broad_phase.hpp"

#include "passes/broad_phase/all_pairs_broad_phase.hpp"
#include "passes/broad_phase/bvh_broad_phase.hpp"
#include "passes/broad_phase/masked_broad_phase.hpp"
#include "passes/broad_phase/octree_broad_phase.hpp"

#include <glcollide/error.hpp>

namespace glcollide::passes {
namespace {
template <typename T> std::vector<PassId> passesOf() {
    return {T::kPasses.begin(), T::kPasses.end()};
}
} // namespace

std::vector<PassId> broadPhasePasses(glcollide::BroadPhase kind) {
    switch (kind) {
    case glcollide::BroadPhase::Octree:
        return passesOf<OctreeBroadPhase>();
    case glcollide::BroadPhase::Masked:
        return passesOf<MaskedBroadPhase>();
    case glcollide::BroadPhase::AllPairs:
        return passesOf<AllPairsBroadPhase>();
    case glcollide::BroadPhase::Bvh:
        return passesOf<BvhBroadPhase>();
    }
    throw Error("unknown broad phase");
}

std::unique_ptr<BroadPhase> createBroadPhase(const BroadPhaseContext& context) {
    switch (context.settings.broadPhase) {
    case glcollide::BroadPhase::Octree:
        return std::make_unique<OctreeBroadPhase>(context);
    case glcollide::BroadPhase::Masked:
        return std::make_unique<MaskedBroadPhase>(context);
    case glcollide::BroadPhase::AllPairs:
        return std::make_unique<AllPairsBroadPhase>(context);
    case glcollide::BroadPhase::Bvh:
        return std::make_unique<BvhBroadPhase>(context);
    }
    throw Error("unknown broad phase");
}

} // namespace glcollide::passes
