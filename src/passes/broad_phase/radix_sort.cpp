#include "passes/broad_phase/radix_sort.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <string>

namespace glcollide::passes {
namespace {

constexpr std::uint32_t kDigits = 1u << GLC_SORT_DIGIT_BITS;

std::uint32_t blocksFor(std::uint32_t count) {
    return (count + GLC_SORT_BLOCK - 1) / GLC_SORT_BLOCK;
}

std::size_t wordBytes(std::uint32_t words) {
    return std::size_t{words} * sizeof(std::uint32_t);
}

} // namespace

RadixSort::RadixSort(std::uint32_t capacity)
    : m_capacity(capacity), m_keys{gl::Buffer("sortKeys", wordBytes(capacity)),
                                   gl::Buffer("sortKeysSwap", wordBytes(capacity))},
      m_values{gl::Buffer("sortValues", wordBytes(capacity)),
               gl::Buffer("sortValuesSwap", wordBytes(capacity))},
      m_blockCounts("sortBlockCounts", wordBytes(kDigits * blocksFor(capacity))), m_count("radix_count"),
      m_scan("radix_scan"), m_scatter("radix_scatter") {
    // radix_scan.comp: one invocation scans at most 65535 entries (llvmpipe's loop limit).
    if (std::uint64_t{kDigits} * blocksFor(capacity) > std::uint64_t{65535} * GLC_SCAN_GROUP)
        throw Error("radix sort: " + std::to_string(capacity) + " keys are more than it supports (2^28)");
}

void RadixSort::load(const std::vector<std::uint32_t>& keys, const std::vector<std::uint32_t>& values) {
    if (keys.size() != values.size() || keys.size() > m_capacity)
        throw Error("radix sort: " + std::to_string(keys.size()) + " keys and " +
                    std::to_string(values.size()) + " values for a capacity of " +
                    std::to_string(m_capacity));
    m_keys[0].upload(0, wordBytes(static_cast<std::uint32_t>(keys.size())), keys.data());
    m_values[0].upload(0, wordBytes(static_cast<std::uint32_t>(values.size())), values.data());
}

void RadixSort::bindForWriting() const {
    m_keys[0].bindStorage(GLC_BIND_SORT_KEYS_OUT);
    m_values[0].bindStorage(GLC_BIND_SORT_VALUES_OUT);
}

void RadixSort::bindForReading() const {
    m_keys[0].bindStorage(GLC_BIND_SORT_KEYS_IN);
    m_values[0].bindStorage(GLC_BIND_SORT_VALUES_IN);
}

void RadixSort::sort(std::uint32_t count, std::uint32_t keyBits) const {
    if (count > m_capacity)
        throw Error("radix sort: " + std::to_string(count) + " keys exceed its capacity " +
                    std::to_string(m_capacity));
    if (count <= 1) return;
    const std::uint32_t blocks = blocksFor(count);
    // An even number of passes leaves the result where it started, in keys()/values().
    std::uint32_t passes = (keyBits + GLC_SORT_DIGIT_BITS - 1) / GLC_SORT_DIGIT_BITS;
    passes += passes % 2;
    for (const gl::ComputeProgram* p : {&m_count, &m_scatter}) {
        p->set("u_count", count);
        p->set("u_blocks", blocks);
    }
    m_scan.set("u_length", kDigits * blocks);
    m_blockCounts.bindStorage(GLC_BIND_SORT_BLOCK_COUNTS);
    for (std::uint32_t pass = 0; pass < passes; ++pass) {
        const std::uint32_t in = pass % 2, out = 1 - in;
        m_keys[in].bindStorage(GLC_BIND_SORT_KEYS_IN);
        m_values[in].bindStorage(GLC_BIND_SORT_VALUES_IN);
        m_keys[out].bindStorage(GLC_BIND_SORT_KEYS_OUT);
        m_values[out].bindStorage(GLC_BIND_SORT_VALUES_OUT);
        const std::uint32_t shift = pass * GLC_SORT_DIGIT_BITS;
        m_count.set("u_shift", shift);
        m_scatter.set("u_shift", shift);
        m_count.use();
        m_count.dispatch1D(blocks * GLC_SORT_BLOCK, GLC_SORT_BLOCK);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        m_scan.use();
        gl::ComputeProgram::dispatch(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        m_scatter.use();
        m_scatter.dispatch1D(blocks * GLC_SORT_BLOCK, GLC_SORT_BLOCK);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

} // namespace glcollide::passes
