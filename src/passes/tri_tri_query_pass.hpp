#pragma once
// TriTriQuery: a batch of independent triangle-triangle queries answered on the GPU with the
// narrow-phase test: fast (shaders/common/tri_tri.glsl) in one dispatch, or robust in two — the
// filtered pass, then the exact pass over the pairs it left undecided
// (shaders/common/tri_tri_robust.glsl). Used by `glcollide query tritri`, the narrow-phase GL
// tests, the tri-tri benchmark and the robust self-check.

#include "gl/handles.hpp"
#include "gl/program.hpp"

#include <glcollide/scene.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::passes {

/// Narrow-phase precision, the scene setting's type (docs/narrow-phase.md): Fast = Moeller 1997
/// in float with an absolute coplanarity epsilon of 1e-6 (length^3); Robust = filtered exact
/// predicates, the answer of the rational oracle for every finite input.
using ::glcollide::TriTriPrecision;

/// "fast" or "robust".
const char* toString(TriTriPrecision precision);

/// One query: the corners a0 a1 a2 b0 b1 b2 as 18 floats (x, y, z each; any unit, finite).
using TriTriPair = std::array<float, 18>;

/// Answers of one batch.
struct TriTriQueryResult {
    std::vector<std::uint8_t> intersect; ///< 1 when the closed triangles share a point, else 0
    std::uint64_t exactFallbacks = 0;    ///< predicates the exact pass evaluated in integers (0 for fast)
    std::uint64_t undecidedPairs = 0;    ///< pairs the filtered pass left to the exact pass (0 for fast)
};

/// A batch on the device: the pairs, the answers, the exact-pass counters and the undecided list.
struct TriTriQueryBatch {
    std::uint32_t pairCount = 0;
    gl::Buffer triangles, results, stats, undecided;
};

class TriTriQueryPass {
  public:
    static constexpr const char* kName = "TriTriQuery";
    explicit TriTriQueryPass(TriTriPrecision precision);
    /// Test hook: robust precision with the given filtered and exact programs (e.g. an exact
    /// kernel built from modified source, tests/gl/tri_tri_gl_test.cpp).
    TriTriQueryPass(gl::ComputeProgram filtered, gl::ComputeProgram exact);

    [[nodiscard]] TriTriPrecision precision() const { return m_precision; }

    /// Uploads `pairs`, answers them, waits and reads the answers back. Throws Error when the
    /// batch exceeds the device's shader storage block size, or when the exact pass could not
    /// finish a pair (read()).
    [[nodiscard]] TriTriQueryResult run(const std::vector<TriTriPair>& pairs) const;

    /// The three steps of run(), for benchmarks that time dispatch() alone, any number of times.
    [[nodiscard]] TriTriQueryBatch upload(const std::vector<TriTriPair>& pairs) const;
    /// Resets the batch's counters, binds it and runs the pass(es); ends with a storage barrier.
    void dispatch(TriTriQueryBatch& batch) const;
    [[nodiscard]] TriTriQueryResult read(const TriTriQueryBatch& batch) const;

  private:
    TriTriPrecision m_precision;
    gl::ComputeProgram m_program;
    gl::ComputeProgram m_exact; ///< robust only: the exact pass over the undecided pairs
};

} // namespace glcollide::passes
