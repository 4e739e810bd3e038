// Continuous collision detection: the exact oracle (src/cpu/oracle/exact_ccd.cpp) against answers
// known by construction and against the ground truth of the CCD benchmark's 7,279 handcrafted
// queries; the conservative float CCD (shaders/common/ccd.glsl, compiled as C++) against the
// oracle: never a false negative (on hard families, random near-degenerate families and every
// benchmark query rounded to float), never a time of impact later than the exact one, and the
// same answers with every coordinate scaled by 2^k, k = -20 ... 20; its error bounds (float corner
// values, projections on the normal, the refutation's quantization and exact values) against
// exact rational values; and its false positives against the benchmark's ground truth.
// This file is compiled twice: into glcollide_unit_tests with the project's flags, and into
// glcollide_relaxed_float_tests with fast-math, FMA contraction and FTZ/DAZ (tests/CMakeLists.txt),
// where the float CCD must keep every guarantee (docs/ccd.md, "Error bound").

#include "cpu/ccd_library.hpp"
#include "cpu/oracle/exact_ccd.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#ifdef GLCOLLIDE_RELAXED_FLOAT
#define CCD_TEST(name) TEST(FloatCcdRelaxedFloat, name)
#else
#define CCD_TEST(name) TEST(FloatCcd, name)
#endif

namespace glcollide {
namespace {

using cpu::ExactCcdResult;
using cpu::RationalCcdQuery;
using glm::vec3;

// The relaxed-float target has no data-directory definition of its own: find the data next to
// this file.
std::filesystem::path sampleQueriesDir() {
#ifdef GLCOLLIDE_TEST_DATA_DIR
    return std::filesystem::path(GLCOLLIDE_TEST_DATA_DIR) / "external" / "ccd-sample-queries";
#else
    return std::filesystem::path(__FILE__).parent_path().parent_path() / "data" / "external" /
           "ccd-sample-queries";
#endif
}

// Sanitizer builds (scripts/test-sanitizers.sh) run these tests about ten times slower: there the
// scale sweeps take every 8th k (still both ends) and the random families are smaller. The
// normal and relaxed builds run them whole.
#if defined(__SANITIZE_ADDRESS__)
#define CCD_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define CCD_SANITIZED 1
#endif
#endif
#ifdef CCD_SANITIZED
constexpr int kScaleStep = 8;
constexpr int kRandomPerFamily = 60;
#else
constexpr int kScaleStep = 1;
constexpr int kRandomPerFamily = 300;
#endif

// Generous for every query here (the benchmark's hardest needs 10^5 only when it is capped).
constexpr int kBudget = 100000;

enum class Kind { VertexFace, EdgeEdge };

struct FloatQuery {
    Kind kind;
    std::array<vec3, 8> p; // t = 0 points, then t = 1 points (exact_ccd.hpp's order)
};

RationalCcdQuery rational(const FloatQuery& q) {
    std::array<glm::dvec3, 8> d;
    for (int i = 0; i < 8; ++i) d[i] = glm::dvec3(q.p[i]);
    return cpu::rationalQuery(d);
}

ExactCcdResult oracle(const FloatQuery& q) {
    return q.kind == Kind::VertexFace ? cpu::exactVertexFaceCcd(rational(q))
                                      : cpu::exactEdgeEdgeCcd(rational(q));
}

struct FloatAnswer {
    bool mayCollide;
    float toi;
    bool capped;
    bool operator==(const FloatAnswer&) const = default;
};

FloatAnswer floatCcd(const FloatQuery& q, float minSeparation = 0.0f, int budget = kBudget) {
    const auto& p = q.p;
    const bool c =
        q.kind == Kind::VertexFace
            ? shader::glcVertexFaceCcd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], minSeparation, budget)
            : shader::glcEdgeEdgeCcd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], minSeparation, budget);
    return {c, shader::glcCcdToi, shader::glcCcdCapped};
}

FloatQuery scaled(FloatQuery q, int k) {
    for (auto& v : q.p) v = vec3(std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k));
    return q;
}

/// The float CCD keeps its contract against the exact answer: a contact is never missed and its
/// time of impact is never later than the exact earliest one.
void expectConservative(const FloatQuery& q, const std::string& what, int budget = kBudget) {
    const ExactCcdResult exact = oracle(q);
    const FloatAnswer answer = floatCcd(q, 0, budget);
    if (exact.touch) {
        EXPECT_TRUE(answer.mayCollide) << what << ": false negative";
        EXPECT_LE(mpq_class(answer.toi), exact.toiLo) << what << ": time of impact later than the exact one";
    }
    for (int k = -20; k <= 20; k += 5)
        EXPECT_EQ(floatCcd(scaled(q, k), 0, budget), answer)
            << what << ": the answer changes at scale 2^" << k;
}

FloatQuery vf(vec3 p0, vec3 a0, vec3 b0, vec3 c0, vec3 p1, vec3 a1, vec3 b1, vec3 c1) {
    return {Kind::VertexFace, {p0, a0, b0, c0, p1, a1, b1, c1}};
}
FloatQuery ee(vec3 a0, vec3 a1, vec3 b0, vec3 b1, vec3 a0e, vec3 a1e, vec3 b0e, vec3 b1e) {
    return {Kind::EdgeEdge, {a0, a1, b0, b1, a0e, a1e, b0e, b1e}};
}
/// A static triangle and a moving vertex.
FloatQuery vertexThrough(vec3 p0, vec3 p1) {
    const vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    return vf(p0, a, b, c, p1, a, b, c);
}
/// A static edge on the x axis and a moving edge.
FloatQuery edgeAcross(vec3 b0, vec3 b1, vec3 b0e, vec3 b1e) {
    const vec3 a0(-1, 0, 0), a1(1, 0, 0);
    return ee(a0, a1, b0, b1, a0, a1, b0e, b1e);
}

// ---------------------------------------------------------------------------------------------
// The exact oracle: answers known by construction.

#ifndef GLCOLLIDE_RELAXED_FLOAT // the oracle is exact arithmetic: one build tests it

mpq_class q(long num, long den) {
    mpq_class r(num, den);
    r.canonicalize();
    return r;
}

TEST(ExactCcd, VertexThroughAnInteriorPointAtAChosenTime) {
    // z = -3 + 7 t crosses the triangle's plane at t = 3/7 at (1/4, 1/4, 0), inside.
    const ExactCcdResult r = oracle(vertexThrough({0.25f, 0.25f, -3}, {0.25f, 0.25f, 4}));
    ASSERT_TRUE(r.touch);
    EXPECT_EQ(r.toiLo, q(3, 7));
    EXPECT_EQ(r.toiHi, q(3, 7));
}

