#include "passes/tri_tri_query_pass.hpp"

#include "core/gpu_layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <limits>
#include <string>
#include <utility>

namespace glcollide::passes {

const char* toString(TriTriPrecision precision) {
    return precision == TriTriPrecision::Robust ? "robust" : "fast";
}

TriTriQueryPass::TriTriQueryPass(TriTriPrecision precision) : m_precision(precision) {
    if (precision == TriTriPrecision::Robust) {
        m_program = gl::ComputeProgram("tri_tri_query_filtered");
        m_exact = gl::ComputeProgram("tri_tri_query_exact");
    } else {
        m_program = gl::ComputeProgram("tri_tri_query_fast");
    }
}

TriTriQueryPass::TriTriQueryPass(gl::ComputeProgram filtered, gl::ComputeProgram exact)
    : m_precision(TriTriPrecision::Robust), m_program(std::move(filtered)), m_exact(std::move(exact)) {}

TriTriQueryBatch TriTriQueryPass::upload(const std::vector<TriTriPair>& pairs) const {
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    const std::size_t inputBytes = pairs.size() * sizeof(TriTriPair);
    if (pairs.size() > std::numeric_limits<std::uint32_t>::max() / 18u ||
        (maxBlock > 0 && inputBytes > static_cast<std::size_t>(maxBlock)))
        throw Error(std::string(kName) + ": " + std::to_string(pairs.size()) + " pairs (" +
                    std::to_string(inputBytes) + " bytes) exceed the device's shader storage block size of " +
                    std::to_string(maxBlock) + " bytes; split the batch");
    TriTriQueryBatch b;
    b.pairCount = static_cast<std::uint32_t>(pairs.size());
    b.triangles = gl::Buffer("query_triangles", inputBytes, pairs.data());
    b.results = gl::Buffer("query_results", pairs.size() * sizeof(std::uint32_t));
    b.stats = gl::Buffer("query_stats", 3 * sizeof(std::uint32_t));
    if (m_precision == TriTriPrecision::Robust)
        b.undecided =
            gl::Buffer("query_undecided", pairs.size() * sizeof(std::uint32_t)); // at most every pair
    return b;
}

void TriTriQueryPass::dispatch(TriTriQueryBatch& b) const {
    if (b.pairCount == 0) return;
    const std::uint32_t zeros[3] = {0, 0, 0};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // after an earlier dispatch's writes to the counters
    b.stats.upload(0, sizeof zeros, zeros);
    b.triangles.bindStorage(GLC_BIND_QUERY_TRIANGLES);
    b.results.bindStorage(GLC_BIND_QUERY_RESULTS);
    b.stats.bindStorage(GLC_BIND_QUERY_STATS);
    if (b.undecided) b.undecided.bindStorage(GLC_BIND_UNDECIDED);
    m_program.use();
    m_program.set("u_pairCount", b.pairCount);
    m_program.dispatch1D(b.pairCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (m_exact.name() != 0) {
        // One read-back of the undecided count sizes the exact pass: its kernel is large, and
        // even invocations that return at once cost a software rasteriser its set-up.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::uint32_t undecided = 0;
        b.stats.download(sizeof(std::uint32_t), sizeof undecided, &undecided);
        m_exact.use();
        m_exact.dispatch1D(undecided, GLC_WORKGROUP_SIZE);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

TriTriQueryResult TriTriQueryPass::read(const TriTriQueryBatch& b) const {
    TriTriQueryResult result;
    std::vector<std::uint32_t> answers(b.pairCount);
    if (b.pairCount == 0) return result;
    b.results.download(0, answers.size() * sizeof(std::uint32_t), answers.data());
    std::uint32_t stats[3] = {0, 0, 0};
    b.stats.download(0, sizeof stats, stats);
    if (stats[2] != 0)
        throw Error(
            std::string(kName) + ": the exact pass could not finish " + std::to_string(stats[2]) + " of " +
            std::to_string(b.pairCount) +
            " pairs (more signs to record than GLC_MAX_EXACT, or a predicate on a point that is not an "
            "input corner: a broken assumption of shaders/common/tri_tri_robust.glsl); no answer is "
            "returned");
    result.intersect.reserve(answers.size());
    for (std::uint32_t a : answers) result.intersect.push_back(a != 0 ? 1 : 0);
    result.exactFallbacks = stats[0];
    result.undecidedPairs = stats[1];
    return result;
}

TriTriQueryResult TriTriQueryPass::run(const std::vector<TriTriPair>& pairs) const {
    if (pairs.empty()) return {};
    TriTriQueryBatch batch = upload(pairs);
    dispatch(batch);
    return read(batch);
}

} // namespace glcollide::passes
