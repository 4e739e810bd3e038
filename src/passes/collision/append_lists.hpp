#pragma once
// The collision pipeline's append lists (GLC_LIST_* of shaders/common/layout.glsl), written once
// for every stage that produces or consumes one: each list is a storage buffer, a capacity and an
// exact count, all counters live in one GpuCollisionCounters array read back with one download.
// A writer appends with GLC_APPEND (shaders/common/lists.glsl), so the count is exact even when
// the list is full; grow() then makes room and the stage chain reruns the writer: nothing is dropped.

#include "gl/handles.hpp"
#include "core/gpu_layout.hpp"
#include "gl/program.hpp"

#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace glcollide::passes {

/// One statistic of GpuCollisionCounters.stats (GLC_STAT_* of layout.glsl): the one table its
/// name, reset value and owner come from (collisionStat).
struct CollisionStatSpec {
    const char* name = "";        ///< snake_case, as in --stats JSON
    std::uint32_t resetValue = 0; ///< what it starts from (bits of +inf for a minimum of floats)
    /// Reset by the stage that writes it, each time that stage runs (resetStats), and kept by the
    /// chain's resets, so a rerun of later stages alone does not lose it. Otherwise reset with
    /// the list counts when detect() starts.
    bool ownedByStage = false;
};
[[nodiscard]] const CollisionStatSpec& collisionStat(std::uint32_t id);

/// What a list holds and where the kernels find it.
struct ListSpec {
    const char* label = "";     ///< buffer label; names the list in errors
    const char* itemNoun = "";  ///< "pairs", "indices": errors say "needs N <noun>"
    std::size_t itemBytes = 0;  ///< 8 for uvec2 pairs, 4 for uint indices
    std::uint32_t binding = 0;  ///< GLC_BIND_* storage binding
    std::uint32_t capacity = 1; ///< first capacity, >= 1
    /// A list whose items are a subset of another list's entries (the undecided candidate
    /// indices) keeps that list's capacity, so it never overflows on its own; -1: none.
    int capacityOf = -1;
};

class AppendLists {
  public:
    /// The counter and indirect-argument buffers; no list is declared yet. `byteLimit`: bytes one
    /// list may grow to (a list is bound whole as one shader storage block); 0 = the device's
    /// GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
    explicit AppendLists(std::uint64_t byteLimit);

    void declare(std::uint32_t list, const ListSpec& spec);
    /// Stores `count` items (count * itemBytes bytes at `items`, count <= capacity) as the whole
    /// of `list` and sets its count: a list the host fills instead of a stage (the candidates of
    /// NarrowPhaseBatch). A chain that does not write the list keeps it.
    void fillFromHost(std::uint32_t list, const void* items, std::uint32_t count);
    [[nodiscard]] bool declared(std::uint32_t list) const {
        return static_cast<bool>(m_lists.at(list).storage);
    }
    [[nodiscard]] const gl::Buffer& storage(std::uint32_t list) const { return m_lists.at(list).storage; }
    [[nodiscard]] std::uint32_t capacity(std::uint32_t list) const { return m_lists.at(list).capacity; }
    /// Exact count at the last readCounters() (may exceed the capacity: the list overflowed).
    [[nodiscard]] std::uint32_t count(std::uint32_t list) const { return m_lists.at(list).count; }
    [[nodiscard]] std::uint32_t storedCount(std::uint32_t list) const;
    [[nodiscard]] bool overflowed(std::uint32_t list) const { return count(list) > capacity(list); }
    /// Times grow() ran on the list since the last resetGrowths().
    [[nodiscard]] std::uint32_t growths(std::uint32_t list) const { return m_lists.at(list).growths; }
    /// Statistic `id` (GLC_STAT_*) at the last readCounters().
    [[nodiscard]] std::uint32_t stat(std::uint32_t id) const { return m_stats.stats[id]; }
    [[nodiscard]] const gl::Buffer& counters() const { return m_counters; }

    /// Binds the counters, the indirect arguments and every declared list to their bindings.
    void bind() const;
    /// Zeroes the counts of `lists` and resets the statistics no stage owns (collisionStat),
    /// keeping the other counts, in one upload of the counter block.
    void resetCounts(const std::vector<std::uint32_t>& lists);
    /// Zeroes the counts of `lists` on the GPU and here, and nothing else (a stage that runs
    /// outside the chain and rewrites its own lists).
    void zeroCounts(std::initializer_list<std::uint32_t> lists);
    void resetGrowths();
    /// Resets the statistics `ids` on the GPU to their reset values: the stage that owns them,
    /// each time it runs.
    void resetStats(std::initializer_list<std::uint32_t> ids);
    /// One download of every counter.
    void readCounters();
    /// Reallocates an overflowed list with room for its exact count (the next power of two when
    /// it fits), and the lists that keep its capacity; throws glcollide::Error, naming the list,
    /// when that would exceed the byte limit. The new capacity reaches the GPU with the next
    /// resetCounts(), the new storage with the next bind().
    void grow(std::uint32_t list);
    /// Writes the indirect arguments of `list` on the GPU (list_dispatch_args.comp: groups of
    /// `itemsPerGroup` entries, `zGroups` in z) and dispatches `program` with them.
    void dispatchOver(const gl::ComputeProgram& program, std::uint32_t list, std::uint32_t itemsPerGroup,
                      std::uint32_t zGroups = 1) const;
    /// Dispatches `program` with the indirect arguments the last dispatchOver() of `list` wrote: for
    /// a pass that runs several kernels over a list whose count has not changed since (ContactImpact's
    /// rounds), one dispatch instead of two.
    void dispatchAgainOver(const gl::ComputeProgram& program, std::uint32_t list) const;

    /// The buffers allocated here, for Engine::allocatedBuffers().
    [[nodiscard]] std::vector<const gl::Buffer*> buffers() const;

  private:
    struct List {
        ListSpec spec;
        gl::Buffer storage;
        std::uint32_t capacity = 0, count = 0, growths = 0;
    };
    void writeCounters();

    std::uint64_t m_byteLimit;
    std::array<List, GLC_LIST_COUNT> m_lists;
    gl::Buffer m_counters, m_dispatchArgs;
    gl::ComputeProgram m_argsProgram;
    gpu::GpuCollisionCounters m_stats{}; ///< the counter block at the last readCounters()
};

} // namespace glcollide::passes