TEST(ExactCcd, IrrationalTimeIsBracketedTightly) {
    // Corner c rises (0, 1, t); the vertex (0.1, t, 1 - t) meets the plane z = t y when
    // t^2 + t - 1 = 0: t = (sqrt 5 - 1) / 2, inside the triangle there.
    const FloatQuery query =
        vf({0.1f, 0, 1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.1f, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 1});
    const ExactCcdResult r = oracle(query);
    ASSERT_TRUE(r.touch);
    const double golden = (std::sqrt(5.0) - 1) / 2;
    EXPECT_LE(r.toiLo.get_d(), golden + 1e-15);
    EXPECT_GE(r.toiHi.get_d(), golden - 1e-15);
    EXPECT_LE(mpq_class(r.toiHi - r.toiLo), mpq_class(mpz_class(1), mpz_class(1) << 64));
}

TEST(ExactCcd, SeparatedByAFixedPlane) {
    // Vertex stays in z >= 1, triangle in z = 0.
    EXPECT_FALSE(oracle(vertexThrough({0.2f, 0.2f, 3}, {5, -4, 1})).touch);
    EXPECT_FALSE(oracle(edgeAcross({0, -1, 2}, {0, 1, 2}, {3, -1, 1}, {3, 1, 1})).touch);
}

TEST(ExactCcd, GrazesAtAnEdgeAndAVertexTouch) {
    // Through the midpoint of edge ab (y = 0): touching counts; 2^-30 beside it: no contact.
    EXPECT_TRUE(oracle(vertexThrough({0.5f, 0, -1}, {0.5f, 0, 1})).touch);
    EXPECT_FALSE(oracle(vertexThrough({0.5f, -0x1p-30f, -1}, {0.5f, -0x1p-30f, 1})).touch);
    // Through corner c.
    EXPECT_TRUE(oracle(vertexThrough({0, 1, -1}, {0, 1, 1})).touch);
    // Edge B sweeps over edge A's end (1, 0, 0) exactly, and 2^-40 past it.
    EXPECT_TRUE(oracle(edgeAcross({1, -1, 1}, {1, 1, 1}, {1, -1, -1}, {1, 1, -1})).touch);
    const float past = 1 + 0x1p-23f;
    EXPECT_FALSE(oracle(edgeAcross({past, -1, 1}, {past, 1, 1}, {past, -1, -1}, {past, 1, -1})).touch);
}

TEST(ExactCcd, ContactAtTheEndsOfTheStep) {
    const ExactCcdResult start = oracle(vertexThrough({0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}));
    ASSERT_TRUE(start.touch);
    EXPECT_EQ(start.toiLo, 0);
    const ExactCcdResult end = oracle(vertexThrough({0.25f, 0.25f, 1}, {0.25f, 0.25f, 0}));
    ASSERT_TRUE(end.touch);
    EXPECT_EQ(end.toiLo, 1);
}

TEST(ExactCcd, CoplanarMotionIsDecidedInThePlane) {
    // In the plane z = 0 the vertex (2 - 1.75 t, 2 - 1.75 t) enters across x + y = 1 at t = 6/7.
    const ExactCcdResult in = oracle(vertexThrough({2, 2, 0}, {0.25f, 0.25f, 0}));
    ASSERT_TRUE(in.touch);
    EXPECT_EQ(in.toiLo, q(6, 7));
    EXPECT_FALSE(oracle(vertexThrough({2, 2, 0}, {3, -1, 0})).touch);
    // Coplanar edges: B slides along the x axis onto A's end at t = 1/2.
    const ExactCcdResult slide = oracle(edgeAcross({2, 0, 0}, {3, 0, 0}, {0, 0, 0}, {1, 0, 0}));
    ASSERT_TRUE(slide.touch);
    EXPECT_EQ(slide.toiLo, q(1, 2));
    // Coplanar, crossing from the start.
    EXPECT_EQ(oracle(edgeAcross({0, -1, 0}, {0, 1, 0}, {0, -1, 0}, {0, 1, 0})).toiLo, 0);
}

TEST(ExactCcd, ParallelEdges) {
    // B parallel to A (along x), descending through A's line at t = 1/2: overlap or not.
    EXPECT_FALSE(oracle(edgeAcross({2, 0, 1}, {3, 0, 1}, {2, 0, -1}, {3, 0, -1})).touch);
    const ExactCcdResult overlap = oracle(edgeAcross({0.5f, 0, 1}, {3, 0, 1}, {0.5f, 0, -1}, {3, 0, -1}));
    ASSERT_TRUE(overlap.touch);
    EXPECT_EQ(overlap.toiLo, q(1, 2));
    // Parallel and beside each other: never.
    EXPECT_FALSE(oracle(edgeAcross({0, 1, 1}, {1, 1, 1}, {0, 1, -1}, {1, 1, -1})).touch);
}

TEST(ExactCcd, DegenerateTrianglesEdgesAndMotion) {
    // Zero-area triangle (collinear corners on the x axis): a vertex through its middle, and beside it.
    const vec3 a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
    EXPECT_TRUE(oracle(vf({1.5f, 0, -1}, a, b, c, {1.5f, 0, 1}, a, b, c)).touch);
    EXPECT_FALSE(oracle(vf({1.5f, 0.5f, -1}, a, b, c, {1.5f, 0.5f, 1}, a, b, c)).touch);
    // All corners in one point: the vertex must hit it.
    EXPECT_TRUE(oracle(vf({-1, -1, -1}, a, a, a, {1, 1, 1}, a, a, a)).touch);
    EXPECT_FALSE(oracle(vf({-1, -1, -1}, a, a, a, {1, 1, 2}, a, a, a)).touch);
    // Zero-length edge B (a point) crossing edge A, and missing it.
    EXPECT_TRUE(oracle(edgeAcross({0.5f, 0, 1}, {0.5f, 0, 1}, {0.5f, 0, -1}, {0.5f, 0, -1})).touch);
    EXPECT_FALSE(
        oracle(edgeAcross({0.5f, 0.5f, 1}, {0.5f, 0.5f, 1}, {0.5f, 0.5f, -1}, {0.5f, 0.5f, -1})).touch);
    // No motion at all: inside, outside.
    EXPECT_EQ(oracle(vertexThrough({0.25f, 0.25f, 0}, {0.25f, 0.25f, 0})).toiLo, 0);
    EXPECT_FALSE(oracle(vertexThrough({0.25f, 0.25f, 0.001f}, {0.25f, 0.25f, 0.001f})).touch);
    // Everything moves together (the cubic is identically 0, the vertex stays inside).
    const vec3 d(0, 0, 5);
    EXPECT_TRUE(
        oracle(vf({0.2f, 0.2f, 0}, a, b, {0, 1, 0}, vec3(0.2f, 0.2f, 0) + d, a + d, b + d, vec3(0, 1, 0) + d))
            .touch);
}

