#pragma once
// NarrowPhaseBatch: a batch of independent triangle pairs answered by the collision pipeline's
// own narrow-phase kernels (robust: tri_tri_filtered, then tri_tri_exact over the undecided list),
// through the very NarrowPhase stages, append lists and stage chain an engine runs. Pair i becomes
// faces 2i and 2i+1 of a model of one-face objects (six nodes per pair), and the candidate list,
// filled by the host, holds exactly the pairs (2i, 2i+1): every pair is tested once, as the
// candidate a broad phase would append. The robust self-check runs its cases through this as well
// as through TriTriQueryPass, so that it checks the kernels engines run
// (docs/narrow-phase.md, "On-device self-check").

#include "passes/collision/append_lists.hpp"
#include "passes/collision/narrow_phase.hpp"
#include "passes/tri_tri_query_pass.hpp"

#include <vector>

namespace glcollide::passes {

class NarrowPhaseBatch {
  public:
    static constexpr const char* kName = "TriTri (batch)";
    /// Builds every program it runs (the narrow phase's and the lists' dispatcher), so that a
    /// caller's setup sink sees them all here.
    explicit NarrowPhaseBatch(TriTriPrecision precision) : m_narrowPhase(precision), m_lists(0) {}
    /// Test hook: see NarrowPhase(filtered, exact).
    explicit NarrowPhaseBatch(NarrowPhase narrowPhase) : m_narrowPhase(std::move(narrowPhase)), m_lists(0) {}

    /// Uploads the pairs as a model, runs the narrow phase's stages over them, waits and reads
    /// the intersection list back. Throws Error when the exact pass could not finish a pair
    /// (NarrowPhase::throwIfExactPassFailed) or a buffer exceeds the device's limits.
    [[nodiscard]] TriTriQueryResult run(const std::vector<TriTriPair>& pairs);

  private:
    NarrowPhase m_narrowPhase;
    AppendLists m_lists; ///< declared afresh, with the batch's capacities, by every run()
};

} // namespace glcollide::passes
