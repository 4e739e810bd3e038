#pragma once
// The substep's collision stages in dispatch order, run with one read-back: each stage appends to
// lists (AppendLists) that later stages consume, sized on the GPU by indirect dispatch. After the
// chain the counters are read once; when a list overflowed, the earliest stage that wrote an
// overflowing list has its overflowed lists grown and the chain reruns from that stage (what it
// and later stages wrote depended on the lost entries). A stage may also ask to rerun when it ran
// out of its work budget (Stage::retry). Written once for every broad phase, the
// narrow phase and the lists a BVH or CCD will add.

#include "gl/gpu_timer.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/pass_id.hpp"

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace glcollide::passes {

struct Stage {
    Stage(PassId pass_, std::vector<std::uint32_t> outputs_, std::function<void()> run_,
          std::function<bool()> retry_ = {})
        : pass(pass_), outputs(std::move(outputs_)), run(std::move(run_)), retry(std::move(retry_)) {}

    PassId pass;                        ///< timer section and debug-group name (a pass may span stages)
    std::vector<std::uint32_t> outputs; ///< GLC_LIST_* it appends to
    std::function<void()> run;          ///< its dispatches; ends with the barriers its readers need
    /// Asked after the chain's read-back, when no earlier stage must rerun: true when the stage
    /// ran out of its work budget (the BVH traversal's rounds) and has arranged to do more; the
    /// chain then reruns from it, as from an overflow. Empty: never.
    std::function<bool()> retry;
};

class StageChain {
  public:
    void add(Stage stage) { m_stages.push_back(std::move(stage)); }
    /// The passes of the stages, each once, in order.
    [[nodiscard]] std::vector<PassId> passes() const;

    /// Resets the counts of every output (and the contact count), runs every stage, reads the
    /// counters, then grows and reruns until no list overflowed. Brackets each stage with
    /// `timer` (section passIndex(stage.pass)) when not null; a rerun adds to its pass's time.
    /// Returns the number of reruns. Throws glcollide::Error when a list cannot grow enough.
    std::uint32_t run(AppendLists& lists, gl::GpuTimer* timer) const;
    /// The outputs of the stages from `first` on, each once.
    [[nodiscard]] std::vector<std::uint32_t> outputsFrom(std::size_t first) const;

  private:
    void runFrom(std::size_t first, gl::GpuTimer* timer) const;

    std::vector<Stage> m_stages;
};

} // namespace glcollide::passes
