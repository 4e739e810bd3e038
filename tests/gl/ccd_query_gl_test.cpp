// The CCD query pass on the GPU (shaders/passes/ccd_query.comp through passes::CcdQueryPass):
//  - against its C++ twin (shaders/common/ccd.glsl compiled as C++, cpu/ccd_library.hpp, same
//    budget) on the CCD benchmark's handcrafted queries (tests/data/external/ccd-sample-queries)
//    rounded to float with the rounding covered (cpu/oracle/ccd_rounding.hpp): the same answer and
//    capped flag for every query. Times of impact are compared bit for bit and their differences
//    counted, not failed: ccd.glsl has no `precise`, so a GLSL compiler may evaluate its float
//    expressions in another order (Mesa fuses x0 + t (x1 - x0) and a - u b into lerps and FMAs),
//    which keeps every guarantee but can change the search path and with it the lower bound
//    reported. Every time of impact is checked against the exact oracle instead: never later than
//    the original rationals' earliest contact. And no ground-truth contact is missed;
//  - its answers do not change when every coordinate and the separation are scaled by 2^k;
//  - the rounding cover, not the error bound's slack, keeps a rounded touching query found: with
//    the kernel's rounding-error bound removed (a copy of its source with N = 0), a query that
//    touches in rationals and whose rounded float query does not touch (the exact oracle decides
//    both) is found with the cover and missed without it.

#include "cpu/ccd_library.hpp"
#include "cpu/oracle/ccd_query_csv.hpp"
#include "cpu/oracle/ccd_rounding.hpp"
#include "cpu/oracle/exact_ccd.hpp"
#include "gl/program.hpp"
#include "passes/ccd_continuation.hpp"
#include "passes/ccd_query_pass.hpp"

#include <glcollide/error.hpp>
#include <glcollide/gl_info.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace glcollide {
namespace {

using passes::CcdKind;
using passes::CcdQuery;
using passes::CcdQueryPass;
using passes::CcdQueryResult;

struct SampleSet {
    std::vector<CcdQuery> queries;            // rounded to float, the rounding covered
    std::vector<cpu::RationalCcdQuery> exact; // as read
    std::vector<bool> truth;                  // of the original rationals
};

/// Every Sample-Queries query of one kind, files in sorted order (deterministic).
SampleSet sampleQueries(CcdKind kind) {
    const auto root = std::filesystem::path(GLCOLLIDE_TEST_DATA_DIR) / "external" / "ccd-sample-queries";
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
        if (entry.path().extension() == ".csv" &&
            entry.path().parent_path().filename() ==
                (kind == CcdKind::VertexFace ? "vertex-face" : "edge-edge"))
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    SampleSet set;
    for (const auto& file : files)
        for (const cpu::SampleCcdQuery& sample : cpu::readSampleCcdQueries(file.string())) {
            const cpu::RoundedCcdQuery r = cpu::roundCcdQuery(sample.points, 0);
            set.queries.push_back({r.points, r.minSeparation});
            set.exact.push_back(sample.points);
            set.truth.push_back(sample.truth);
        }
    return set;
}

/// The C++ twin as a solver: the same functions, one call per query.
passes::CcdSolver twinSolver(CcdKind kind, int budget) {
    return [kind, budget](const std::vector<CcdQuery>& queries) {
        std::vector<passes::CcdAnswer> answers;
        for (const CcdQuery& q : queries) {
            const auto& p = q.points;
            const bool hit = kind == CcdKind::VertexFace
                                 ? shader::glcVertexFaceCcd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7],
                                                            q.minSeparation, budget)
                                 : shader::glcEdgeEdgeCcd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7],
                                                          q.minSeparation, budget);
            answers.push_back({hit, shader::glcCcdToi, shader::glcCcdCapped,
                               static_cast<std::uint32_t>(shader::glcCcdBoxes)});
        }
        return answers;
    };
}

