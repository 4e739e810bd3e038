#pragma once
// TriTriQuery: a batch of independent triangle-triangle queries answered on the GPU in one
// dispatch with the narrow-phase test of shaders/common/tri_tri.glsl. Used by `glcollide query
// tritri`, the narrow-phase GL tests and the tri-tri benchmark.

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
    std::uint64_t exactFallbacks = 0;    ///< predicates robust decided exactly (0 for fast)
};

class TriTriQueryPass {
public:
    static constexpr const char* kName = "TriTriQuery";
    explicit TriTriQueryPass(TriTriPrecision precision);

    [[nodiscard]] TriTriPrecision precision() const { return m_precision; }

    /// Uploads `pairs`, dispatches one invocation per pair, waits and reads the answers back.
    /// Throws Error when the batch exceeds the device's shader storage block size.
    [[nodiscard]] TriTriQueryResult run(const std::vector<TriTriPair>& pairs) const;

    /// Dispatch only, on buffers already bound at GLC_BIND_QUERY_* (benchmarks: no transfers).
    void dispatch(std::uint32_t pairCount) const;

private:
    TriTriPrecision m_precision;
    gl::ComputeProgram m_program;
};

} // namespace glcollide::passes