TEST(ExactCcd, EqualsTheGroundTruthOfEverySampleQuery) {
    int queries = 0, disagreements = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(sampleQueriesDir())) {
        if (entry.path().extension() != ".csv") continue;
        const bool vertexFace = entry.path().parent_path().filename() == "vertex-face";
        for (const auto& sample : cpu::readSampleCcdQueries(entry.path().string())) {
            const ExactCcdResult r =
                vertexFace ? cpu::exactVertexFaceCcd(sample.points) : cpu::exactEdgeEdgeCcd(sample.points);
            ++queries;
            if (r.touch != sample.truth) ++disagreements;
            EXPECT_EQ(r.touch, sample.truth) << entry.path() << ", query " << queries;
        }
    }
    EXPECT_EQ(queries, 7279);
    EXPECT_EQ(disagreements, 0);
}

TEST(ExactCcd, CsvErrorsNameTheLine) {
    const auto path = std::filesystem::temp_directory_path() / "glcollide_ccd_bad.csv";
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("0,1,0,1,0,1,0\n1,1,x,1,0,1,0\n", f);
    std::fclose(f);
    try {
        cpu::readSampleCcdQueries(path.string());
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(":2: field 3 'x' is not an integer"), std::string::npos)
            << e.what();
    }
    std::filesystem::remove(path);
}

#endif // GLCOLLIDE_RELAXED_FLOAT

// ---------------------------------------------------------------------------------------------
// The float CCD against the oracle.

std::vector<FloatQuery> hardFamilies() {
    const vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    const float tiny = 0x1p-30f;
    // A face tilted on the plane z = 2x, and points on it whose x has a bit below the refutation's
    // 2^-29 grid (after the normalization by 1/2): quantized, they lie 2^-29 above the plane.
    const vec3 tilted(0.5f, 0, 1);
    const float w = 0x1p-7f + 0x1p-29f, w2 = 0x3p-8f + 0x1p-29f;
    std::vector<FloatQuery> qs = {
        vertexThrough({0.25f, 0.25f, -3}, {0.25f, 0.25f, 4}),              // through the interior at 3/7
        vertexThrough({0.5f, 0, -1}, {0.5f, 0, 1}),                        // through an edge's midpoint
        vertexThrough({0.5f, -tiny, -1}, {0.5f, -tiny, 1}),                // 2^-30 beside it
        vertexThrough({0, 1, -1}, {0, 1, 1}),                              // through a corner
        vertexThrough({0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}),               // touching at t = 0
        vertexThrough({0.25f, 0.25f, 1}, {0.25f, 0.25f, 0}),               // touching at t = 1
        vertexThrough({0.25f, 0.25f, 1}, {0.25f, 0.25f, tiny}),            // stopping 2^-30 short
        vertexThrough({2, 2, 0}, {0.2f, 0.2f, 0}),                         // sliding in the plane, entering
        vertexThrough({2, 2, 0}, {3, -1, 0}),                              // sliding in the plane, outside
        vertexThrough({-1, 0, 0}, {2, 0, 0}),                              // sliding along an edge's line
        vertexThrough({0.5f, 0.5f, 0}, {0.5f, 0.5f, 0}),                   // resting on the hypotenuse
        vertexThrough({0.25f, 0.25f, 0.001f}, {0.25f, 0.25f, 0.001f}),     // resting above
        vertexThrough({0.5f, 0.5f + tiny, 0}, {0.5f, 0.5f + tiny, 0}),     // resting beside
        vf({0.1f, 0, 1}, a, b, c, {0.1f, 1, 0}, a, b, {0, 1, 1}),          // irrational time
        vf({1.5f, 0, -1}, a, b, {2, 0, 0}, {1.5f, 0, 1}, a, b, {2, 0, 0}), // zero-area triangle
        vf({-1, -1, -1}, a, a, a, {1, 1, 1}, a, a, a),                     // triangle collapsed to a point
        vf({-1, -1, -1}, a, a, a, {1, 1, 2}, a, a, a),                     // and missing it
        vf({0.2f, 0.2f, 0}, a, b, c, {0.2f, 0.2f, 5}, {0, 0, 5}, {1, 0, 5}, {0, 1, 5}), // moving together
        vf({0.25f, 0.25f, 1}, a, b, c, {0.25f, 0.25f, 1}, {0, 0, 2}, {1, 0, 2},
           {0, 1, 2}),                                                        // face hits a still vertex
        vf({w, 0.25f, 2 * w}, a, tilted, c, {w, 0.25f, 2 * w}, a, tilted, c), // resting off the grid
        vf({w, 0.1f, 2 * w}, a, tilted, c, {w2, 0.6f, 2 * w2}, a, tilted, c), // sliding off the grid
        vf({0.125f, 0.1f, 0.25f + 0x1p-20f}, a, tilted, c, {0.125f, 0.6f, 0.25f + 0x1p-20f}, a, tilted,
           c),                                                      // sliding 2^-20 above the tilted face
        edgeAcross({0, -1, 1}, {0, 1, 1}, {0, -1, -1}, {0, 1, -1}), // crossing at t = 1/2
        edgeAcross({1, -1, 1}, {1, 1, 1}, {1, -1, -1}, {1, 1, -1}), // grazing A's end
        edgeAcross({1 + 0x1p-23f, -1, 1}, {1 + 0x1p-23f, 1, 1}, {1 + 0x1p-23f, -1, -1},
                   {1 + 0x1p-23f, 1, -1}),
        edgeAcross({2, 0, 1}, {3, 0, 1}, {2, 0, -1}, {3, 0, -1}), // parallel, through the line, no overlap
        edgeAcross({0.5f, 0, 1}, {3, 0, 1}, {0.5f, 0, -1}, {3, 0, -1}),       // parallel, overlapping
        edgeAcross({0, 1, 1}, {1, 1, 1}, {0, 1, -1}, {1, 1, -1}),             // parallel, beside
        edgeAcross({2, 0, 0}, {3, 0, 0}, {0, 0, 0}, {1, 0, 0}),               // collinear, sliding onto A
        edgeAcross({0, -1, 0}, {0, 1, 0}, {0, -1, 0}, {0, 1, 0}),             // crossing, no motion
        edgeAcross({0, -1, tiny}, {0, 1, tiny}, {0, -1, tiny}, {0, 1, tiny}), // 2^-30 above, no motion
        edgeAcross({0.5f, 0, 1}, {0.5f, 0, 1}, {0.5f, 0, -1}, {0.5f, 0, -1}), // zero-length edge through A
        ee({0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0},
           {0, 0, 0}), // all zero
    };
    // The same, huge and tiny, and far from the origin (the float query there is what is decided).
    const std::size_t n = qs.size();
    for (std::size_t i = 0; i < n; ++i) {
        qs.push_back(scaled(qs[i], 60));
        qs.push_back(scaled(qs[i], -60));
        FloatQuery far = qs[i];
        for (auto& v : far.p) v += vec3(1000.0f, -3e5f, 7.0f);
        qs.push_back(far);
    }
    return qs;
}

