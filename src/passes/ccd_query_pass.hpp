#pragma once
// CcdQueryPass: a batch of independent continuous-collision queries (vertex-face or edge-edge,
// linear motion over t in [0, 1]) answered on the GPU by the conservative float CCD of
// shaders/common/ccd.glsl, one invocation per query (shaders/passes/ccd_query.comp); queries that
// run out of budget continue on halves of their time interval, one dispatch per round
// (passes/ccd_continuation.hpp). Used by `glcollide query ccd`, the CCD GL tests and the CCD
// benchmark. C++ twin: cpu/ccd_library.hpp (the same GLSL compiled as C++), continued by the same
// host code; method and guarantees: docs/ccd.md, "glcollide query ccd". Inputs that are not floats
// (rationals, doubles) are rounded with their rounding covered by cpu::roundCcdQuery first.

#include "gl/program.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace glcollide::passes {

/// The most boxes one query may evaluate on llvmpipe: its shaders end an invocation after 65,535
/// loop iterations in all, and a query runs at most 2 * budget + 77 iterations (docs/ccd.md,
/// "Tolerances"; 21,844 even keeps 3 * budget + 1 below the limit). Other devices have no such
/// limit, and no forward-progress guarantee either.
inline constexpr int kMaxLlvmpipeCcdBudget = 21844;

/// Boxes a query may evaluate before it answers "may collide" with its lower bound of the time of
/// impact, counted as capped: the most llvmpipe allows, so the default runs everywhere.
inline constexpr int kDefaultCcdBudget = kMaxLlvmpipeCcdBudget;

/// Rounds in which capped queries continue on halves of their time interval (ccd_continuation.hpp):
/// a query capped in every round is split into at most 2^rounds pieces, each with its own budget.
inline constexpr int kDefaultCcdContinuationRounds = 4;

enum class CcdKind { VertexFace, EdgeEdge };

/// "vf" or "ee".
const char* toString(CcdKind kind);

/// One query: 4 points at t = 0, then the same 4 at t = 1 (the CCD benchmark's order).
/// Vertex-face: the vertex, then the triangle's corners; edge-edge: edge A's ends, then edge B's.
/// minSeparation >= 0: the answer is "may collide" when the primitives may come within it.
struct CcdQuery {
    std::array<glm::vec3, 8> points;
    float minSeparation = 0.0f;
};

/// One query's answer from one run of the float CCD (the kernel, or its C++ twin).
struct CcdAnswer {
    bool mayCollide = false;
    float toi = 1.0f;
    bool capped = false;
    std::uint32_t boxes = 0;
};

/// Answers of one batch, one entry per query in input order.
struct CcdQueryResult {
    std::vector<std::uint8_t> mayCollide;  ///< 1: may come within minSeparation in [0, 1]; 0: never do
    std::vector<float> toi;                ///< never later than the true earliest contact; 1 when 0
    std::uint32_t capped = 0;              ///< queries answered 1 only because pieces ran out of budget
    std::uint64_t boxes = 0;               ///< boxes evaluated, all queries and rounds together
    std::vector<std::uint8_t> cappedFlags; ///< 1 for each query counted in `capped`
    std::uint32_t continued = 0;           ///< queries capped in the first round, continued in halves
};

class CcdQueryPass {
  public:
    static constexpr const char* kName = "CcdQuery";
    /// `budget` >= 1 boxes per query and piece; at most kMaxLlvmpipeCcdBudget on llvmpipe (run()
    /// throws Error there otherwise, since a cut loop would answer "no contact"). `continuationRounds`
    /// >= 0: rounds in which capped queries continue on halves of their time interval (0: none).
    explicit CcdQueryPass(int budget = kDefaultCcdBudget,
                          int continuationRounds = kDefaultCcdContinuationRounds);
    /// Test hook: the programs of both kinds given (e.g. built from modified source).
    CcdQueryPass(gl::ComputeProgram vertexFace, gl::ComputeProgram edgeEdge, int budget = kDefaultCcdBudget,
                 int continuationRounds = kDefaultCcdContinuationRounds);

    [[nodiscard]] int budget() const { return m_budget; }
    [[nodiscard]] int continuationRounds() const { return m_rounds; }

    /// Builds the program of `kind` now (run() builds it on first use), e.g. to time run() alone.
    void prepare(CcdKind kind) const { (void)program(kind); }

    /// Uploads the queries, answers them (in chunks that fit the device's shader storage block
    /// size), continues the capped ones (answerWithContinuation), waits and reads the answers back.
    /// Throws Error for a negative or non-finite minimum separation or a budget the device cannot
    /// run.
    [[nodiscard]] CcdQueryResult run(CcdKind kind, const std::vector<CcdQuery>& queries) const;

  private:
    [[nodiscard]] const gl::ComputeProgram& program(CcdKind kind) const;
    /// One round on the device: the kernel's answer to each query, nothing continued.
    [[nodiscard]] std::vector<CcdAnswer> solve(CcdKind kind, const std::vector<CcdQuery>& queries) const;

    int m_budget;
    int m_rounds;
    /// Built on first use of each kind (a CLI run needs one).
    mutable std::optional<gl::ComputeProgram> m_vertexFace, m_edgeEdge;
};

} // namespace glcollide::passes
