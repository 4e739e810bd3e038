#pragma once
// Test access to an AppendLists' GPU side: writing into the buffers a test holds only by const
// reference (the list storage and the counters belong to AppendLists) and reading a list back in
// order, for the GL tests that fill a candidate list by hand and read the feature-pair lists
// (contact_response_gl_test.cpp, contact_impact_gl_test.cpp).

#include "core/gpu_layout.hpp"
#include "gl/handles.hpp"
#include "passes/collision/append_lists.hpp"

#include <epoxy/gl.h>

#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glcollide::test {

/// Writes `bytes` at `offset` of `buffer`.
inline void poke(const gl::Buffer& buffer, std::size_t offset, std::size_t bytes, const void* data) {
    glBindBuffer(GL_COPY_WRITE_BUFFER, buffer.name());
    glBufferSubData(GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                    data);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

/// Fills the declared candidate list with `pairs` (face pairs) and its count, as a broad phase leaves
/// it, and reads the counters back (the host's copy of the count, which the stage chain's resets keep).
inline void fillCandidates(passes::AppendLists& lists, const std::vector<glm::uvec2>& pairs) {
    const auto count = static_cast<std::uint32_t>(pairs.size());
    if (count != 0)
        poke(lists.storage(GLC_LIST_CANDIDATES), 0, pairs.size() * sizeof(glm::uvec2), pairs.data());
    poke(lists.counters(),
         offsetof(gpu::GpuCollisionCounters, lists) + GLC_LIST_CANDIDATES * sizeof(gpu::GpuListCounter) +
             offsetof(gpu::GpuListCounter, count),
         sizeof count, &count);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    lists.readCounters();
}

/// The stored entries of `list`, sorted.
inline std::vector<std::array<std::uint32_t, 2>> readList(const passes::AppendLists& lists,
                                                          std::uint32_t list) {
    std::vector<std::array<std::uint32_t, 2>> pairs(lists.storedCount(list));
    lists.storage(list).download(0, pairs.size() * sizeof pairs[0], pairs.data());
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

} // namespace glcollide::test
