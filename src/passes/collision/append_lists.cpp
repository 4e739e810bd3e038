#include "passes/collision/append_lists.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <string>

namespace glcollide::passes {
namespace {
constexpr std::uint32_t kPlusInfinityBits = 0x7F800000u;

// GLC_STAT_* in order: the one id -> name table of the collision statistics.
constexpr std::array<CollisionStatSpec, GLC_STAT_COUNT> kCollisionStats = {{
    {"exact_fallbacks", 0u, false},
    {"contacts", 0u, false},
    {"bvh_unfinished", 0u, true},
    {"bvh_node_visits", 0u, true},
    {"exact_errors", 0u, false},
    {"ccd_vertex_face_hits", 0u, true},
    {"ccd_edge_edge_hits", 0u, true},
    {"ccd_capped", 0u, true},
    {"ccd_boxes", 0u, true},
    {"ccd_earliest_toi", kPlusInfinityBits, true},
    {"safe_step_cuts", 0u, false},
    {"safe_step_ground_crossings", 0u, false},
    {"ccd_tangled", 0u, true},
    {"radial_culled_tri_tri", 0u, true},
    {"radial_culled_ccd", 0u, true},
    {"radial_non_positive", 0u, true},
    {"radial_free", 0u, true},
}};
constexpr std::size_t kArgsPerList = 3 * sizeof(std::uint32_t); // glDispatchComputeIndirect's x, y, z
} // namespace

const CollisionStatSpec& collisionStat(std::uint32_t id) {
    return kCollisionStats.at(id);
}

namespace {
std::uint64_t deviceListByteLimit() {
    GLint64 limit = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limit);
    return static_cast<std::uint64_t>(std::max<GLint64>(limit, GLint64{1} << 24)); // 2^24: GL 4.3's minimum
}
} // namespace

AppendLists::AppendLists(std::uint64_t byteLimit)
    : m_byteLimit(byteLimit != 0 ? byteLimit : deviceListByteLimit()),
      m_counters("collisionCounters", sizeof(gpu::GpuCollisionCounters)),
      m_dispatchArgs("dispatchArgs", GLC_LIST_COUNT * kArgsPerList), m_argsProgram("list_dispatch_args") {
    for (std::uint32_t id = 0; id < GLC_STAT_COUNT; ++id) m_stats.stats[id] = kCollisionStats[id].resetValue;
    writeCounters();
}

void AppendLists::declare(std::uint32_t list, const ListSpec& spec) {
    if (spec.capacity < 1)
        throw Error(std::string("collision list '") + spec.label + "': capacity must be at least 1");
    List& l = m_lists.at(list);
    l.spec = spec;
    l.capacity = spec.capacityOf >= 0 ? capacity(static_cast<std::uint32_t>(spec.capacityOf)) : spec.capacity;
    l.storage = gl::Buffer(spec.label, std::size_t{l.capacity} * spec.itemBytes);
    writeCounters();
}

void AppendLists::fillFromHost(std::uint32_t list, const void* items, std::uint32_t count) {
    List& l = m_lists.at(list);
    if (count > l.capacity)
        throw Error(std::string("collision list '") + l.spec.label + "': " + std::to_string(count) +
                    " items filled from the host, capacity " + std::to_string(l.capacity));
    if (count != 0) l.storage.upload(0, std::size_t{count} * l.spec.itemBytes, items);
    l.count = count;
    writeCounters();
}

std::uint32_t AppendLists::storedCount(std::uint32_t list) const {
    const List& l = m_lists.at(list);
    return l.count < l.capacity ? l.count : l.capacity;
}

void AppendLists::bind() const {
    m_counters.bindStorage(GLC_BIND_COLLISION_COUNTERS);
    m_dispatchArgs.bindStorage(GLC_BIND_DISPATCH_ARGS);
    for (const List& l : m_lists)
        if (l.storage) l.storage.bindStorage(l.spec.binding);
}

void AppendLists::writeCounters() {
    // The host holds an exact copy of every count (readCounters) and capacity, so the whole block
    // is written at once: one upload per reset, not one per field.
    gpu::GpuCollisionCounters c{};
    for (std::size_t i = 0; i < m_lists.size(); ++i) c.lists[i] = {m_lists[i].count, m_lists[i].capacity};
    for (std::uint32_t id = 0; id < GLC_STAT_COUNT; ++id)
        c.stats[id] = kCollisionStats[id].ownedByStage ? m_stats.stats[id] : kCollisionStats[id].resetValue;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after earlier shader writes to the counters
    m_counters.upload(0, sizeof c, &c);
}

