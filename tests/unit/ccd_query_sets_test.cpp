// The external CCD query sets of the Scalable-CCD sample data (cloth-funnel 227 -> 228 and
// cloth-ball 92 -> 93, tests/data/external/scalable-ccd-data/README.md), rebuilt from their mesh
// frames by src/cpu/oracle/ccd_query_sets.cpp: the rebuilt queries against the upstream query
// CSVs and the vertex lists the data's README gives; the exact oracle and the conservative float
// CCD (shaders/common/ccd.glsl, compiled as C++) against the upstream exact answers (mma_bool).
// This file is compiled twice, like ccd_test.cpp: into glcollide_unit_tests, and into
// glcollide_relaxed_float_tests (fast-math, FMA contraction, FTZ/DAZ), where the float CCD must
// still miss nothing. The loader and oracle tests run in the first build only.

#include "cpu/ccd_library.hpp"
#include "cpu/oracle/ccd_query_sets.hpp"
#include "cpu/oracle/exact_ccd.hpp"

#include <glcollide/error.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#ifdef GLCOLLIDE_RELAXED_FLOAT
#define SETS_TEST(name) TEST(FloatCcdOnSetsRelaxedFloat, name)
#define SETS_LONG_TEST(name) TEST(FloatCcdOnSetsRelaxedFloatLong, name)
#else
#define SETS_TEST(name) TEST(FloatCcdOnSets, name)
#define SETS_LONG_TEST(name) TEST(FloatCcdOnSetsLong, name) // label "long" (tests/CMakeLists.txt)
#endif

namespace glcollide {
namespace {

using cpu::CcdPairKind;
using cpu::MeshCcdQuery;
using cpu::ScalableCcdSet;
using glm::vec3;

std::filesystem::path externalDir() {
#ifdef GLCOLLIDE_TEST_DATA_DIR
    return std::filesystem::path(GLCOLLIDE_TEST_DATA_DIR) / "external";
#else
    return std::filesystem::path(__FILE__).parent_path().parent_path() / "data" / "external";
#endif
}

/// The set named `name` of cpu::scalableCcdSets.
ScalableCcdSet set(const std::string& name) {
    for (const ScalableCcdSet& s : cpu::scalableCcdSets(externalDir()))
        if (s.name == name) return s;
    throw std::runtime_error("no CCD set named " + name);
}

std::vector<MeshCcdQuery> listed(const std::string& name) {
    const ScalableCcdSet s = set(name);
    return cpu::readListedCcdQueries(cpu::readCcdStep(s.startFrame, s.endFrame), s);
}

/// The published counts (scalable-ccd-data/README.md): queries, and how many collide.
struct Published {
    const char* name;
    std::size_t queries, collide;
};
[[maybe_unused]] constexpr std::array<Published, 4> kPublished{{{"cloth-funnel vf", 92, 27},
                                                                {"cloth-funnel ee", 263, 107},
                                                                {"cloth-ball vf", 19034, 19032},
                                                                {"cloth-ball ee", 94825, 94822}}};

// ---------------------------------------------------------------------------------------------
// The float CCD against the exact answers.

// Sanitizer builds (scripts/test-sanitizers.sh) run about ten times slower: there the cloth-ball
// sets (113,859 queries, about 8 s in a RelWithDebInfo build on 2 shared cores) are checked on
// every 8th query; the normal and relaxed builds check every query.
#if defined(__SANITIZE_ADDRESS__)
#define SETS_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define SETS_SANITIZED 1
#endif
#endif
#ifdef SETS_SANITIZED
constexpr std::size_t kClothBallStride = 8;
#else
constexpr std::size_t kClothBallStride = 1;
#endif

// As in ccd_test.cpp: generous for every query of these sets (none is capped at this budget).
constexpr int kBudget = 100000;

struct FloatAnswer {
    bool mayCollide;
    float toi;
    bool capped;
    bool operator==(const FloatAnswer&) const = default;
};

/// The float query: every coordinate of these sets is exactly a float (checked by
/// SetCoordinatesAreExactlyFloats), so this conversion is exact and the float CCD decides the very
/// query that mma_bool answers. `k`: every coordinate scaled by 2^k (exact).
std::array<vec3, 8> floatPoints(const MeshCcdQuery& q, int k = 0) {
    std::array<vec3, 8> p;
    for (int i = 0; i < 8; ++i)
        p[i] = vec3(static_cast<float>(std::ldexp(q.points[i].x, k)),
                    static_cast<float>(std::ldexp(q.points[i].y, k)),
                    static_cast<float>(std::ldexp(q.points[i].z, k)));
    return p;
}

FloatAnswer floatCcd(CcdPairKind kind, const std::array<vec3, 8>& p) {
    const bool c =
        kind == CcdPairKind::VertexFace
            ? shader::glcVertexFaceCcd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], 0.0f, kBudget)
            : shader::glcEdgeEdgeCcd(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], 0.0f, kBudget);
    return {c, shader::glcCcdToi, shader::glcCcdCapped};
}

