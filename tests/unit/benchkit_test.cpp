// The benchmark harness without GL: suite files (built-in and shipped ones parse; bad ones fail
// with a JSON pointer), the order statistics, the log-log slope, and the Google Benchmark JSON.

#include "benchkit/bvh_experiment.hpp"
#include "benchkit/folded_cloth.hpp"
#include "benchkit/report.hpp"
#include "benchkit/results.hpp"
#include "benchkit/suite.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

namespace glcollide::benchkit {
namespace {

using ::testing::HasSubstr;

std::string errorOf(const std::string& text) {
    try {
        parseSuite(text, GLCOLLIDE_SOURCE_DIR "/bench/suites", "t.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

const char* kScene = R"({"format_version": 1, "effects": ["gravity"],
  "objects": [{"generator": {"type": "cloth", "size": [1, 1], "resolution": [2, 2]}, "mass": 1}]})";

std::string suiteWith(const std::string& experimentFields) {
    return std::string(R"({"name": "t", "experiments": [{"name": "e", )") + experimentFields + "}]}";
}

std::string sceneList() {
    return std::string(R"("scenes": [{"name": "s", "scene": )") + kScene + "}]";
}

TEST(BenchkitSuite, BuiltInAndShippedSuitesParse) {
    const Suite d = defaultSuite();
    EXPECT_EQ(d.name, "default");
    // Every accuracy axis and the scaling run are in the default suite.
    for (ExperimentKind k : {ExperimentKind::BroadPhase, ExperimentKind::NarrowPhase,
                             ExperimentKind::Integration, ExperimentKind::Contact, ExperimentKind::Scaling})
        EXPECT_TRUE(std::any_of(d.experiments.begin(), d.experiments.end(), [&](const Experiment& e) {
            return e.kind == k;
        })) << kindName(k);
    EXPECT_EQ(smokeSuite().name, "smoke");
    const Suite full = loadSuite(GLCOLLIDE_SOURCE_DIR "/bench/suites/full.json");
    EXPECT_EQ(full.name, "full");
    // The bvh experiment: quick in smoke, the seed's sizes in default, to ~1M faces in bvh.json.
    for (const Suite& s : {smokeSuite(), d, loadSuite(GLCOLLIDE_SOURCE_DIR "/bench/suites/bvh.json")}) {
        const auto bvh = std::find_if(s.experiments.begin(), s.experiments.end(),
                                      [](const Experiment& e) { return e.kind == ExperimentKind::Bvh; });
        ASSERT_NE(bvh, s.experiments.end()) << s.name;
        EXPECT_EQ(bvh->name, "bvh");
    }
    const Suite bvh = loadSuite(GLCOLLIDE_SOURCE_DIR "/bench/suites/bvh.json");
    const BvhSpec& spec = bvh.experiments.at(0).bvh;
    EXPECT_EQ(spec.tableFaces, (std::vector<std::uint32_t>{2244, 27030, 35992}));
    EXPECT_EQ(spec.scalingFaces.back(), 1000000u);
    EXPECT_THAT(bvh.experiments.at(0).scenes.at(0).sceneJson, HasSubstr("cloth_ball92.ply"));
}

TEST(BenchkitSuite, BvhKeys) {
    const std::string configs =
        R"("configs": [{"name": "bvh", "patch": {"collision": {"broad_phase": "bvh"}}}, {"name": "o"}])";
    const Suite s =
        parseSuite(suiteWith(R"("kind": "bvh", "table_faces": [2244], "scaling_faces": [1000, 3000],
        "octree_max_faces": 2000, "slow_run_seconds": 7, "cpu_check_max_faces": 10, "fold_layers": 3,
        "cloth_patch": {"collision": {"thickness": 0.02}}, "engine_configs": ["o"], "scene_configs": ["bvh"], )" +
                             configs),
                   {}, "t.json");
    const Experiment& e = s.experiments.at(0);
    EXPECT_TRUE(e.scenes.empty()); // optional for this kind
    EXPECT_EQ(e.bvh.tableFaces, (std::vector<std::uint32_t>{2244}));
    EXPECT_EQ(e.bvh.scalingFaces, (std::vector<std::uint32_t>{1000, 3000}));
    EXPECT_EQ(e.bvh.octreeMaxFaces, 2000u);
    EXPECT_EQ(e.bvh.slowRunSeconds, 7);
    EXPECT_EQ(e.bvh.cpuCheckMaxFaces, 10u);
    EXPECT_EQ(e.bvh.foldLayers, 3);
    EXPECT_THAT(e.bvh.clothPatch, HasSubstr("0.02"));
    EXPECT_EQ(e.bvh.engineConfigs, (std::vector<std::string>{"o"}));
    EXPECT_EQ(e.bvh.sceneConfigs, (std::vector<std::string>{"bvh"}));

    EXPECT_THAT(errorOf(suiteWith(R"("kind": "bvh", )" + configs)),
                HasSubstr("/experiments/0: a bvh experiment needs table_faces, scaling_faces or scenes"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "bvh", "table_faces": [1], )" + configs)),
                HasSubstr("/experiments/0/table_faces/0: expected a face count"));
    EXPECT_THAT(
        errorOf(suiteWith(R"("kind": "bvh", "table_faces": [100], "engine_configs": ["x"], )" + configs)),
        HasSubstr("/experiments/0/engine_configs/0: not the name of one of this experiment's configs"));
    EXPECT_THAT(
        errorOf(suiteWith(R"("kind": "scaling", "table_faces": [100], )" + sceneList() + ", " + configs)),
        HasSubstr("/experiments/0/table_faces: only bvh experiments have this key"));
}

TEST(BenchkitSeed, TablesAsPrinted) {
    const auto& rows = seedTables();
    EXPECT_EQ(rows[0].triangles, 2244u);
    EXPECT_EQ(rows[1].triangles, 27030u);
    EXPECT_EQ(rows[2].triangles, 35992u);
    EXPECT_STREQ(rows[0].build[0], "23.94 ms");
    EXPECT_STREQ(rows[2].traverse[0], "041 s"); // garbled in the OCR: quoted, not read as 0.41 s
}

/// Unique edges -> number of faces using each.
std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse(const Body& b) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> use;
    for (const auto& f : b.faces)
        for (int k = 0; k < 3; ++k) ++use[std::minmax(f[k], f[(k + 1) % 3])];
    return use;
}

TEST(BenchkitFoldedCloth, ExactTriangleCountsAndAValidSheet) {
    for (std::uint32_t faces : {2u, 3u, 1000u, 2244u, 27030u, 35992u}) {
        const Body b = foldedCloth({.faces = faces});
        EXPECT_EQ(b.faces.size(), faces);
        // Every node is used, every edge has one or two faces, one spring per edge, masses positive.
        std::vector<int> used(b.positions.size(), 0);
        for (const auto& f : b.faces)
            for (std::uint32_t n : f) used.at(n) = 1;
        EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << faces;
        const auto use = edgeUse(b);
        for (const auto& [edge, count] : use) EXPECT_LE(count, 2) << faces;
        EXPECT_EQ(b.springs.size(), use.size());
        EXPECT_TRUE(std::all_of(b.masses.begin(), b.masses.end(), [](double m) { return m > 0; }));
        EXPECT_TRUE(std::all_of(b.springs.begin(), b.springs.end(),
                                [](const Spring& s) { return s.restLength > 0; }));
        EXPECT_EQ(b.velocities.size(), b.positions.size());
        EXPECT_EQ(b.pinned.size(), b.positions.size());
    }
}

TEST(BenchkitFoldedCloth, DeterministicAndFoldedWithinTheThickness) {
    const FoldedClothSpec spec{.faces = 27030, .thickness = 0.01};
    const Body a = foldedCloth(spec), b = foldedCloth(spec);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.faces, b.faces);
    EXPECT_EQ(foldedClothLayers(spec), 3);
    // 3 layers 0.8 x thickness apart, all lifted alike by the crumpling (amplitude half a cell):
    // the heights span 2 spacings plus twice the amplitude.
    double lo = 1e9, hi = -1e9;
    for (const glm::dvec3& p : a.positions) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
    const double spacing = 0.8 * spec.thickness, amplitude = 0.5 * 2.0 * spec.thickness;
    EXPECT_NEAR(hi - lo, 2 * spacing + 2 * amplitude, 0.25 * spacing);
    // A short sheet gets fewer layers, each panel at least two cells long.
    EXPECT_LT(foldedClothLayers({.faces = 20}), 3);
    EXPECT_GE(foldedClothLayers({.faces = 20}), 1);
}

