#pragma once
// A stable GPU radix sort of (key, value) uint pairs in core GL 4.3 compute: least significant
// digit first, GLC_SORT_DIGIT_BITS bits per pass, each pass reduce-then-scan in three dispatches
// (radix_count, radix_scan, radix_scatter; docs/design/decisions/0017-gpu-linear-bvh.md). No
// subgroup operations, no decoupled look-back: nothing assumes that work groups run together.
// Tested against std::stable_sort (tests/gl/bvh_gl_test.cpp).

#include "gl/handles.hpp"
#include "gl/program.hpp"

#include <cstdint>
#include <vector>

namespace glcollide::passes {

class RadixSort {
  public:
    /// Room for `capacity` pairs (>= 1).
    explicit RadixSort(std::uint32_t capacity);

    /// The pairs to sort, and after sort() the sorted pairs: keys() and values() hold `count`
    /// entries. Fill them (a kernel bound to GLC_BIND_SORT_KEYS_OUT / GLC_BIND_SORT_VALUES_OUT,
    /// see bindForWriting) before sort().
    [[nodiscard]] const gl::Buffer& keys() const { return m_keys[0]; }
    [[nodiscard]] const gl::Buffer& values() const { return m_values[0]; }
    /// Uploads pairs from the host (tests); throws when they exceed the capacity.
    void load(const std::vector<std::uint32_t>& keys, const std::vector<std::uint32_t>& values);
    /// Binds keys()/values() as the output of the kernel that fills them.
    void bindForWriting() const;
    /// Binds keys()/values() as input (GLC_BIND_SORT_KEYS_IN / GLC_BIND_SORT_VALUES_IN), where
    /// the kernels that read the sorted pairs find them.
    void bindForReading() const;

    /// Sorts the first `count` pairs by the low `keyBits` bits of the key (higher bits must be
    /// 0), stably: equal keys keep their order. Ends with a storage barrier.
    void sort(std::uint32_t count, std::uint32_t keyBits) const;

    [[nodiscard]] std::uint32_t capacity() const { return m_capacity; }
    [[nodiscard]] std::vector<const gl::Buffer*> buffers() const {
        return {&m_keys[0], &m_values[0], &m_keys[1], &m_values[1], &m_blockCounts};
    }

  private:
    std::uint32_t m_capacity;
    gl::Buffer m_keys[2], m_values[2], m_blockCounts;
    gl::ComputeProgram m_count, m_scan, m_scatter;
};

} // namespace glcollide::passes