CCD_TEST(NeverMissesAHardFamilyAndKeepsItsAnswerAtEveryScale) {
    const auto qs = hardFamilies();
    for (std::size_t i = 0; i < qs.size(); ++i) expectConservative(qs[i], "hard family " + std::to_string(i));
}

CCD_TEST(DecidesClearCasesAndTimesTheCrossingClosely) {
    // Clear answers: not what soundness needs, but a float CCD that said "may collide" to these
    // would be useless. The error bound is 18 gamma_32 M ~ 3.5e-5 M (M <= 4 here), far below
    // the 0.5 that separates the misses.
    EXPECT_FALSE(floatCcd(vertexThrough({0.2f, 0.2f, 3}, {5, -4, 1})).mayCollide);
    EXPECT_FALSE(floatCcd(vertexThrough({2, 2, 0}, {3, -1, 0})).mayCollide);
    EXPECT_FALSE(floatCcd(edgeAcross({0, 1, 1}, {1, 1, 1}, {0, 1, -1}, {1, 1, -1})).mayCollide);
    // Crossing at 3/7: the time of impact is at most 3/7 and within the t-width of an accepted
    // box, about errorBound / |dF/dt| = 3.5e-5 * 4 / 7 = 2e-5; 1e-3 leaves a margin of 50.
    const FloatAnswer cross = floatCcd(vertexThrough({0.25f, 0.25f, -3}, {0.25f, 0.25f, 4}));
    ASSERT_TRUE(cross.mayCollide);
    EXPECT_LE(cross.toi, 3.0f / 7.0f);
    EXPECT_GE(cross.toi, 3.0f / 7.0f - 1e-3f);
    EXPECT_FALSE(cross.capped);
}

CCD_TEST(MinimumSeparationCountsEuclideanDistance) {
    // The vertex passes over the triangle's interior at height d, and diagonally beside corner
    // b at distance d (offset (d/sqrt2, -d/sqrt2) in the plane: no single axis shows d). With
    // minSeparation >= d it must report; at d / 2 the error bound (~3.5e-5) cannot blur a 0.125 gap.
    const float d = 0.25f;
    const FloatQuery over = vertexThrough({-1, 0.25f, d}, {2, 0.25f, d});
    const float s = d / std::sqrt(2.0f);
    const FloatQuery beside = vertexThrough({1 + s, -s, -1}, {1 + s, -s, 1});
    const FloatQuery edges = edgeAcross({0, -1, d}, {0, 1, d}, {0, -1, d}, {0, 1, d});
    // Over a face whose normal is (1, 1, 1) / sqrt3, at distance d along it, sliding parallel to it:
    // the projection n . F = d |n|_2 on the normal must be compared with minSeparation |n|_1 (a
    // shorter norm of n, such as max |n_i|, would drop it).
    const vec3 centroid(1 / 3.0f, 1 / 3.0f, 1 / 3.0f), lift = vec3(d / std::sqrt(3.0f)),
                                                       slide(0.1f, -0.1f, 0);
    const vec3 ta(1, 0, 0), tb(0, 1, 0), tc(0, 0, 1);
    const FloatQuery tilted = vf(centroid + lift + slide, ta, tb, tc, centroid + lift - slide, ta, tb, tc);
    for (const FloatQuery& query : {over, beside, edges, tilted}) {
        // The true distances of `beside` (s sqrt2, rounded s) and `tilted` are d within float
        // rounding: report from 1.0001 d on.
        EXPECT_TRUE(floatCcd(query, d * 1.0001f).mayCollide);
        EXPECT_FALSE(floatCcd(query, d / 2).mayCollide);
        for (int k = -20; k <= 20; ++k) {
            EXPECT_EQ(floatCcd(scaled(query, k), std::ldexp(d * 1.0001f, k)), floatCcd(query, d * 1.0001f))
                << k;
            EXPECT_EQ(floatCcd(scaled(query, k), std::ldexp(d / 2, k)), floatCcd(query, d / 2)) << k;
        }
    }
    EXPECT_TRUE(floatCcd(over, d).mayCollide); // exactly d: touching the separation counts
}

CCD_TEST(OutOfBudgetAnswersMayCollideWithALowerBound) {
    // A crossing at 3/7 with one box allowed: capped, "may collide", time of impact 0 (nothing
    // was excluded). With a few boxes: still never later than 3/7.
    const FloatQuery cross = vertexThrough({0.25f, 0.25f, -3}, {0.25f, 0.25f, 4});
    const FloatAnswer one = floatCcd(cross, 0, 1);
    EXPECT_TRUE(one.mayCollide);
    EXPECT_TRUE(one.capped);
    EXPECT_EQ(one.toi, 0.0f);
    for (int budget = 2; budget < 64; ++budget) {
        const FloatAnswer some = floatCcd(cross, 0, budget);
        EXPECT_TRUE(some.mayCollide) << budget;
        EXPECT_LE(some.toi, 3.0f / 7.0f) << budget;
    }
    // A clear miss is refuted within a handful of boxes.
    const FloatAnswer miss = floatCcd(vertexThrough({0.2f, 0.2f, 3}, {5, -4, 1}), 0, 8);
    EXPECT_FALSE(miss.mayCollide);
    EXPECT_FALSE(miss.capped);
}

// The refutation at work: misses closer than the float search's error bound (about 2^-15 of the
// coordinates) but far above the quantization grid (2^-29) are answered "no collision", where the
// float search alone says "may collide". Not what soundness needs: what the refutation is for.
CCD_TEST(RefutesNearMissesTheFloatBoundCannotSeparate) {
    const vec3 a(0, 0, 0), tilted(0.5f, 0, 1), c(0, 1, 0);
    const float h = 0x1p-20f, s = 0x1p-21f;
    // 2^-20 above a face whose normal is diagonal (no single axis shows the gap), sliding along it.
    const FloatQuery overFace =
        vf({0.125f, 0.1f, 0.25f + h}, a, tilted, c, {0.125f, 0.6f, 0.25f + h}, a, tilted, c);
    // An edge sliding past another one at sqrt2 2^-21, along a diagonal normal.
    const FloatQuery pastEdge =
        ee({-1, 0, 0}, {1, 0, 0}, {-0.5f, -0.5f - s, -0.5f + s}, {-0.5f, 0.5f - s, 0.5f + s}, {-1, 0, 0},
           {1, 0, 0}, {0.5f, -0.5f - s, -0.5f + s}, {0.5f, 0.5f - s, 0.5f + s});
    for (const FloatQuery& query : {overFace, pastEdge}) {
        EXPECT_FALSE(oracle(query).touch);
        // The float search alone, on the normalized query (the largest coordinate, 1, becomes 1/2).
        std::array<vec3, 8> n;
        for (int i = 0; i < 8; ++i) n[i] = query.p[i] * 0.5f;
        shader::glcCcdBoxes = 0;
        shader::glcCcdCapped = false;
        EXPECT_TRUE(shader::glcCcdFloatSearch(query.kind == Kind::EdgeEdge, n[0], n[1], n[2], n[3], n[4],
                                              n[5], n[6], n[7], 0.0f, kBudget));
        for (int k = -20; k <= 20; ++k) {
            const FloatAnswer answer = floatCcd(scaled(query, k));
            EXPECT_FALSE(answer.mayCollide) << k;
            EXPECT_EQ(answer.toi, 1.0f) << k;
            EXPECT_FALSE(answer.capped) << k;
        }
    }
}