void AppendLists::resetCounts(const std::vector<std::uint32_t>& lists) {
    for (std::uint32_t list : lists) m_lists.at(list).count = 0;
    writeCounters();
}

void AppendLists::zeroCounts(std::initializer_list<std::uint32_t> lists) {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after earlier shader writes to the counters
    const std::uint32_t zero = 0;
    for (std::uint32_t list : lists) {
        m_lists.at(list).count = 0;
        m_counters.upload(offsetof(gpu::GpuCollisionCounters, lists) + list * sizeof(gpu::GpuListCounter) +
                              offsetof(gpu::GpuListCounter, count),
                          sizeof zero, &zero);
    }
}

void AppendLists::resetGrowths() {
    for (List& l : m_lists) l.growths = 0;
}

void AppendLists::readCounters() {
    gpu::GpuCollisionCounters c{};
    m_counters.download(0, sizeof c, &c);
    for (std::size_t i = 0; i < m_lists.size(); ++i) m_lists[i].count = c.lists[i].count;
    m_stats = c;
}

void AppendLists::resetStats(std::initializer_list<std::uint32_t> ids) {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after earlier shader writes to the counters
    for (std::uint32_t id : ids) {
        m_stats.stats[id] = kCollisionStats.at(id).resetValue;
        m_counters.upload(offsetof(gpu::GpuCollisionCounters, stats) + id * sizeof(std::uint32_t),
                          sizeof(std::uint32_t), &m_stats.stats[id]);
    }
}

void AppendLists::grow(std::uint32_t list) {
    List& l = m_lists.at(list);
    ++l.growths;
    const std::uint32_t count = l.count;
    const std::uint64_t maxEntries = m_byteLimit / l.spec.itemBytes;
    // A list is bound whole as one shader storage block: past the limit the items cannot be
    // stored, and dropping them silently is not an option.
    if (count > maxEntries)
        throw Error(std::string("collision list '") + l.spec.label + "' needs " + std::to_string(count) +
                    " " + l.spec.itemNoun + " (" + std::to_string(std::uint64_t{count} * l.spec.itemBytes) +
                    " bytes), more than one shader storage block can hold on this device "
                    "(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, " +
                    std::to_string(m_byteLimit) +
                    " bytes); no pair was dropped: use fewer or smaller bodies, a smaller thickness or a "
                    "deeper octree");
    // Next power of two (fewer regrowths) when it fits; 2^31 and up: exact size.
    std::uint32_t capacity = count <= (1u << 31) ? std::bit_ceil(count) : count;
    if (capacity > maxEntries) capacity = count;
    l.capacity = capacity;
    l.storage = gl::Buffer(l.spec.label, std::size_t{capacity} * l.spec.itemBytes);
    for (List& follower : m_lists)
        if (follower.storage && follower.spec.capacityOf == static_cast<int>(list) &&
            follower.capacity < capacity) {
            follower.capacity = capacity;
            follower.storage =
                gl::Buffer(follower.spec.label, std::size_t{capacity} * follower.spec.itemBytes);
        }
    // The chain resets the counts (writeCounters) and binds the new storage before it reruns.
}

void AppendLists::dispatchOver(const gl::ComputeProgram& program, std::uint32_t list,
                               std::uint32_t itemsPerGroup, std::uint32_t zGroups) const {
    m_argsProgram.use();
    m_argsProgram.set("u_list", list);
    m_argsProgram.set("u_itemsPerGroup", itemsPerGroup);
    m_argsProgram.set("u_zGroups", zGroups);
    gl::ComputeProgram::dispatch(1, 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
    program.use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, m_dispatchArgs.name());
    gl::ComputeProgram::dispatchIndirect(static_cast<std::intptr_t>(list * kArgsPerList));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void AppendLists::dispatchAgainOver(const gl::ComputeProgram& program, std::uint32_t list) const {
    program.use();
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, m_dispatchArgs.name());
    gl::ComputeProgram::dispatchIndirect(static_cast<std::intptr_t>(list * kArgsPerList));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

std::vector<const gl::Buffer*> AppendLists::buffers() const {
    std::vector<const gl::Buffer*> b;
    for (const List& l : m_lists)
        if (l.storage) b.push_back(&l.storage);
    b.push_back(&m_counters);
    b.push_back(&m_dispatchArgs);
    return b;
}

} // namespace glcollide::passes
