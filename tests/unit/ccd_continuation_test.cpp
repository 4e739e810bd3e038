// The continuation of capped CCD queries on halves of their time interval
// (passes/ccd_continuation.hpp), run with the float CCD's C++ twin (cpu/ccd_library.hpp) as the
// solver: the split positions' rounding is covered (checked against exact GMP midpoints), no
// contact of the CCD benchmark's queries is missed and no time of impact is later than the exact
// oracle's, and the continuation decides queries that a small budget leaves capped.

#include "cpu/ccd_library.hpp"
#include "cpu/oracle/ccd_rounding.hpp"
#include "cpu/oracle/exact_ccd.hpp"
#include "passes/ccd_continuation.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

namespace glcollide {
namespace {

using passes::CcdAnswer;
using passes::CcdKind;
using passes::CcdQuery;
using passes::CcdQueryResult;

passes::CcdSolver twinSolver(CcdKind kind, int budget) {
    return [kind, budget](const std::vector<CcdQuery>& queries) {
        std::vector<CcdAnswer> answers;
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

TEST(CcdContinuation, HalvesCoverTheRoundingOfTheSplitPositions) {
    // Random queries with coordinates of mixed magnitudes and signs: each half's new positions are
    // within (its separation - the query's) / 2 of the exact midpoints, which GMP computes.
    std::mt19937 random(22);
    std::uniform_real_distribution<float> significand(-1.0f, 1.0f);
    std::uniform_int_distribution<int> exponent(-40, 40);
    int widened = 0;
    for (int n = 0; n < 2000; ++n) {
        CcdQuery q;
        for (auto& p : q.points)
            for (int k = 0; k < 3; ++k) p[k] = std::ldexp(significand(random), exponent(random));
        q.minSeparation = n % 2 ? 0.0f : std::ldexp(1.0f, exponent(random));
        for (int half = 0; half < 2; ++half) {
            const std::optional<CcdQuery> piece = passes::halfOfTime(q, half);
            ASSERT_TRUE(piece.has_value());
            mpq_class worst = 0;
            for (std::size_t p = 0; p < 4; ++p) {
                const glm::vec3 kept = half == 0 ? piece->points[p] : piece->points[p + 4];
                const glm::vec3 mid = half == 0 ? piece->points[p + 4] : piece->points[p];
                EXPECT_EQ(kept, half == 0 ? q.points[p] : q.points[p + 4]);
                for (int k = 0; k < 3; ++k) {
                    const mpq_class exact = (mpq_class(q.points[p][k]) + mpq_class(q.points[p + 4][k])) / 2;
                    worst = std::max(worst, mpq_class(abs(exact - mpq_class(mid[k]))));
                }
            }
            EXPECT_GE(mpq_class(piece->minSeparation), mpq_class(q.minSeparation) + 2 * worst) << n;
            widened += piece->minSeparation > q.minSeparation;
        }
    }
    EXPECT_GT(widened, 1000); // most random midpoints are not floats: the check above had work to do
}

TEST(CcdContinuation, ExactMidpointsWidenNothing) {
    CcdQuery q;
    for (std::size_t p = 0; p < 4; ++p) {
        q.points[p] = glm::vec3(float(p), -1.0f, 0.5f);
        q.points[p + 4] = glm::vec3(float(p) + 2.0f, 1.0f, 0.25f);
    }
    const std::optional<CcdQuery> early = passes::halfOfTime(q, 0);
    ASSERT_TRUE(early.has_value());
    EXPECT_EQ(early->minSeparation, 0.0f);
    EXPECT_EQ(early->points[4], glm::vec3(1.0f, 0.0f, 0.375f));
}

/// A vertex falls through the triangle (0,0,0) (1,0,0) (0,1,0) at t = 3/4. With one box less than
/// the whole search needs, the first round is capped; the early half, [0, 1/2], holds no contact
/// and is dropped at once, and the late half, [1/2, 1], finds the crossing within the budget.
TEST(CcdContinuation, MapsTheTimeOfImpactBackFromItsPiece) {
    CcdQuery q;
    q.points = {glm::vec3(0.25f, 0.25f, -3), glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                glm::vec3(0.25f, 0.25f, 1),  glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};
    const CcdAnswer whole = twinSolver(CcdKind::VertexFace, 1000000)({q})[0];
    ASSERT_TRUE(whole.mayCollide && !whole.capped);
    // The largest budget that cuts the search short (capped). The whole search's boxes include its
    // exact refutation's (docs/ccd.md), which may fail without capping the float search: step down.
    int budget = static_cast<int>(whole.boxes) - 1;
    while (budget > 1 && !twinSolver(CcdKind::VertexFace, budget)({q})[0].capped) --budget;
    const passes::CcdSolver solve = twinSolver(CcdKind::VertexFace, budget);
    ASSERT_TRUE(solve({q})[0].capped);
    const CcdQueryResult r = passes::answerWithContinuation({q}, solve, 1);
    EXPECT_EQ(r.continued, 1u);
    ASSERT_EQ(r.mayCollide[0], 1);
    EXPECT_EQ(r.cappedFlags[0], 0);
    EXPECT_LE(r.toi[0], 0.75f);
    EXPECT_GT(r.toi[0], 0.5f) << "the crossing is in the late half; an earlier time is a loose bound";
    EXPECT_GE(r.toi[0], whole.toi - 0x1p-12f) << "within the CCD's time tolerance of the whole search's";
}

struct Sample {
    CcdQuery query;
    cpu::RationalCcdQuery exact;
    bool truth;
};

std::vector<Sample> sampleQueries(CcdKind kind) {
    const auto root = std::filesystem::path(GLCOLLIDE_TEST_DATA_DIR) / "external" / "ccd-sample-queries";
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
        if (entry.path().extension() == ".csv" &&
            entry.path().parent_path().filename() ==
                (kind == CcdKind::VertexFace ? "vertex-face" : "edge-edge"))
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::vector<Sample> samples;
    for (const auto& file : files)
        for (const cpu::SampleCcdQuery& s : cpu::readSampleCcdQueries(file.string())) {
            const cpu::RoundedCcdQuery r = cpu::roundCcdQuery(s.points, 0);
            samples.push_back({{r.points, r.minSeparation}, s.points, s.truth});
        }
    return samples;
}

// A budget of 200 boxes caps hundreds of the benchmark's queries; six rounds of halving decide some
// of them (halving t does not shorten the u and v halvings a contact needs, so a budget too small
// for those stays capped). Nothing is missed and no time is late.
TEST(CcdContinuation, NeverMissesASampleQueryAndDecidesCappedOnes) {
    for (CcdKind kind : {CcdKind::VertexFace, CcdKind::EdgeEdge}) {
        const std::vector<Sample> samples = sampleQueries(kind);
        std::vector<CcdQuery> queries;
        for (const Sample& s : samples) queries.push_back(s.query);
        const passes::CcdSolver solve = twinSolver(kind, 200);
        const CcdQueryResult once = passes::answerWithContinuation(queries, solve, 0);
        const CcdQueryResult continued = passes::answerWithContinuation(queries, solve, 6);
        int falseNegatives = 0, lateTimes = 0;
        for (std::size_t i = 0; i < samples.size(); ++i) {
            if (!samples[i].truth) continue;
            falseNegatives += continued.mayCollide[i] == 0;
            const cpu::ExactCcdResult exact = kind == CcdKind::VertexFace
                                                  ? cpu::exactVertexFaceCcd(samples[i].exact)
                                                  : cpu::exactEdgeEdgeCcd(samples[i].exact);
            lateTimes += exact.touch && mpq_class(continued.toi[i]) > exact.toiLo;
        }
        EXPECT_EQ(falseNegatives, 0) << passes::toString(kind);
        EXPECT_EQ(lateTimes, 0) << passes::toString(kind);
        EXPECT_EQ(continued.continued, once.capped) << passes::toString(kind);
        EXPECT_GT(once.capped, 100u) << passes::toString(kind) << ": the budget should cap many queries";
        EXPECT_LT(continued.capped, once.capped) << passes::toString(kind);
        std::printf("%s, budget 200: capped %u in one round, %u after 6 rounds of halving\n",
                    passes::toString(kind), once.capped, continued.capped);
    }
}

} // namespace
} // namespace glcollide