// The separating-plane certificate (docs/ccd.md, "Separating plane") at work: a vertex sliding
// beside a face's corner in the face's own plane, at gaps g = 2^-6 ... 2^-21 of the coordinates,
// moving away from it by 64 g. The projection on the face normal shows no gap, so the search and
// the refutation alone must resolve the gap box by box: below the float search's error bound they
// answer "may collide" (measured: from 2^-19 on), which in the engine's safe step froze resting
// bodies (decision 0024, "Response iterations"); the plane answers "no collision" at every gap and
// scale without a box. Truth: the exact oracle (no touch) and the construction (the vertex stays
// at least g, within the inputs' float rounding, from the triangle: beside corner b, then beyond
// edge bc).
CCD_TEST(SeparatingPlaneDecidesCloseSlidingPairs) {
    // The face's plane spanned by (1, 1, 1) / sqrt3 and (1, 1, -2) / sqrt6, so that every coordinate
    // axis sees the in-plane gap mixed with the motion along the other in-plane direction: no box
    // much wider than the gap lies on one side of an axis.
    const glm::dvec3 e1 = glm::normalize(glm::dvec3(1, 1, 1)), e2 = glm::normalize(glm::dvec3(1, 1, -2));
    const auto turned = [&](double x, double y) { return vec3(x * e1 + y * e2); };
    const vec3 a = turned(0, 0), b = turned(1, 0), c = turned(0, 1);
    int searchGaveUp = 0;
    for (int k = 6; k <= 21; ++k) { // below 2^-21 the inputs' own rounding (2^-24) nears the gap
        // Gap g, sliding 64 g past the corner (a resting pair moves far more than its gap).
        const double g = std::ldexp(1.0, -k), s = g / std::sqrt(2.0), slide = 64 * g;
        const FloatQuery beside = vf(turned(1 + s, -s), a, b, c, turned(1 + slide + s, slide - s), a, b, c);
        EXPECT_FALSE(oracle(beside).touch) << k;
        for (const float separation : {0.0f, static_cast<float>(g / 4)}) {
            const FloatAnswer answer = floatCcd(beside, separation);
            EXPECT_FALSE(answer.mayCollide) << k << " " << separation;
            EXPECT_EQ(answer.toi, 1.0f) << k;
            EXPECT_EQ(shader::glcCcdBoxes, 0) << k << ": decided before the search";
            for (int e = -20; e <= 20; e += 5)
                EXPECT_EQ(floatCcd(scaled(beside, e), std::ldexp(separation, e)), answer) << k << " " << e;
        }
        // The search and the refutation alone, on the normalized query, as glcCcdInclusion ran
        // them before the plane.
        float largest = 0;
        for (const vec3& v : beside.p)
            largest = std::max({largest, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
        std::array<vec3, 8> n;
        for (int i = 0; i < 8; ++i) n[i] = beside.p[i] * shader::glcCcdNormalizingScale(largest);
        shader::glcCcdBoxes = 0;
        shader::glcCcdCapped = false;
        const bool found = shader::glcCcdFloatSearch(false, n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7],
                                                     0.0f, kBudget - kBudget / 8);
        const bool refuted = found && shader::glcCcdRefute(false, n[0], n[1], n[2], n[3], n[4], n[5], n[6],
                                                           n[7], 0.0f, kBudget - shader::glcCcdBoxes);
        if (found && !refuted) ++searchGaveUp;
        std::printf("  gap 2^-%d: search alone %s after %d boxes\n", k,
                    !found ? "no collision" : (refuted ? "refuted" : "may collide"), shader::glcCcdBoxes);
    }
    // Not what soundness needs: what the plane is for.
    EXPECT_GT(searchGaveUp, 0);
}

// Random near-degenerate motions: contacts constructed at a random time through a random corner,
// edge point or interior point, then nudged by a few float ulps either way; coplanar motions;
// vertices landing on a face at the end of the step; parallel edges. The oracle decides each float query; the
// float CCD must never miss.
std::vector<FloatQuery> randomNearDegenerate(unsigned seed, int perFamily) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-1, 1);
    std::uniform_int_distribution<int> nudge(-3, 3), pick(0, 2), dyadic(0, 64);
    auto point = [&] { return vec3(coord(rng), coord(rng), coord(rng)); };
    auto ulps = [&](vec3 v) {
        for (int i = 0; i < 3; ++i)
            for (int n = nudge(rng); n != 0; n += n > 0 ? -1 : 1)
                v[i] = std::nextafter(v[i], n > 0 ? 2.0f : -2.0f);
        return v;
    };
    std::vector<FloatQuery> qs;
    for (int i = 0; i < perFamily; ++i) {
        const float t = static_cast<float>(dyadic(rng)) / 64.0f,
                    w0 = static_cast<float>(dyadic(rng)) / 128.0f,
                    w1 = static_cast<float>(dyadic(rng)) / 128.0f;
        // Vertex-face: the triangle moves; the vertex passes through a point of it at time t.
        std::array<vec3, 3> s{point(), point(), point()}, e{point(), point(), point()}, at;
        for (int k = 0; k < 3; ++k) at[k] = s[k] + t * (e[k] - s[k]);
        vec3 target;
        switch (pick(rng)) {
        case 0:
            target = at[pick(rng)];
            break; // a corner
        case 1:
            target = at[0] + w0 * (at[1] - at[0]);
            break; // an edge
        default:
            target = at[0] + w0 * (at[1] - at[0]) + w1 * (at[2] - at[0]); // inside or near
        }
        const vec3 dir = point();
        qs.push_back(
            vf(ulps(target - t * dir), s[0], s[1], s[2], ulps(target + (1 - t) * dir), e[0], e[1], e[2]));
        // Edge-edge: edge B passes through a point of edge A at time t.
        const vec3 a0 = point(), a1 = point(), a0e = point(), a1e = point();
        const vec3 onA = (a0 + t * (a0e - a0)) + w0 * ((a1 + t * (a1e - a1)) - (a0 + t * (a0e - a0)));
        const vec3 half = point() * 0.5f, move = point();
        qs.push_back(ee(a0, a1, ulps(onA - half - t * move), ulps(onA + half - t * move), a0e, a1e,
                        ulps(onA - half + (1 - t) * move), ulps(onA + half + (1 - t) * move)));
        // Coplanar (z = 0 throughout) vertex-face and edge-edge.
        auto flat = [&] { return vec3(coord(rng), coord(rng), 0); };
        qs.push_back(vf(flat(), flat(), flat(), flat(), flat(), flat(), flat(), flat()));
        qs.push_back(ee(flat(), flat(), flat(), flat(), flat(), flat(), flat(), flat()));
        // Landing: the vertex comes to rest on a face parallel to z = 0 exactly at t = 1 (or
        // leaves it at t = 0), from a random height, over a random offset. Evaluated in float, the
        // contact corner is typically off by an ulp: only the error bound keeps those boxes.
        for (int k = 0; k < 4; ++k) {
            const float h = 8 * coord(rng), sx = 3 * coord(rng), z0 = h + 4 * std::abs(coord(rng)) + 1e-3f;
            const vec3 fa(sx, 0, h), fb(sx + 1, 0, h), fc(sx, 1, h), from(sx + 0.25f, 0.25f, z0);
            const vec3 to(sx + 0.275f + 0.225f * coord(rng), 0.25f + 0.2f * coord(rng), h); // inside
            qs.push_back(k % 2 ? vf(to, fa, fb, fc, from, fa, fb, fc) : vf(from, fa, fb, fc, to, fa, fb, fc));
        }
        // Parallel edges: B is A's direction, offset, descending through A's line.
        const vec3 dirA = point(), base = point(), off = ulps(vec3(0, 0, 0.5f));
        qs.push_back(ee(base, base + dirA, base + off + dirA * w0, base + off + dirA * (1 + w1), base,
                        base + dirA, base - off + dirA * w0, base - off + dirA * (1 + w1)));
    }
    return qs;
}