TEST(BenchkitSuite, MergePatchesApplyToTheScene) {
    const Suite s = parseSuite(
        suiteWith(
            R"("kind": "scaling", "scenes": [{"name": "s", "scene": )" + std::string(kScene) +
            R"(, "patch": {"gravity": [0, -1, 0]}}], "configs": [{"name": "c", "patch": {"damping": 2}, "substep_factor": 3}])"),
        {}, "t.json");
    const Experiment& e = s.experiments.at(0);
    EXPECT_THAT(e.scenes.at(0).sceneJson, HasSubstr("\"gravity\":[0,-1,0]"));
    EXPECT_EQ(e.configs.at(0).substepFactor, 3);
    EXPECT_THAT(e.configs.at(0).patchJson, HasSubstr("\"damping\":2"));
}

TEST(BenchkitSuite, ErrorsNameTheJsonPointer) {
    const std::string configs = R"("configs": [{"name": "c"}])";
    EXPECT_THAT(errorOf("{"), HasSubstr("t.json: invalid JSON"));
    // A number beyond double range is nlohmann's out_of_range, not a parse error (found by
    // fuzz/bench_suite_fuzz.cpp): still one clear error, with the line.
    EXPECT_THAT(errorOf("{\n\"name\": 1e999}"),
                HasSubstr("t.json: invalid JSON: line 2: number 1e999 is outside the range of a double"));
    EXPECT_THAT(errorOf(R"({"name": "t", "experiments": [], "extra": 1})"), HasSubstr("/extra: unknown key"));
    EXPECT_THAT(errorOf(R"({"name": "t", "experiments": []})"),
                HasSubstr("/experiments: expected a non-empty array"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "speed", )" + sceneList() + ", " + configs)),
                HasSubstr("/experiments/0/kind: unknown kind \"speed\""));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "scaling", "scenes": [], )" + configs)),
                HasSubstr("/experiments/0/scenes: expected a non-empty array"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "scaling", )" + sceneList() +
                                  R"(, "configs": [{"name": "c"}, {"name": "c"}])")),
                HasSubstr("/experiments/0/configs/1/name: duplicate name \"c\""));
    EXPECT_THAT(errorOf(suiteWith(
                    R"("kind": "scaling", "scenes": [{"name": "s", "scene": "missing.json"}], )" + configs)),
                HasSubstr("missing.json: cannot open scene file"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "scaling", "scenes": [{"name": "s", "scene": 3}], )" + configs)),
                HasSubstr("/experiments/0/scenes/0/scene: expected a scene object or a file path"));
    EXPECT_THAT(
        errorOf(suiteWith(R"("kind": "scaling", "reference": "ballistic", )" + sceneList() + ", " + configs)),
        HasSubstr("/experiments/0/reference: only integration experiments have a reference"));
    EXPECT_THAT(
        errorOf(suiteWith(R"("kind": "integration", "reference": "exact", )" + sceneList() + ", " + configs)),
        HasSubstr("/experiments/0/reference: unknown reference \"exact\""));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "narrow_phase", "case_families": ["hard", "easy"], )" +
                                  sceneList() + ", " + configs)),
                HasSubstr("/experiments/0/case_families/1: unknown family"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "scaling", )" + sceneList() +
                                  R"(, "configs": [{"name": "c", "substep_factor": 0}])")),
                HasSubstr("/experiments/0/configs/0/substep_factor: expected an integer in 1 ..."));
    EXPECT_THAT(errorOf(R"({"name": "t", "experiments": [{"name": "Bad Name", "kind": "scaling", )" +
                        sceneList() + ", " + configs + "}]}"),
                HasSubstr("/experiments/0/name: use lower-case letters"));
}