struct Tally {
    int queries = 0, collide = 0, falseNegatives = 0, falsePositives = 0, capped = 0, scaleChanges = 0;
    double seconds = 0;
};

/// Runs the float CCD on every `stride`-th listed query of `name`, also at each scale 2^k of
/// `scales`.
Tally runFloatCcd(const std::string& name, const std::vector<int>& scales, std::size_t stride = 1) {
    const ScalableCcdSet s = set(name);
    const std::vector<MeshCcdQuery> queries = listed(name);
    Tally t;
    const auto begin = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < queries.size(); i += stride) {
        const MeshCcdQuery& q = queries[i];
        const FloatAnswer answer = floatCcd(s.kind, floatPoints(q));
        ++t.queries;
        t.collide += q.truth;
        t.capped += answer.capped;
        t.falseNegatives += q.truth && !answer.mayCollide;
        t.falsePositives += !q.truth && answer.mayCollide;
        for (const int k : scales) t.scaleChanges += !(floatCcd(s.kind, floatPoints(q, k)) == answer);
    }
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::printf("%s: %d queries (%d collide): false negatives %d, false positives %d, capped %d, "
                "answers changed by scaling %d (%zu scales); %.2f s\n",
                name.c_str(), t.queries, t.collide, t.falseNegatives, t.falsePositives, t.capped,
                t.scaleChanges, scales.size(), t.seconds);
    return t;
}

SETS_TEST(NeverMissesAClothFunnelPairAtAnyScale) {
    // Scaling by a power of two changes no answer by construction (ccd.glsl normalizes by one);
    // the float CCD must give the same answer, time of impact and cap at every scale.
    const std::vector<int> scales{-20, -12, -4, 4, 12, 20};
    for (const char* name : {"cloth-funnel vf", "cloth-funnel ee"}) {
        const Tally t = runFloatCcd(name, scales);
        EXPECT_EQ(t.falseNegatives, 0) << name;
        EXPECT_EQ(t.scaleChanges, 0) << name;
    }
}

SETS_TEST(NeverMissesAClothBallPair) {
    for (const char* name : {"cloth-ball vf", "cloth-ball ee"}) {
        const Tally t = runFloatCcd(name, {}, kClothBallStride);
        EXPECT_EQ(t.falseNegatives, 0) << name;
        EXPECT_GT(t.collide, 0) << name; // the set was read: a test of nothing would pass too
    }
}