// Parallel edges through each other's line are the costly family (cells along the contact line
// are excluded one by one): most use up this budget and answer "may collide", which must be sound
// too. Smaller than kBudget to keep the test short.
constexpr int kRandomBudget = 20000;

CCD_TEST(NeverMissesARandomNearDegenerateMotion) {
    const auto qs = randomNearDegenerate(2026, kRandomPerFamily);
    int contacts = 0;
    for (std::size_t i = 0; i < qs.size(); ++i) {
        contacts += oracle(qs[i]).touch;
        expectConservative(qs[i], "random query " + std::to_string(i), kRandomBudget);
    }
    // The families are built to touch often: a generator that never did would test nothing.
    EXPECT_GT(contacts, static_cast<int>(qs.size()) / 10);
}

// The error bound of the argument (docs/ccd.md, "Error bound") holds for the corner values as this
// build evaluates them (in the relaxed build: contracted, reassociated, flushed): random
// normalized points with heavy cancellation, random dyadic t, u, v of every level, each corner
// value against its exact rational value. Also prints how much of the bound is used.
CCD_TEST(CornerValuesStayWithinTheErrorBound) {
    std::mt19937 rng(21);
    // Magnitudes just above 0.5 (where an ulp is largest relative to the value) make roundings
    // weigh most against the bound.
    std::uniform_real_distribution<float> coord(0.5f, 0.52f), offset(-1e-3f, 1e-3f);
    std::uniform_int_distribution<int> level(0, GLC_CCD_MAX_LEVEL), sign(0, 1);
    const float gamma = GLC_CCD_ROUNDINGS * shader::GLC_CCD_UNIT_ROUNDOFF /
                        (1.0f - GLC_CCD_ROUNDINGS * shader::GLC_CCD_UNIT_ROUNDOFF);
    auto dyadic = [&] {
        const int l = level(rng);
        std::uniform_int_distribution<long> k(0, 1L << l);
        const float value = std::ldexp(static_cast<float>(k(rng)), -l); // exact: at most 25 bits, in [0, 1]
        return sign(rng) ? value : std::ldexp(value, -level(rng));      // half of them small: a small bound
    };
    double worst = 0;
    for (int i = 0; i < 50000; ++i) {
        const bool edgeEdge = i % 2 == 1;
        // Nearly equal points (cancellation), signs mixed, largest magnitude near 1.
        const vec3 base(sign(rng) ? coord(rng) : -coord(rng), sign(rng) ? coord(rng) : -coord(rng),
                        coord(rng));
        std::array<vec3, 8> p;
        for (auto& v : p) v = base + vec3(offset(rng), offset(rng), offset(rng));
        const float t = dyadic(), u = dyadic(), v = dyadic();
        const vec3 f =
            shader::glcCcdF(edgeEdge, shader::glcCcdAt(p[0], p[4], t), shader::glcCcdAt(p[1], p[5], t),
                            shader::glcCcdAt(p[2], p[6], t), shader::glcCcdAt(p[3], p[7], t), u, v);
        const vec3 m0 = max(abs(p[0]), abs(p[4])), m1 = max(abs(p[1]), abs(p[5])),
                   m2 = max(abs(p[2]), abs(p[6])), m3 = max(abs(p[3]), abs(p[7]));
        const vec3 bound = gamma * shader::glcCcdMonomialSum(edgeEdge, m0, m1, m2, m3, t, u, v);
        for (int axis = 0; axis < 3; ++axis) {
            auto at = [&](int k) {
                const mpq_class x0(p[k][axis]), x1(p[k + 4][axis]);
                return mpq_class(x0 + mpq_class(t) * (x1 - x0));
            };
            const mpq_class P = at(0), A = at(1), B = at(2), C = at(3), U(u), V(v);
            const mpq_class exact = edgeEdge ? mpq_class((P + U * (A - P)) - (B + V * (C - B)))
                                             : mpq_class(P - A - U * (B - A) - V * (C - A));
            const mpq_class error = abs(mpq_class(f[axis]) - exact);
            EXPECT_LE(error, mpq_class(bound[axis])) << "query " << i << " axis " << axis;
            worst = std::max(worst, error.get_d() / bound[axis]);
        }
    }
    std::printf("largest corner error: %.4f of the error bound\n", worst);
}

// Random normalized points for the bound tests: nearly equal (cancellation), signs mixed, the
// largest magnitude near 1; every 4th query also has coordinates far below the refutation's grid.
struct BoundSample {
    bool edgeEdge;
    std::array<vec3, 8> p;
    float t, u, v;
};

