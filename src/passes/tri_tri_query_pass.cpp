#include "passes/tri_tri_query_pass.hpp"

#include "gl/layout.hpp"

#include <glcollide/error.hpp>

#include <epoxy/gl.h>

#include <limits>
#include <string>

namespace glcollide::passes {

const char* toString(TriTriPrecision precision) { return precision == TriTriPrecision::Robust ? "robust" : "fast"; }

TriTriQueryPass::TriTriQueryPass(TriTriPrecision precision)
    : m_precision(precision),
      m_program("tri_tri_query", precision == TriTriPrecision::Robust ? std::vector<std::string>{"GLC_PRECISION_ROBUST"}
                                                                      : std::vector<std::string>{}) {}

void TriTriQueryPass::dispatch(std::uint32_t pairCount) const {
    m_program.use();
    m_program.set("u_pairCount", pairCount);
    m_program.dispatch1D(pairCount, GLC_WORKGROUP_SIZE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

TriTriQueryResult TriTriQueryPass::run(const std::vector<TriTriPair>& pairs) const {
    TriTriQueryResult result;
    if (pairs.empty()) return result;
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    const std::size_t inputBytes = pairs.size() * sizeof(TriTriPair);
    if (pairs.size() > std::numeric_limits<std::uint32_t>::max() / 18u ||
        (maxBlock > 0 && inputBytes > static_cast<std::size_t>(maxBlock)))
        throw Error(std::string(kName) + ": " + std::to_string(pairs.size()) + " pairs (" +
                    std::to_string(inputBytes) + " bytes) exceed the device's shader storage block size of " +
                    std::to_string(maxBlock) + " bytes; split the batch");
    const auto count = static_cast<std::uint32_t>(pairs.size());
    const gl::Buffer triangles("query_triangles", inputBytes, pairs.data());
    const gl::Buffer results("query_results", pairs.size() * sizeof(std::uint32_t));
    const std::uint32_t zero = 0;
    const gl::Buffer stats("query_stats", sizeof(std::uint32_t), &zero);
    triangles.bindStorage(GLC_BIND_QUERY_TRIANGLES);
    results.bindStorage(GLC_BIND_QUERY_RESULTS);
    stats.bindStorage(GLC_BIND_QUERY_STATS);
    dispatch(count);
    std::vector<std::uint32_t> answers(pairs.size());
    results.download(0, answers.size() * sizeof(std::uint32_t), answers.data());
    std::uint32_t fallbacks = 0;
    stats.download(0, sizeof(fallbacks), &fallbacks);
    result.intersect.reserve(answers.size());
    for (std::uint32_t a : answers) result.intersect.push_back(a != 0 ? 1 : 0);
    result.exactFallbacks = fallbacks;
    return result;
}

} // namespace glcollide::passes
