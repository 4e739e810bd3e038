#include "passes/ccd_query_pass.hpp"

#include "passes/ccd_continuation.hpp"

#include "core/gpu_layout.hpp"
#include "gl/handles.hpp"

#include <glcollide/error.hpp>
#include <glcollide/gl_info.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

namespace glcollide::passes {
namespace {

constexpr std::size_t kFloatsPerQuery = 25; // 8 points xyz, then the minimum separation
constexpr std::size_t kUintsPerResult = 3;  // flags, time of impact bits, boxes
constexpr std::uint32_t kMayCollideBit = 1u, kCappedBit = 2u;

/// Queries per dispatch: as many as fit the device's shader storage block size (llvmpipe: 2^27
/// bytes, 1.3 million queries), so a batch of any size runs.
std::size_t queriesPerChunk() {
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    const std::size_t bytes = maxBlock > 0 ? static_cast<std::size_t>(maxBlock) : std::size_t(1) << 24;
    return std::max<std::size_t>(1, bytes / (kFloatsPerQuery * sizeof(float)));
}

void checkSeparations(const std::vector<CcdQuery>& queries) {
    for (std::size_t i = 0; i < queries.size(); ++i) {
        const float d = queries[i].minSeparation;
        if (!(d >= 0.0f) || std::isinf(d))
            throw Error(std::string(CcdQueryPass::kName) + ": query " + std::to_string(i) +
                        " has minimum separation " + std::to_string(d) + "; expected a finite value >= 0");
    }
}

/// A cut loop would end the search with boxes left and answer "no contact": refuse budgets a
/// software rasteriser's loop limit could cut (docs/ccd.md, "Tolerances").
void checkBudget(int budget) {
    if (budget < 1)
        throw Error(std::string(CcdQueryPass::kName) + ": budget " + std::to_string(budget) +
                    " boxes; expected at least 1");
    if (budget > kMaxLlvmpipeCcdBudget && queryGlInfo().isSoftware)
        throw Error(std::string(CcdQueryPass::kName) + ": budget " + std::to_string(budget) +
                    " boxes exceeds " + std::to_string(kMaxLlvmpipeCcdBudget) +
                    ", the most a software rasteriser runs (it ends an invocation after 65,535 loop "
                    "iterations, and a query needs up to 3 per box)");
}

} // namespace

const char* toString(CcdKind kind) {
    return kind == CcdKind::EdgeEdge ? "ee" : "vf";
}

CcdQueryPass::CcdQueryPass(int budget, int continuationRounds)
    : m_budget(budget), m_rounds(continuationRounds) {}

CcdQueryPass::CcdQueryPass(gl::ComputeProgram vertexFace, gl::ComputeProgram edgeEdge, int budget,
                           int continuationRounds)
    : m_budget(budget), m_rounds(continuationRounds), m_vertexFace(std::move(vertexFace)),
      m_edgeEdge(std::move(edgeEdge)) {}

const gl::ComputeProgram& CcdQueryPass::program(CcdKind kind) const {
    if (kind == CcdKind::EdgeEdge) {
        if (!m_edgeEdge) m_edgeEdge.emplace("ccd_query", std::vector<std::string>{"GLC_CCD_EDGE_EDGE"});
        return *m_edgeEdge;
    }
    if (!m_vertexFace) m_vertexFace.emplace("ccd_query");
    return *m_vertexFace;
}

std::vector<CcdAnswer> CcdQueryPass::solve(CcdKind kind, const std::vector<CcdQuery>& queries) const {
    std::vector<CcdAnswer> answers;
    if (queries.empty()) return answers;
    answers.reserve(queries.size());
    const gl::ComputeProgram& kernel = program(kind);
    const std::size_t chunk = std::min(queries.size(), queriesPerChunk());
    gl::Buffer input("ccd_queries", chunk * kFloatsPerQuery * sizeof(float));
    gl::Buffer output("ccd_results", chunk * kUintsPerResult * sizeof(std::uint32_t));
    std::vector<float> packed(chunk * kFloatsPerQuery);
    std::vector<std::uint32_t> raw(chunk * kUintsPerResult);
    kernel.set("u_budget", static_cast<std::uint32_t>(m_budget));
    for (std::size_t first = 0; first < queries.size(); first += chunk) {
        const std::size_t count = std::min(chunk, queries.size() - first);
        for (std::size_t i = 0; i < count; ++i) {
            const CcdQuery& q = queries[first + i];
            float* out = packed.data() + i * kFloatsPerQuery;
            for (std::size_t p = 0; p < 8; ++p)
                for (int k = 0; k < 3; ++k) out[3 * p + static_cast<std::size_t>(k)] = q.points[p][k];
            out[24] = q.minSeparation;
        }
        input.upload(0, count * kFloatsPerQuery * sizeof(float), packed.data());
        input.bindStorage(GLC_BIND_CCD_QUERIES);
        output.bindStorage(GLC_BIND_CCD_RESULTS);
        kernel.use();
        kernel.set("u_queryCount", static_cast<std::uint32_t>(count));
        kernel.dispatch1D(static_cast<std::uint32_t>(count), GLC_WORKGROUP_SIZE);
        output.download(0, count * kUintsPerResult * sizeof(std::uint32_t), raw.data()); // barrier included
        for (std::size_t i = 0; i < count; ++i) {
            const std::uint32_t flags = raw[kUintsPerResult * i];
            CcdAnswer a;
            std::memcpy(&a.toi, &raw[kUintsPerResult * i + 1], sizeof a.toi);
            a.mayCollide = (flags & kMayCollideBit) != 0;
            a.capped = (flags & kCappedBit) != 0;
            a.boxes = raw[kUintsPerResult * i + 2];
            answers.push_back(a);
        }
    }
    return answers;
}

CcdQueryResult CcdQueryPass::run(CcdKind kind, const std::vector<CcdQuery>& queries) const {
    checkBudget(m_budget);
    checkSeparations(queries);
    if (m_rounds < 0)
        throw Error(std::string(kName) + ": " + std::to_string(m_rounds) +
                    " continuation rounds; expected >= 0");
    return answerWithContinuation(
        queries, [&](const std::vector<CcdQuery>& batch) { return solve(kind, batch); }, m_rounds);
}

} // namespace glcollide::passes