BoundSample boundSample(std::mt19937& rng, int i) {
    std::uniform_real_distribution<float> coord(0.5f, 0.52f), offset(-1e-3f, 1e-3f), small(-1e-6f, 1e-6f);
    std::uniform_int_distribution<int> level(0, GLC_CCD_MAX_LEVEL), sign(0, 1);
    auto dyadic = [&] {
        const int l = level(rng);
        std::uniform_int_distribution<long> k(0, 1L << l);
        const float value = std::ldexp(static_cast<float>(k(rng)), -l); // exact: at most 25 bits, in [0, 1]
        return sign(rng) ? value : std::ldexp(value, -level(rng));      // half of them small
    };
    BoundSample b;
    b.edgeEdge = i % 2 == 1;
    const vec3 base(sign(rng) ? coord(rng) : -coord(rng), sign(rng) ? coord(rng) : -coord(rng), coord(rng));
    for (auto& x : b.p) x = base + vec3(offset(rng), offset(rng), offset(rng));
    if (i % 4 >= 2)
        for (int k = 0; k < 8; k += 3) b.p[k] = vec3(small(rng), offset(rng), small(rng));
    b.t = dyadic();
    b.u = dyadic();
    b.v = dyadic();
    return b;
}

// The exact value of one coordinate of F at (t, u, v) for points given as rationals.
mpq_class exactF(bool edgeEdge, const std::array<mpq_class, 8>& x, const mpq_class& t, const mpq_class& u,
                 const mpq_class& v) {
    auto at = [&](int k) { return mpq_class(x[k] + t * (x[k + 4] - x[k])); };
    const mpq_class P = at(0), A = at(1), B = at(2), C = at(3);
    return edgeEdge ? mpq_class((P + u * (A - P)) - (B + v * (C - B)))
                    : mpq_class(P - A - u * (B - A) - v * (C - A));
}

// The projection of the corner values on the direction of the box (the float search's second
// test) stays within its bound gamma_ND sum_i |n_i| (monomial sum)_i, as this build evaluates it.
CCD_TEST(ProjectionStaysWithinItsErrorBound) {
    std::mt19937 rng(22);
    const float gamma = GLC_CCD_DIRECTION_ROUNDINGS * shader::GLC_CCD_UNIT_ROUNDOFF /
                        (1.0f - GLC_CCD_DIRECTION_ROUNDINGS * shader::GLC_CCD_UNIT_ROUNDOFF);
    double worst = 0;
    int projected = 0;
    for (int i = 0; i < 50000; ++i) {
        const BoundSample b = boundSample(rng, i);
        const auto& p = b.p;
        const vec3 P = shader::glcCcdAt(p[0], p[4], b.t), A = shader::glcCcdAt(p[1], p[5], b.t),
                   B = shader::glcCcdAt(p[2], p[6], b.t), C = shader::glcCcdAt(p[3], p[7], b.t);
        const vec3 n = shader::glcCcdDirection(b.edgeEdge, P, A, B, C);
        if (n == vec3(0.0f)) continue;
        ++projected;
        const float computed = dot(n, shader::glcCcdF(b.edgeEdge, P, A, B, C, b.u, b.v));
        const vec3 m0 = max(abs(p[0]), abs(p[4])), m1 = max(abs(p[1]), abs(p[5])),
                   m2 = max(abs(p[2]), abs(p[6])), m3 = max(abs(p[3]), abs(p[7]));
        const float bound =
            gamma * dot(abs(n), shader::glcCcdMonomialSum(b.edgeEdge, m0, m1, m2, m3, b.t, b.u, b.v));
        mpq_class exact = 0;
        for (int axis = 0; axis < 3; ++axis) {
            std::array<mpq_class, 8> x;
            for (int k = 0; k < 8; ++k) x[k] = p[k][axis];
            exact += mpq_class(n[axis]) * exactF(b.edgeEdge, x, b.t, b.u, b.v);
        }
        const mpq_class error = abs(mpq_class(computed) - exact);
        EXPECT_LE(error, mpq_class(bound)) << "query " << i;
        worst = std::max(worst, error.get_d() / bound);
    }
    EXPECT_GT(projected, 40000); // the directions exist: the test tests something
    std::printf("largest projection error: %.4f of its error bound\n", worst);
}

// The refutation's corner values: the quantized query (every coordinate truncated to the grid
// 2^-29, computed here in double) has an F within GLC_CCD_QUANTUM_ERROR of the float query's F;
// its exact value, converted, is within 5.0001 * 2^-24 of itself; and the projection on the
// box's direction computed from the converted values is within GLC_CCD_EXACT_PROJECTION_ERROR
// |n| . |f| of the exact projection of the quantized F.
CCD_TEST(ExactCornerValuesStayWithinTheirErrorBounds) {
    std::mt19937 rng(23);
    double worstQuantization = 0, worstConversion = 0, worstProjection = 0;
    for (int i = 0; i < 20000; ++i) {
        BoundSample b = boundSample(rng, i);
        // Box corners are dyadic of level <= 24: snap t, u, v to that grid.
        for (float* x : {&b.t, &b.u, &b.v}) *x = std::ldexp(std::trunc(std::ldexp(*x, 24)), -24);
        const auto& p = b.p;
        const shader::GlcCcdExactQuery q =
            shader::glcCcdExact(b.edgeEdge, p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]);
        const unsigned T = shader::glcCcdGrid(b.t), U = shader::glcCcdGrid(b.u), V = shader::glcCcdGrid(b.v);
        const vec3 f(
            shader::glcCcdExactCorners(q.g0.x, q.g1.x, q.h0.x, q.h1.x, q.k0.x, q.k1.x, T, U, U, V, V).x,
            shader::glcCcdExactCorners(q.g0.y, q.g1.y, q.h0.y, q.h1.y, q.k0.y, q.k1.y, T, U, U, V, V).x,
            shader::glcCcdExactCorners(q.g0.z, q.g1.z, q.h0.z, q.h1.z, q.k0.z, q.k1.z, T, U, U, V, V).x);
        const vec3 n = shader::glcCcdDirection(
            b.edgeEdge, shader::glcCcdAt(p[0], p[4], b.t), shader::glcCcdAt(p[1], p[5], b.t),
            shader::glcCcdAt(p[2], p[6], b.t), shader::glcCcdAt(p[3], p[7], b.t));
        mpq_class projection = 0;
        for (int axis = 0; axis < 3; ++axis) {
            std::array<mpq_class, 8> x, quantized;
            for (int k = 0; k < 8; ++k) {
                x[k] = p[k][axis];
                // Truncation toward zero on the grid 2^-29 (exact in double: 24 bits times 2^29).
                quantized[k] = mpq_class(static_cast<long>(std::ldexp(static_cast<double>(p[k][axis]), 29))) /
                               mpq_class(1L << 29);
            }
            const mpq_class F = exactF(b.edgeEdge, x, b.t, b.u, b.v),
                            Q = exactF(b.edgeEdge, quantized, b.t, b.u, b.v);
            const mpq_class quantization = abs(Q - F), conversion = abs(mpq_class(f[axis]) - Q);
            EXPECT_LE(quantization, mpq_class(shader::GLC_CCD_QUANTUM_ERROR))
                << "query " << i << " axis " << axis;
            const mpq_class relative = mpq_class(5.0001 * 0x1p-24) * abs(Q);
            EXPECT_LE(conversion, relative) << "query " << i << " axis " << axis;
            worstQuantization =
                std::max(worstQuantization, quantization.get_d() / shader::GLC_CCD_QUANTUM_ERROR);
            if (Q != 0) worstConversion = std::max(worstConversion, conversion.get_d() / relative.get_d());
            projection += mpq_class(n[axis]) * Q;
        }
        const float computed = dot(n, f);
        const float bound = shader::GLC_CCD_EXACT_PROJECTION_ERROR * dot(abs(n), abs(f));
        const mpq_class error = abs(mpq_class(computed) - projection);
        EXPECT_LE(error, mpq_class(bound)) << "query " << i;
        if (bound > 0) worstProjection = std::max(worstProjection, error.get_d() / bound);
    }
    std::printf("largest errors, of their bounds: quantization %.4f, conversion %.4f, projection %.4f\n",
                worstQuantization, worstConversion, worstProjection);
}