TEST(BenchkitResults, OrderStatistics) {
    const Summary s = summarize({5, 1, 4, 2, 3});
    EXPECT_EQ(s.samples, 5u);
    EXPECT_DOUBLE_EQ(s.median, 3);
    EXPECT_DOUBLE_EQ(s.q1, 2);
    EXPECT_DOUBLE_EQ(s.q3, 4);
    EXPECT_DOUBLE_EQ(s.min, 1);
    EXPECT_DOUBLE_EQ(s.max, 5);
    // Even count: the median interpolates between the middle two (type-7 quantiles).
    EXPECT_DOUBLE_EQ(summarize({1, 2, 3, 10}).median, 2.5);
    EXPECT_EQ(summarize({}).samples, 0u);
}

TEST(BenchkitReport, LogLogSlopeOfAPowerLaw) {
    std::vector<RunResult> runs;
    for (std::uint32_t faces : {1000u, 4000u, 16000u, 64000u}) {
        RunResult r;
        r.faces = faces;
        r.time = 3e-4 * std::pow(double(faces), 1.5);
        runs.push_back(r);
    }
    // Exact data: the least-squares fit recovers the exponent up to rounding in log/pow (1e-12).
    EXPECT_NEAR(logLogSlope(runs), 1.5, 1e-12);
    runs.resize(1);
    EXPECT_TRUE(std::isnan(logLogSlope(runs)));
}