std::uint32_t bits(float f) {
    std::uint32_t b = 0;
    std::memcpy(&b, &f, sizeof b);
    return b;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Every Sample-Queries query of `kind` on the GPU and through the twin (see the top of the file).
void expectGpuAgreesWithTwinOnSampleQueries(CcdKind kind, std::size_t expectedQueries) {
    const SampleSet set = sampleQueries(kind);
    ASSERT_EQ(set.queries.size(), expectedQueries);
    const CcdQueryPass pass; // the default budget
    pass.prepare(kind);      // compiled outside the timing
    auto start = std::chrono::steady_clock::now();
    const CcdQueryResult gpu = pass.run(kind, set.queries);
    const double gpuSeconds = secondsSince(start);
    start = std::chrono::steady_clock::now();
    // The twin continues capped queries the same way (passes/ccd_continuation.hpp).
    const CcdQueryResult cpu = passes::answerWithContinuation(set.queries, twinSolver(kind, pass.budget()),
                                                              pass.continuationRounds());
    const double twinSeconds = secondsSince(start);
    ASSERT_EQ(gpu.mayCollide.size(), set.queries.size());
    int answerDifferences = 0, toiDifferences = 0, lateTimes = 0, falseNegatives = 0, falsePositives = 0;
    int capped = 0;
    for (std::size_t i = 0; i < set.queries.size(); ++i) {
        if ((gpu.mayCollide[i] != cpu.mayCollide[i] || gpu.cappedFlags[i] != cpu.cappedFlags[i]) &&
            ++answerDifferences <= 10)
            ADD_FAILURE() << "query " << i << ": GPU (" << int(gpu.mayCollide[i]) << ", capped "
                          << int(gpu.cappedFlags[i]) << ") != twin (" << int(cpu.mayCollide[i]) << ", capped "
                          << int(cpu.cappedFlags[i]) << ")";
        toiDifferences += bits(gpu.toi[i]) != bits(cpu.toi[i]);
        falseNegatives += set.truth[i] && gpu.mayCollide[i] == 0;
        falsePositives += !set.truth[i] && gpu.mayCollide[i] != 0;
        capped += gpu.cappedFlags[i];
        if (set.truth[i]) {
            const cpu::ExactCcdResult exact = kind == CcdKind::VertexFace
                                                  ? cpu::exactVertexFaceCcd(set.exact[i])
                                                  : cpu::exactEdgeEdgeCcd(set.exact[i]);
            if (exact.touch && mpq_class(gpu.toi[i]) > exact.toiLo && ++lateTimes <= 10)
                ADD_FAILURE() << "query " << i << ": GPU time of impact " << gpu.toi[i]
                              << " is later than the exact one, " << exact.toiLo.get_d();
        }
    }
    EXPECT_EQ(answerDifferences, 0);
    EXPECT_EQ(lateTimes, 0);
    EXPECT_EQ(falseNegatives, 0) << "ground-truth contacts missed";
    EXPECT_EQ(gpu.capped, static_cast<std::uint32_t>(capped));
    EXPECT_EQ(gpu.continued, cpu.continued);
    std::printf("%s: %zu queries, budget %d, %d rounds: GPU %.2f s, twin %.2f s; continued %u, capped %d, "
                "boxes %llu (twin %llu); times of impact "
                "not bit-identical to the twin's: %d; against the ground truth: %d false negatives, %d false "
                "positives\n",
                passes::toString(kind), set.queries.size(), pass.budget(), pass.continuationRounds(),
                gpuSeconds, twinSeconds, gpu.continued, capped, static_cast<unsigned long long>(gpu.boxes),
                static_cast<unsigned long long>(cpu.boxes), toiDifferences, falseNegatives, falsePositives);
}

TEST(CcdQueryGl, VertexFaceAgreesWithTheTwinOnEverySampleQuery) {
    expectGpuAgreesWithTwinOnSampleQueries(CcdKind::VertexFace, 3085);
}

TEST(CcdQueryGl, EdgeEdgeAgreesWithTheTwinOnEverySampleQuery) {
    expectGpuAgreesWithTwinOnSampleQueries(CcdKind::EdgeEdge, 4194);
}

/// The queries scaled by 2^k: coordinates and separation (exact, nothing overflows or underflows).
std::vector<CcdQuery> scaled(std::vector<CcdQuery> queries, int k) {
    for (CcdQuery& q : queries) {
        for (glm::vec3& p : q.points)
            p = glm::vec3(std::ldexp(p.x, k), std::ldexp(p.y, k), std::ldexp(p.z, k));
        q.minSeparation = std::ldexp(q.minSeparation, k);
    }
    return queries;
}

TEST(CcdQueryGl, ScalingByPowersOfTwoChangesNoAnswer) {
    for (CcdKind kind : {CcdKind::VertexFace, CcdKind::EdgeEdge}) {
        const SampleSet set = sampleQueries(kind);
        const CcdQueryPass pass;
        const CcdQueryResult unscaled = pass.run(kind, set.queries);
        for (int k = -20; k <= 20; k += 8) { // -20, -12, -4, 4, 12, 20
            const CcdQueryResult s = pass.run(kind, scaled(set.queries, k));
            int changes = 0;
            for (std::size_t i = 0; i < set.queries.size(); ++i)
                changes += s.mayCollide[i] != unscaled.mayCollide[i] ||
                           bits(s.toi[i]) != bits(unscaled.toi[i]) ||
                           s.cappedFlags[i] != unscaled.cappedFlags[i];
            EXPECT_EQ(changes, 0) << passes::toString(kind) << " at scale 2^" << k;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The rounding cover.

/// The ccd_query kernel with its rounding-error bound removed (N = 0: only the flush-to-zero term
/// is left): a CCD without slack for the input rounding to hide in. Unsound in general; exact
/// enough for the query below, whose corner values are computed exactly or within 2^-24 of
/// themselves, far inside the margins the test relies on.
gl::ComputeProgram kernelWithoutErrorBound(const std::vector<std::string>& defines) {
    std::string source = gl::shaderSource("ccd_query", defines);
    const std::string bound = "#define GLC_CCD_ROUNDINGS 32.0f";
    const std::size_t at = source.find(bound);
    if (at == std::string::npos) throw Error("ccd_query: '" + bound + "' not found; update this test");
    source.replace(at, bound.size(), "#define GLC_CCD_ROUNDINGS 0.0f");
    return gl::ComputeProgram::fromSource("ccd_query (no error bound)", source);
}

/// A static vertex on a tilted triangle, L = 1024 away from the origin:
///   a = (L, 0, L), b = (L + 1, 0, L), c = (L, 1, L + 1/3), p = (L + 1/8, 3/4, L + 1/4)
///   = a + (1/8)(b - a) + (3/4)(c - a): the vertex lies in the triangle at every t.
/// L + 1/3 is no float: it rounds to L + 2731/8192 (ulp 2^-13 at 1024), which lifts the rounded
/// triangle's plane by 1/32768 under the vertex: the rounded query never touches.
std::string touchingQueryCsv() {
    const std::string rows = "8193,8,3,4,4097,4\n"  // p = (L + 1/8, 3/4, L + 1/4)
                             "1024,1,0,1,1024,1\n"  // a = (L, 0, L)
                             "1025,1,0,1,1024,1\n"  // b = (L + 1, 0, L)
                             "1024,1,1,1,3073,3\n"; // c = (L, 1, L + 1/3)
    return rows + rows;                             // the same at t = 1: no motion
}

TEST(CcdQueryGl, TheRoundingCoverFindsATouchThatRoundingSeparates) {
    const std::vector<cpu::CcdCsvQuery> csv = cpu::parseCcdQueryCsv(touchingQueryCsv(), "touch.csv");
    ASSERT_EQ(csv.size(), 1u);
    const cpu::RoundedCcdQuery rounded = cpu::roundCcdQuery(csv[0].points, 0);
    // The oracle: the rationals touch; the rounded floats do not.
    ASSERT_TRUE(cpu::exactVertexFaceCcd(csv[0].points).touch);
    std::array<glm::dvec3, 8> floats;
    for (std::size_t i = 0; i < 8; ++i) floats[i] = glm::dvec3(rounded.points[i]);
    ASSERT_FALSE(cpu::exactVertexFaceCcd(cpu::rationalQuery(floats)).touch);
    // The rounding error is that of L + 1/3, 1/24576 = |L + 1/3 - (L + 2731/8192)|, scaled with its
    // axis by 2^-11 (a contact query: z's largest magnitude, L + 1/3, into [0.5, 1)).
    ASSERT_EQ(rounded.axisScale[2], -11);
    ASSERT_EQ(rounded.roundingError, mpq_class(1, 24576 * 2048));
    EXPECT_GT(rounded.minSeparation, 0.0f);

    const CcdQueryPass withoutBound(kernelWithoutErrorBound({}),
                                    kernelWithoutErrorBound({"GLC_CCD_EDGE_EDGE"}));
    const CcdQuery covered{rounded.points, rounded.minSeparation};
    const CcdQuery uncovered{rounded.points, 0.0f};
    const CcdQueryResult r = withoutBound.run(CcdKind::VertexFace, {covered, uncovered});
    EXPECT_EQ(r.mayCollide[0], 1) << "with the cover";
    EXPECT_EQ(r.mayCollide[1], 0) << "without the cover a kernel without slack misses it: the test would "
                                     "prove nothing";
    EXPECT_EQ(r.capped, 0u);
    // The shipped kernel finds it too (with or without the cover: its error bound is 16 times the
    // input rounding, docs/ccd.md).
    EXPECT_EQ(CcdQueryPass().run(CcdKind::VertexFace, {covered}).mayCollide[0], 1);
}

TEST(CcdQueryGl, RefusesBadSeparationsAndBudgets) {
    const CcdQuery q{{}, -1.0f};
    EXPECT_THROW((void)CcdQueryPass().run(CcdKind::EdgeEdge, {q}), Error);
    EXPECT_THROW((void)CcdQueryPass(0).run(CcdKind::EdgeEdge, {CcdQuery{}}), Error);
    EXPECT_TRUE(CcdQueryPass().run(CcdKind::EdgeEdge, {}).mayCollide.empty());
    // A software rasteriser ends an invocation after 65,535 loop iterations: a larger budget would
    // let it cut a search and answer "no contact".
    const CcdQueryPass large(passes::kMaxLlvmpipeCcdBudget + 1);
    if (queryGlInfo().isSoftware)
        EXPECT_THROW((void)large.run(CcdKind::EdgeEdge, {CcdQuery{}}), Error);
    else
        EXPECT_EQ(large.run(CcdKind::EdgeEdge, {CcdQuery{}}).mayCollide.size(), 1u);
}

} // namespace
} // namespace glcollide