struct Tally {
    int queries = 0, contacts = 0, falseNegatives = 0, falsePositives = 0, capped = 0;
    int truthFalseNegatives = 0, truthFalsePositives = 0;
    long boxes = 0;
    int mostBoxes = 0;
};

// The budget a GPU pass on llvmpipe may give a query: llvmpipe ends an invocation after 65,535
// loop iterations, and a query runs at most 2 budget + 4 (docs/ccd.md, "Tolerances").
constexpr int kLlvmpipeBudget = 21844;

CCD_TEST(NeverMissesASampleQueryRoundedToFloatAtAnyScale) {
    Tally tally[2], llvmpipe[2]; // [0] vertex-face, [1] edge-edge; at kBudget and at kLlvmpipeBudget
    std::map<std::string, std::array<int, 2>> perSet; // false positives against the ground truth
    int scaleChanges = 0, lateTimes = 0;
    auto count = [](Tally& t, const ExactCcdResult& exact, bool truth, const FloatAnswer& answer) {
        ++t.queries;
        t.contacts += exact.touch;
        t.capped += answer.capped;
        t.boxes += shader::glcCcdBoxes;
        t.mostBoxes = std::max(t.mostBoxes, shader::glcCcdBoxes);
        if (exact.touch && !answer.mayCollide) ++t.falseNegatives;
        if (!exact.touch && answer.mayCollide) ++t.falsePositives;
        if (truth && !answer.mayCollide) ++t.truthFalseNegatives;
        if (!truth && answer.mayCollide) ++t.truthFalsePositives;
    };
    for (const auto& entry : std::filesystem::recursive_directory_iterator(sampleQueriesDir())) {
        if (entry.path().extension() != ".csv") continue;
        const bool vertexFace = entry.path().parent_path().filename() == "vertex-face";
        const int kind = vertexFace ? 0 : 1;
        const std::string set = entry.path().parent_path().parent_path().filename().string();
        for (const auto& sample : cpu::readSampleCcdQueries(entry.path().string())) {
            FloatQuery query{vertexFace ? Kind::VertexFace : Kind::EdgeEdge, {}};
            for (int i = 0; i < 8; ++i)
                query.p[i] = vec3(float(sample.points[i].x.get_d()), float(sample.points[i].y.get_d()),
                                  float(sample.points[i].z.get_d()));
            // get_d truncates toward zero, but the benchmark's coordinates are doubles (its README),
            // so get_d is exact and the float conversion rounds to nearest once.
            const ExactCcdResult exact = oracle(query); // the rounded query is the one decided
            const FloatAnswer answer = floatCcd(query);
            count(tally[kind], exact, sample.truth, answer);
            perSet[set][kind] += !sample.truth && answer.mayCollide;
            if (exact.touch && answer.mayCollide && mpq_class(answer.toi) > exact.toiLo) ++lateTimes;
            for (int k = -20; k <= 20; k += kScaleStep)
                if (k != 0 && !(floatCcd(scaled(query, k)) == answer)) ++scaleChanges;
            count(llvmpipe[kind], exact, sample.truth, floatCcd(query, 0, kLlvmpipeBudget));
        }
    }
    for (int kind = 0; kind < 2; ++kind)
        for (const Tally* t : {&tally[kind], &llvmpipe[kind]}) {
            std::printf(
                "%s, budget %d: %d queries, %d contacts of the float query; false negatives %d, false "
                "positives %d, capped %d; against the original ground truth: false negatives %d, false "
                "positives %d; boxes per query %.1f (most %d)\n",
                kind == 0 ? "vertex-face" : "edge-edge", t == &tally[kind] ? kBudget : kLlvmpipeBudget,
                t->queries, t->contacts, t->falseNegatives, t->falsePositives, t->capped,
                t->truthFalseNegatives, t->truthFalsePositives, double(t->boxes) / t->queries, t->mostBoxes);
            EXPECT_EQ(t->falseNegatives, 0);
            EXPECT_EQ(t->truthFalseNegatives, 0);
        }
    for (const auto& [set, fp] : perSet)
        std::printf("  %s: false positives against the ground truth %d vertex-face, %d edge-edge\n",
                    set.c_str(), fp[0], fp[1]);
    EXPECT_EQ(tally[0].queries, 3085);
    EXPECT_EQ(tally[1].queries, 4194);
    EXPECT_EQ(lateTimes, 0);
    EXPECT_EQ(scaleChanges, 0) << "answers that changed under scaling by 2^k, k = -20 ... 20";
    // Targets (issue 22): at most Tight-Inclusion float's false positives against the ground truth
    // of the original queries, 154 vertex-face and 250 edge-edge, at the tests' budget and at the
    // llvmpipe budget (a capped query answers "may collide"). Of these, 92 / 160 are queries whose
    // rounding to float truly touches (no method deciding the float query can avoid them).
    for (const Tally* t : {&tally[0], &llvmpipe[0]}) EXPECT_LE(t->truthFalsePositives, 154);
    for (const Tally* t : {&tally[1], &llvmpipe[1]}) EXPECT_LE(t->truthFalsePositives, 250);
}

} // namespace
} // namespace glcollide