/// The float CCD on every swept-box candidate of the step of `name`, of which the listed pairs
/// hold every collision (scalable-ccd-data/README.md: the unlisted ones were checked numerically to
/// stay apart by at least 3.6e-8 in cloth-funnel, 6.3e-7 in cloth-ball): false positives here are
/// what a CCD adds on a real broad phase.
void expectNoMissOnTheWholeBroadPhase(const std::string& name) {
    const ScalableCcdSet s = set(name);
    const cpu::CcdStep step = cpu::readCcdStep(s.startFrame, s.endFrame);
    const std::vector<cpu::BoxPair> listedPairs = cpu::readBoxPairs(s.boxes);
    const std::vector<bool> truth = cpu::readMmaBool(s.truth);
    std::vector<cpu::BoxPair> colliding;
    for (std::size_t i = 0; i < listedPairs.size(); ++i)
        if (truth[i]) colliding.push_back(listedPairs[i]);
    std::sort(colliding.begin(), colliding.end());
    int candidates = 0, collide = 0, falseNegatives = 0, falsePositives = 0, capped = 0;
    const auto begin = std::chrono::steady_clock::now();
    for (const cpu::BoxPair& pair : cpu::sweptBoxCandidates(step, s.kind)) {
        const MeshCcdQuery q{cpu::ccdPairPoints(step, s.kind, pair),
                             std::binary_search(colliding.begin(), colliding.end(), pair)};
        const FloatAnswer answer = floatCcd(s.kind, floatPoints(q));
        ++candidates;
        collide += q.truth;
        capped += answer.capped;
        falseNegatives += q.truth && !answer.mayCollide;
        falsePositives += !q.truth && answer.mayCollide;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::printf("%s, every swept-box candidate: %d queries (%d collide): false negatives %d, false positives "
                "%d, capped %d; %.2f s\n",
                name.c_str(), candidates, collide, falseNegatives, falsePositives, capped, seconds);
    EXPECT_EQ(collide, static_cast<int>(colliding.size())) << name << ": a colliding pair is not a candidate";
    EXPECT_EQ(falseNegatives, 0) << name;
}

SETS_TEST(NeverMissesOnTheFunnelsWholeBroadPhase) {
    expectNoMissOnTheWholeBroadPhase("cloth-funnel vf");
    expectNoMissOnTheWholeBroadPhase("cloth-funnel ee");
}

// 6.85 million queries: about 25 s in a RelWithDebInfo build on 2 shared cores, hence "long".
SETS_LONG_TEST(NeverMissesOnTheClothBallsWholeBroadPhase) {
    expectNoMissOnTheWholeBroadPhase("cloth-ball vf");
    expectNoMissOnTheWholeBroadPhase("cloth-ball ee");
}

// ---------------------------------------------------------------------------------------------
// The loader and the exact oracle: one build (no float arithmetic to relax).

#ifndef GLCOLLIDE_RELAXED_FLOAT

TEST(CcdQuerySets, LibiglEdgeOrderIsByHighEndThenLowEnd) {
    // Faces (0, 3, 1) and (1, 3, 2): edges {0,3}, {1,3}, {0,1}, {2,3}, {1,2}. igl::edges lists
    // them column by column of the adjacency matrix: by the larger end, then the smaller.
    const std::vector<cpu::MeshEdge> edges = cpu::libiglEdges({{0, 3, 1}, {1, 3, 2}});
    const std::vector<cpu::MeshEdge> expected{{0, 1}, {1, 2}, {0, 3}, {1, 3}, {2, 3}};
    EXPECT_EQ(edges, expected);
}

TEST(CcdQuerySets, StepsHaveThePublishedSizes) {
    // scalable-ccd-data/README.md, "ID mapping": V, E and F of each scene.
    const ScalableCcdSet funnel = set("cloth-funnel vf"), ball = set("cloth-ball vf");
    const cpu::CcdStep f = cpu::readCcdStep(funnel.startFrame, funnel.endFrame);
    EXPECT_EQ(f.start.size(), 9450u);
    EXPECT_EQ(f.edges.size(), 27930u);
    EXPECT_EQ(f.faces.size(), 18484u);
    const cpu::CcdStep b = cpu::readCcdStep(ball.startFrame, ball.endFrame);
    EXPECT_EQ(b.start.size(), 46598u);
    EXPECT_EQ(b.edges.size(), 138825u);
    EXPECT_EQ(b.faces.size(), 92230u);
}

TEST(CcdQuerySets, ListsHaveThePublishedCountsOfQueriesAndCollisions) {
    for (const Published& p : kPublished) {
        const std::vector<MeshCcdQuery> queries = listed(p.name);
        std::size_t collide = 0;
        for (const MeshCcdQuery& q : queries) collide += q.truth;
        EXPECT_EQ(queries.size(), p.queries) << p.name;
        EXPECT_EQ(collide, p.collide) << p.name;
    }
}

TEST(CcdQuerySets, FunnelQueriesRebuiltFromFramesEqualTheUpstreamCsvExactly) {
    // Upstream published the cloth-funnel queries as exact rationals too: the 8 points rebuilt
    // from the frames, the box ids and the libigl edge order must be those, bit for bit.
    const std::filesystem::path csv = externalDir() / "scalable-ccd-data" / "cloth-funnel" / "queries";
    for (const auto& [name, file] :
         {std::pair{"cloth-funnel vf", "227vf.csv"}, std::pair{"cloth-funnel ee", "227ee.csv"}}) {
        const std::vector<cpu::SampleCcdQuery> rebuilt = cpu::readScalableCcdQueries(set(name));
        const std::vector<cpu::RationalCcdQuery> upstream = cpu::readCcdQueryPoints((csv / file).string());
        ASSERT_EQ(rebuilt.size(), upstream.size()) << name;
        int equal = 0;
        for (std::size_t i = 0; i < rebuilt.size(); ++i) {
            bool same = true;
            for (int k = 0; k < 8; ++k) {
                const cpu::RationalPoint &a = rebuilt[i].points[k], &b = upstream[i][k];
                same = same && a.x == b.x && a.y == b.y && a.z == b.z;
            }
            EXPECT_TRUE(same) << name << " query " << i;
            equal += same;
        }
        std::printf("%s: %d of %zu rebuilt queries equal upstream's CSV\n", name, equal, rebuilt.size());
    }
}

TEST(CcdQuerySets, ClothBallNonCollidingPairsAreTheVerticesTheReadmeNames) {
    // scalable-ccd-data/README.md lists the 5 `false` cloth-ball entries with their vertices
    // (v, f0, f1, f2 or a0, a1, b0, b1): the loader's points must be those vertices' positions.
    struct Entry {
        const char* set;
        std::size_t index;
        std::array<std::uint32_t, 4> vertices;
    };
    const std::array<Entry, 5> entries{{{"cloth-ball vf", 16667, {9056, 10480, 34822, 10391}},
                                        {"cloth-ball vf", 17157, {38844, 35323, 35324, 10989}},
                                        {"cloth-ball ee", 21309, {2775, 14017, 20416, 40593}},
                                        {"cloth-ball ee", 57469, {9056, 27794, 10391, 34822}},
                                        {"cloth-ball ee", 68755, {21088, 21089, 11789, 22084}}}};
    const ScalableCcdSet ball = set("cloth-ball vf");
    const cpu::CcdStep step = cpu::readCcdStep(ball.startFrame, ball.endFrame);
    std::vector<std::size_t> falseIndices[2];
    for (const char* name : {"cloth-ball vf", "cloth-ball ee"}) {
        const std::vector<MeshCcdQuery> queries = cpu::readListedCcdQueries(step, set(name));
        for (std::size_t i = 0; i < queries.size(); ++i)
            if (!queries[i].truth) falseIndices[std::string(name).ends_with("ee") ? 1 : 0].push_back(i);
        for (const Entry& e : entries) {
            if (std::string(e.set) != name) continue;
            ASSERT_LT(e.index, queries.size());
            EXPECT_FALSE(queries[e.index].truth) << name << " " << e.index;
            for (int k = 0; k < 4; ++k) {
                EXPECT_EQ(queries[e.index].points[k], step.start[e.vertices[k]]) << name << " " << e.index;
                EXPECT_EQ(queries[e.index].points[k + 4], step.end[e.vertices[k]]) << name << " " << e.index;
            }
        }
    }
    EXPECT_EQ(falseIndices[0], (std::vector<std::size_t>{16667, 17157}));
    EXPECT_EQ(falseIndices[1], (std::vector<std::size_t>{21309, 57469, 68755}));
}

TEST(CcdQuerySets, SetCoordinatesAreExactlyFloats) {
    // The float tests above convert to float assuming this (the data's README states it).
    for (const char* name : {"cloth-funnel vf", "cloth-ball vf"}) {
        const ScalableCcdSet s = set(name);
        const cpu::CcdStep step = cpu::readCcdStep(s.startFrame, s.endFrame);
        int inexact = 0;
        for (const auto* frame : {&step.start, &step.end})
            for (const glm::dvec3& p : *frame)
                for (int axis = 0; axis < 3; ++axis)
                    inexact += static_cast<double>(static_cast<float>(p[axis])) != p[axis];
        EXPECT_EQ(inexact, 0) << name;
    }
}

TEST(CcdQuerySets, ExactOracleAgreesWithTheUpstreamAnswersOnTheFunnel) {
    for (const char* name : {"cloth-funnel vf", "cloth-funnel ee"}) {
        const ScalableCcdSet s = set(name);
        int disagree = 0, collide = 0;
        for (const cpu::SampleCcdQuery& q : cpu::readScalableCcdQueries(s)) {
            const bool touch = s.kind == CcdPairKind::VertexFace ? cpu::exactVertexFaceCcd(q.points).touch
                                                                 : cpu::exactEdgeEdgeCcd(q.points).touch;
            disagree += touch != q.truth;
            collide += touch;
        }
        std::printf("%s: the exact oracle finds %d collisions, %d disagreements with mma_bool\n", name,
                    collide, disagree);
        EXPECT_EQ(disagree, 0) << name;
    }
}

TEST(CcdQuerySets, SweptBoxCandidatesHaveThePublishedCountsAndHoldTheListedPairs) {
    // scalable-ccd-data/README.md, "Which pairs are listed": the counts (cloth-ball's equal those
    // Scalable-CCD's own broad-phase test asserts), and every listed pair is a candidate.
    const std::array<std::size_t, 4> counts{7319, 33770, 1655541, 5197332};
    const std::vector<ScalableCcdSet> sets = cpu::scalableCcdSets(externalDir());
    ASSERT_EQ(sets.size(), counts.size());
    for (std::size_t i = 0; i < sets.size(); i += 2) {
        const cpu::CcdStep step = cpu::readCcdStep(sets[i].startFrame, sets[i].endFrame);
        for (std::size_t k = i; k < i + 2; ++k) {
            const auto begin = std::chrono::steady_clock::now();
            const std::vector<cpu::BoxPair> candidates = cpu::sweptBoxCandidates(step, sets[k].kind);
            std::printf("%s: %zu swept-box candidates in %.2f s\n", sets[k].name.c_str(), candidates.size(),
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
            EXPECT_EQ(candidates.size(), counts[k]) << sets[k].name;
            int missing = 0;
            for (const cpu::BoxPair& pair : cpu::readBoxPairs(sets[k].boxes))
                missing += !std::binary_search(candidates.begin(), candidates.end(), pair);
            EXPECT_EQ(missing, 0) << sets[k].name;
        }
    }
}

TEST(CcdQuerySets, QueriesWrittenAsCsvReadBackExactly) {
    const std::vector<cpu::SampleCcdQuery> queries = cpu::readScalableCcdQueries(set("cloth-funnel ee"));
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / "glcollide_ccd_sets_roundtrip.csv";
    cpu::writeSampleCcdQueries(file.string(), queries);
    const std::vector<cpu::SampleCcdQuery> back = cpu::readSampleCcdQueries(file.string());
    std::filesystem::remove(file);
    ASSERT_EQ(back.size(), queries.size());
    for (std::size_t i = 0; i < back.size(); ++i) {
        EXPECT_EQ(back[i].truth, queries[i].truth) << i;
        for (int k = 0; k < 8; ++k) {
            EXPECT_EQ(back[i].points[k].x, queries[i].points[k].x) << i;
            EXPECT_EQ(back[i].points[k].y, queries[i].points[k].y) << i;
            EXPECT_EQ(back[i].points[k].z, queries[i].points[k].z) << i;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Bad files: one error naming the file and what is wrong.

class BadCcdSetFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = std::filesystem::temp_directory_path() /
              ("glcollide_bad_ccd_sets_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::create_directories(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::filesystem::path write(const std::string& name, const std::string& text) {
        const std::filesystem::path p = dir / name;
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }
    /// The message of the glcollide::Error that `f` throws ("" when none).
    template <class F> static std::string errorOf(F f) {
        try {
            f();
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
    /// An ASCII PLY: three vertices, then the given face lines.
    std::filesystem::path ply(const std::string& name, int vertices, const std::vector<std::string>& faces) {
        std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
                           "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                           std::to_string(faces.size()) +
                           "\nproperty list uchar int vertex_indices\nend_header\n";
        for (int i = 0; i < vertices; ++i) text += std::to_string(i) + " " + std::to_string(i * i) + " 1\n";
        for (const std::string& f : faces) text += f + "\n";
        return write(name, text);
    }
    std::filesystem::path dir;
};

TEST_F(BadCcdSetFiles, BoxPairsNameTheFileAndTheEntry) {
    const auto notPair = write("pairs.json", "[[1,2],[3],[4,5]]");
    EXPECT_EQ(errorOf([&] { cpu::readBoxPairs(notPair); }),
              notPair.string() + ": /1: expected [a, b], two non-negative integer box ids, found [3]");
    const auto negative = write("negative.json", "[[1,-2]]");
    EXPECT_NE(errorOf([&] { cpu::readBoxPairs(negative); }).find(negative.string() + ": /0: expected [a, b]"),
              std::string::npos);
    const auto notJson = write("broken.json", "[[1,2],");
    EXPECT_EQ(errorOf([&] { cpu::readBoxPairs(notJson); }).rfind(notJson.string() + ": invalid JSON: ", 0),
              0u);
    const auto object = write("object.json", "{}");
    EXPECT_EQ(errorOf([&] { cpu::readBoxPairs(object); }),
              object.string() + ": expected an array of [a, b] box-id pairs at the top");
    EXPECT_EQ(errorOf([&] { cpu::readBoxPairs(dir / "missing.json"); }),
              (dir / "missing.json").string() + ": cannot open file");
}

TEST_F(BadCcdSetFiles, AnswersNameTheFileAndTheEntry) {
    const auto notBool = write("mma.json", "[true,1,false]");
    EXPECT_EQ(errorOf([&] { cpu::readMmaBool(notBool); }),
              notBool.string() + ": /1: expected true or false, found 1");
}

TEST_F(BadCcdSetFiles, PairsThatAreNotPrimitivesOfTheStepAreNamed) {
    // Two triangles on 4 vertices: V = 4, E = 5, F = 2 (box ids 0-3, 4-8, 9-10).
    const auto frame = ply("frame.ply", 4, {"3 0 1 2", "3 1 3 2"});
    ScalableCcdSet s{"test vf",
                     CcdPairKind::VertexFace,
                     frame,
                     frame,
                     write("vf.json", "[[0,10],[3,8]]"),
                     write("vf_mma.json", "[true,false]")};
    const cpu::CcdStep step = cpu::readCcdStep(frame, frame);
    EXPECT_EQ(errorOf([&] { cpu::readListedCcdQueries(step, s); }),
              s.boxes.string() + ": /1: box id 8 is not a face (9 .. 10) of " + frame.string());
    s.boxes = write("vf2.json", "[[0,10]]");
    EXPECT_EQ(errorOf([&] { cpu::readListedCcdQueries(step, s); }),
              s.truth.string() + ": 2 answers for the 1 pairs of " + s.boxes.string());
    s.kind = CcdPairKind::EdgeEdge;
    s.boxes = write("ee.json", "[[4,9]]");
    s.truth = write("ee_mma.json", "[false]");
    EXPECT_EQ(errorOf([&] { cpu::readListedCcdQueries(step, s); }),
              s.boxes.string() + ": /0: box id 9 is not an edge (4 .. 8) of " + frame.string());
}

TEST_F(BadCcdSetFiles, FramesThatDoNotMakeOneStepAreNamed) {
    const auto frame = ply("frame.ply", 4, {"3 0 1 2", "3 1 3 2"});
    const auto fewer = ply("fewer.ply", 3, {"3 0 1 2", "3 1 0 2"});
    EXPECT_EQ(errorOf([&] { cpu::readCcdStep(frame, fewer); }),
              fewer.string() + ": 3 vertices, but " + frame.string() +
                  " has 4 (the two frames of a step must have the same vertices)");
    const auto other = ply("other.ply", 4, {"3 0 1 2", "3 1 2 3"});
    EXPECT_EQ(errorOf([&] { cpu::readCcdStep(frame, other); }),
              other.string() + ": face 1 differs from " + frame.string() +
                  "'s (the two frames of a step must have the same faces)");
    const auto quad = ply("quad.ply", 4, {"3 0 1 2", "4 0 1 3 2"});
    EXPECT_EQ(errorOf([&] { cpu::readCcdStep(quad, quad); }),
              quad.string() + ": face 1 is not a triangle (the CCD sets number faces as the file does)");
}

TEST_F(BadCcdSetFiles, QueryCsvRowsNameTheLine) {
    const auto mixed = write("mixed.csv", std::string("1,1,2,1,3,1\n") + "1,1,2,1,3,1,0\n");
    try {
        cpu::readCcdQueryPoints(mixed.string());
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  mixed.string() +
                      ":2: the ground-truth column is here but not on line 1, the query's first row");
    }
    // Spaces are allowed (the upstream README writes its example rows with them).
    std::string spaced;
    for (int i = 0; i < 8; ++i) spaced += "1, 2, -3, 4, 0, 1\n";
    const auto ok = write("spaced.csv", spaced);
    const std::vector<cpu::RationalCcdQuery> q = cpu::readCcdQueryPoints(ok.string());
    ASSERT_EQ(q.size(), 1u);
    EXPECT_EQ(q[0][7].x, mpq_class(1, 2));
    EXPECT_EQ(q[0][7].y, mpq_class(-3, 4));
    EXPECT_EQ(q[0][7].z, mpq_class(0));
}

#endif // GLCOLLIDE_RELAXED_FLOAT

} // namespace
} // namespace glcollide