TEST(BenchkitReport, GoogleBenchmarkJson) {
    ExperimentResult x;
    x.experiment.name = "broad_phase";
    x.experiment.kind = ExperimentKind::BroadPhase;
    x.timeLabel = "ms";
    x.errorLabel = "missed";
    RunResult r;
    r.scene = "boxes";
    r.config = "octree d2";
    r.faces = 10;
    r.substeps = 1;
    r.passNames = {"BBUpdate", "TriTri"};
    r.passMs = {summarize({1, 2, 3}), summarize({4, 5, 6})};
    r.gpuMs = summarize({5, 7, 9});
    r.wallMs = summarize({6, 8, 10});
    r.set("false_negatives", 0);
    r.set("diverged_metric", std::nan(""));
    x.runs.push_back(r);
    RunContext c;
    c.renderer = "llvmpipe";
    c.gitCommit = "abc";
    Suite suite;
    suite.name = "t";
    const auto j = nlohmann::json::parse(benchmarkJson(c, suite, {x}));
    EXPECT_EQ(j.at("context").at("gl_renderer"), "llvmpipe");
    EXPECT_EQ(j.at("context").at("git_commit"), "abc");
    const auto& b = j.at("benchmarks");
    ASSERT_EQ(b.size(), 4u); // two passes, gpu_total, wall
    EXPECT_EQ(b[0].at("name"), "broad_phase/boxes/octree d2/BBUpdate");
    EXPECT_EQ(b[0].at("real_time"), 2.0);
    EXPECT_EQ(b[0].at("time_unit"), "ms");
    EXPECT_EQ(b[0].at("iterations"), 3);
    EXPECT_EQ(b[2].at("name"), "broad_phase/boxes/octree d2/gpu_total");
    EXPECT_EQ(b[2].at("accuracy_error"), 0.0);
    EXPECT_TRUE(b[2].at("diverged_metric").is_null()); // JSON has no NaN
    EXPECT_EQ(b[3].at("real_time"), 8.0);
}

} // namespace
} // namespace glcollide::benchkit
