// The benchmark harness without GL: suite files (built-in and shipped ones parse; bad ones fail
// with a JSON pointer), the order statistics, the log-log slope, the Google Benchmark JSON, and
// the oscillator reference (its closed form, and the period and amplitude estimators on sampled
// curves whose answers are known).

#include "benchkit/bvh_experiment.hpp"
#include "benchkit/ccd_experiment.hpp"
#include "benchkit/experiments.hpp"
#include "benchkit/folded_cloth.hpp"
#include "benchkit/oscillator.hpp"
#include "benchkit/report.hpp"
#include "benchkit/response_experiment.hpp"
#include "benchkit/results.hpp"
#include "benchkit/suite.hpp"

#include <glcollide/error.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
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

// Every suite shipped in bench/suites loads, and every configuration of every scene it names
// parses (the scene reader's own checks, mesh files included): a suite edited or a scene moved
// fails here, not in a long benchmark run.
TEST(BenchSuites, EveryShippedSuiteLoadsAndEveryConfigOfItsScenesParses) {
    int suites = 0;
    for (const auto& file : std::filesystem::directory_iterator(GLCOLLIDE_SOURCE_DIR "/bench/suites")) {
        if (file.path().extension() != ".json") continue;
        ++suites;
        SCOPED_TRACE(file.path().filename().string());
        const Suite suite = loadSuite(file.path());
        EXPECT_FALSE(suite.experiments.empty());
        for (const Experiment& e : suite.experiments)
            for (const SceneEntry& scene : e.scenes)
                for (const ConfigEntry& config : e.configs)
                    EXPECT_NO_THROW(buildScene(scene, config)) << scene.source;
    }
    EXPECT_GE(suites, 8)
        << "bench/suites: bvh, default, dynamics, full, ogc_layers, response, response_shipped, smoke";
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
    // The oscillator reference with its stiff variant in default and full, the quick one in smoke.
    for (const Suite& s : {smokeSuite(), d, full}) {
        int oscillators = 0;
        for (const Experiment& e : s.experiments)
            oscillators += e.reference == IntegrationReference::Oscillator ? 1 : 0;
        EXPECT_EQ(oscillators, s.name == "smoke" ? 1 : 2) << s.name;
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

TEST(BenchkitSuite, CcdKeys) {
    const Suite s = parseSuite(suiteWith(R"("kind": "ccd", "sets": ["sample-queries", "cloth-ball"],
        "budgets": [256, 21844], "min_separations": [0, 1e-4], "scale_exponents": [-20, 20], "peer": false,
        "peer_timeout_seconds": 60, "engine_sets": ["cloth-funnel"], "engine_thickness": 0.001)"),
                               {}, "t.json");
    const Experiment& e = s.experiments.at(0);
    EXPECT_EQ(e.kind, ExperimentKind::Ccd);
    EXPECT_TRUE(e.scenes.empty());
    ASSERT_EQ(e.configs.size(), 1u); // one configuration unless told
    EXPECT_EQ(e.ccd.sets, (std::vector<std::string>{"sample-queries", "cloth-ball"}));
    EXPECT_EQ(e.ccd.budgets, (std::vector<int>{256, 21844}));
    EXPECT_EQ(e.ccd.minSeparations, (std::vector<double>{0, 1e-4}));
    EXPECT_EQ(e.ccd.scaleExponents, (std::vector<int>{-20, 20}));
    EXPECT_FALSE(e.ccd.peer);
    EXPECT_EQ(e.ccd.peerTimeoutSeconds, 60);
    EXPECT_EQ(e.ccd.engineSets, (std::vector<std::string>{"cloth-funnel"}));
    EXPECT_EQ(e.ccd.engineThickness, 0.001);
    // The built-in suites run it: every set in default, one small set without the peer in smoke.
    for (const Suite& suite : {defaultSuite(), smokeSuite()}) {
        const auto ccd = std::find_if(suite.experiments.begin(), suite.experiments.end(),
                                      [](const Experiment& x) { return x.kind == ExperimentKind::Ccd; });
        ASSERT_NE(ccd, suite.experiments.end()) << suite.name;
        EXPECT_EQ(ccd->ccd.peer, suite.name == "default");
    }

    EXPECT_THAT(errorOf(suiteWith(R"("kind": "ccd")")),
                HasSubstr("/experiments/0/sets: a ccd experiment needs a non-empty list of query sets"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "ccd", "sets": ["funnel"])")),
                HasSubstr("/experiments/0/sets/0: unknown set"));
    EXPECT_THAT(
        errorOf(suiteWith(R"("kind": "ccd", "sets": ["cloth-ball"], "engine_sets": ["sample-queries"])")),
        HasSubstr("/experiments/0/engine_sets/0: unknown step"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "ccd", "sets": ["cloth-ball"], "budgets": [0])")),
                HasSubstr("/experiments/0/budgets/0: expected an integer"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "ccd", "sets": ["cloth-ball"], )" + sceneList())),
                HasSubstr("/experiments/0/scenes: a ccd experiment has sets, not scenes"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "scaling", "sets": ["cloth-ball"], )" + sceneList() +
                                  R"(, "configs": [{"name": "c"}])")),
                HasSubstr("/experiments/0/sets: only ccd experiments have this key"));
}

TEST(BenchkitSuite, ResponseConfigsAreEveryResponseAtEverySubstepCount) {
    const Suite s = parseSuite(
        suiteWith(
            R"("kind": "response", "responses": ["intersection_free", "penalty"], "substeps": [1, 4], )" +
            sceneList()),
        {}, "t.json");
    const Experiment& e = s.experiments.at(0);
    EXPECT_EQ(e.kind, ExperimentKind::Response);
    std::vector<std::string> names;
    for (const ConfigEntry& c : e.configs) names.push_back(c.name);
    EXPECT_EQ(names,
              (std::vector<std::string>{"intersection_free, 1 substep", "intersection_free, 4 substeps",
                                        "penalty, 1 substep", "penalty, 4 substeps"}));
    // The response replaces the scene's and the scene's detection goes (a merge patch's null), so
    // each response brings its own (detectionOf), whatever the scene named; the substep count
    // replaces the scene's.
    const nlohmann::json first = nlohmann::json::parse(e.configs[1].patchJson);
    nlohmann::json patched = {{"collision", {{"response", "bridson"}, {"detection", "discrete"}}}};
    patched.merge_patch(first);
    EXPECT_EQ(patched["collision"]["response"], "intersection_free");
    EXPECT_FALSE(patched["collision"].contains("detection"));
    EXPECT_EQ(patched["time"]["substeps"], 4);
    const nlohmann::json third = nlohmann::json::parse(e.configs[2].patchJson);
    patched = {{"collision", {{"response", "intersection_free"}, {"detection", "continuous"}}}};
    patched.merge_patch(third);
    EXPECT_EQ(patched["collision"]["response"], "penalty");
    EXPECT_FALSE(patched["collision"].contains("detection"));
    EXPECT_EQ(patched["time"]["substeps"], 1);
    // Without substeps: one configuration per response at the scene's own count.
    const Suite own = parseSuite(suiteWith(R"("kind": "response", "responses": ["bridson"], )" + sceneList()),
                                 {}, "t.json");
    ASSERT_EQ(own.experiments.at(0).configs.size(), 1u);
    EXPECT_EQ(own.experiments.at(0).configs[0].name, "bridson");
    EXPECT_FALSE(nlohmann::json::parse(own.experiments.at(0).configs[0].patchJson).contains("time"));
    // The smoke suite runs it (every response, one small scene); the shipped response suite parses.
    const Suite smoke = smokeSuite();
    EXPECT_TRUE(std::any_of(smoke.experiments.begin(), smoke.experiments.end(),
                            [](const Experiment& x) { return x.kind == ExperimentKind::Response; }));
    EXPECT_EQ(loadSuite(GLCOLLIDE_SOURCE_DIR "/bench/suites/response.json").experiments.at(0).configs.size(),
              9u);

    EXPECT_THAT(errorOf(suiteWith(R"("kind": "response", )" + sceneList())),
                HasSubstr("/experiments/0/responses: required list of responses is missing"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "response", "responses": ["ipc"], )" + sceneList())),
                HasSubstr("/experiments/0/responses/0: unknown response"));
    EXPECT_THAT(
        errorOf(suiteWith(R"("kind": "response", "responses": ["penalty", "penalty"], )" + sceneList())),
        HasSubstr("/experiments/0/responses/1: duplicate response"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "response", "responses": ["penalty"], "substeps": [2, 2], )" +
                                  sceneList())),
                HasSubstr("/experiments/0/substeps/1: duplicate substep count"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "response", "responses": ["penalty"], "substeps": [0], )" +
                                  sceneList())),
                HasSubstr("/experiments/0/substeps/0: expected an integer"));
    EXPECT_THAT(
        errorOf(suiteWith(R"("kind": "response", "responses": ["penalty"], "configs": [{"name": "c"}], )" +
                          sceneList())),
        HasSubstr("/experiments/0/configs: a response experiment makes its configs"));
    EXPECT_THAT(errorOf(suiteWith(R"("kind": "scaling", "responses": ["penalty"], )" + sceneList() +
                                  R"(, "configs": [{"name": "c"}])")),
                HasSubstr("/experiments/0/responses: only response experiments have this key"));
}

// Drift and largest rise on a series whose answers are known: the rise is the largest single
// step up (not the total climb, not the first one), and a series that only falls never rose.
TEST(BenchkitResponse, EnergyDriftAndLargestRise) {
    const EnergyDrift d = energyDrift({10.0, 12.0, 11.0, 14.5, 14.0, 9.0});
    EXPECT_EQ(d.start, 10.0);
    EXPECT_EQ(d.end, 9.0);
    EXPECT_EQ(d.drift, -1.0);
    EXPECT_EQ(d.maxRise, 3.5); // 11 -> 14.5, exact in binary
    EXPECT_EQ(d.maxRiseFrame, 3);
    const EnergyDrift falling = energyDrift({3.0, 2.0, 1.0});
    EXPECT_EQ(falling.maxRise, 0.0);
    EXPECT_EQ(falling.maxRiseFrame, 0);
    EXPECT_EQ(falling.drift, -2.0);
    const EnergyDrift none = energyDrift({});
    EXPECT_EQ(none.drift, 0.0);
}

// The tally against ground truth: a set with every combination of truth and answer, each repeated
// a different number of times, so that swapping or merging two categories changes a count.
TEST(BenchkitCcd, TallyCountsEachKindOfAnswerAgainstTheTruth) {
    std::vector<std::uint8_t> answers;
    std::vector<bool> truth;
    const auto add = [&](bool t, std::uint8_t a, int times) {
        for (int i = 0; i < times; ++i) {
            truth.push_back(t);
            answers.push_back(a);
        }
    };
    add(true, 1, 5);   // true positives
    add(true, 0, 2);   // false negatives
    add(false, 7, 3);  // false positives (any non-zero answer means "may collide")
    add(false, 0, 11); // true negatives
    const CcdTally t = tallyCcd(answers, truth);
    EXPECT_EQ(t.queries, 21u);
    EXPECT_EQ(t.truthPositives, 7u);
    EXPECT_EQ(t.positives, 8u);
    EXPECT_EQ(t.falseNegatives, 2u);
    EXPECT_EQ(t.falsePositives, 3u);
    EXPECT_THROW((void)tallyCcd({1}, {true, false}), Error);
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

// --- the oscillator reference ---------------------------------------------------------------------

/// u'' = −(c u' + k u) / m by classical Runge-Kutta in double: an integration independent of the
/// closed form. Global error O(h⁴): at hω = 6e-4 about (hω)⁴ ω t / 120 ~ 1e-14 of the amplitude.
std::pair<double, double> rungeKutta(const DampedOscillator& o, double tEnd, int steps) {
    const double h = tEnd / steps;
    double u = o.u0, v = o.v0;
    const auto a = [&](double x, double y) { return -(o.damping * y + o.stiffness * x) / o.mass; };
    for (int i = 0; i < steps; ++i) {
        const double k1u = v, k1v = a(u, v);
        const double k2u = v + 0.5 * h * k1v, k2v = a(u + 0.5 * h * k1u, v + 0.5 * h * k1v);
        const double k3u = v + 0.5 * h * k2v, k3v = a(u + 0.5 * h * k2u, v + 0.5 * h * k2v);
        const double k4u = v + h * k3v, k4v = a(u + h * k3u, v + h * k3v);
        u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    return {u, v};
}

TEST(BenchkitOscillator, ClosedFormMatchesAnIndependentIntegration) {
    for (const DampedOscillator& o :
         {DampedOscillator{1.0, 40.0, 0.0, 0.0, 0.06}, DampedOscillator{1.0, 40.0, 0.2, 0.0, 0.06},
          DampedOscillator{0.3, 500.0, 1.5, 0.01, -0.4}}) {
        SCOPED_TRACE(o.damping);
        EXPECT_DOUBLE_EQ(o.displacement(0.0), o.u0);
        EXPECT_NEAR(o.velocity(0.0), o.v0, 1e-15);
        for (double t : {0.37, 1.0, 2.9}) {
            const auto [u, v] = rungeKutta(o, t, 200000);
            // RK4's own error is ~1e-14 of the amplitude (see rungeKutta): 1e-10 is rounding room.
            EXPECT_NEAR(o.displacement(t), u, 1e-10 * o.amplitude());
            EXPECT_NEAR(o.velocity(t), v, 1e-10 * o.amplitude() * o.omega());
            // One damped period later the state is the same times e^{−ζω T_d}.
            EXPECT_NEAR(o.displacement(t + o.period()), o.amplitudeRatioPerPeriod() * o.displacement(t),
                        1e-12 * o.amplitude());
        }
    }
    // The benchmark's body: k = 40 N/m on m = 1 kg, v0 = 0.06 m/s.
    const DampedOscillator undamped{1.0, 40.0, 0.0, 0.0, 0.06};
    EXPECT_DOUBLE_EQ(undamped.period(), 2 * std::numbers::pi / std::sqrt(40.0));
    EXPECT_DOUBLE_EQ(undamped.amplitude(), 0.06 / std::sqrt(40.0));
    EXPECT_EQ(undamped.amplitudeRatioPerPeriod(), 1.0);
    EXPECT_DOUBLE_EQ(undamped.energy(1.234), 0.5 * 1.0 * 0.06 * 0.06); // conserved
    const DampedOscillator damped{1.0, 40.0, 0.2, 0.0, 0.06};
    EXPECT_NEAR(damped.zeta(), 0.2 / (2 * std::sqrt(40.0)), 1e-16);
    EXPECT_NEAR(damped.amplitudeRatioPerPeriod(), 0.9054182356, 1e-10);
}

/// u_i = A sin(ω i dt + φ) e^{−a i dt}, i = 0 .. n−1.
std::vector<double> sampled(double a, double omega, double phase, double dt, int n) {
    std::vector<double> u;
    for (int i = 0; i < n; ++i) u.push_back(std::exp(-a * i * dt) * std::sin(omega * i * dt + phase));
    return u;
}

TEST(BenchkitOscillator, PeriodFromZeroCrossingsWithinTheInterpolationBound) {
    // Samples of sin(ωt + φ) cross upwards at t = (2πj − φ)/ω exactly. Each linearly interpolated
    // crossing is within crossingTimeBound (½ max|f''| / min|f'| · dt²/4 over the bracket), so
    // the mean period is within twice that over the crossings − 1 periods.
    const double omega = std::sqrt(40.0);
    for (double framesPerPeriod : {8.0, 20.0, 49.67}) {
        const double dt = 2 * std::numbers::pi / omega / framesPerPeriod;
        for (double phase : {0.0, 0.3, 1.7, 4.0}) {
            SCOPED_TRACE(std::to_string(framesPerPeriod) + " frames per period, phase " +
                         std::to_string(phase));
            const std::vector<double> u = sampled(0.0, omega, phase, dt, int(10.3 * framesPerPeriod));
            const std::vector<double> t = upwardZeroCrossings(u, dt);
            ASSERT_GE(t.size(), 10u);
            const double bound = crossingTimeBound(omega, 0.0, dt);
            const double first = (phase > 0 ? 2 * std::numbers::pi - phase : 0.0) / omega;
            for (std::size_t j = 0; j < t.size(); ++j)
                EXPECT_NEAR(t[j], first + double(j) * 2 * std::numbers::pi / omega, bound + 1e-15) << j;
            EXPECT_NEAR(meanPeriod(t), 2 * std::numbers::pi / omega, 2 * bound / double(t.size() - 1));
        }
    }
    // Damped: the zeros of e^{−at} sin(ω_d t + φ) are those of the sine; the bound includes a.
    const double a = 0.5, dt = 0.02;
    const std::vector<double> u = sampled(a, omega, 0.3, dt, 600);
    const std::vector<double> t = upwardZeroCrossings(u, dt);
    ASSERT_GE(t.size(), 5u);
    for (std::size_t j = 0; j < t.size(); ++j)
        EXPECT_NEAR(t[j], (2 * std::numbers::pi * double(j + 1) - 0.3) / omega,
                    crossingTimeBound(omega, a, dt));
    EXPECT_TRUE(std::isnan(meanPeriod({1.0})));
    EXPECT_TRUE(upwardZeroCrossings({std::nan(""), 1.0, -1.0, std::nan("")}, 1.0).empty());
    EXPECT_TRUE(std::isinf(crossingTimeBound(omega, 0.0, 2.0 / omega))); // ω dt past π/2: no bound
}

TEST(BenchkitOscillator, PeaksAndAmplitudeRatioWithinTheParabolaBound) {
    // Pure sine: every peak is 1, each within peakBound = 3φ⁴/128 (φ = ω dt), the leading term of
    // the parabola's worst sampling phase (oscillator.hpp; at φ <= 2π/8 the higher terms lower it).
    const double omega = std::sqrt(40.0);
    for (double framesPerPeriod : {8.0, 20.0, 49.67}) {
        const double dt = 2 * std::numbers::pi / omega / framesPerPeriod;
        for (double phase : {0.0, 0.3, 1.7, 4.0}) {
            SCOPED_TRACE(std::to_string(framesPerPeriod) + " frames per period, phase " +
                         std::to_string(phase));
            const std::vector<double> u = sampled(0.0, omega, phase, dt, int(10.3 * framesPerPeriod));
            const std::vector<double> peaks = periodPeaks(u, dt, upwardZeroCrossings(u, dt));
            ASSERT_GE(peaks.size(), 9u);
            const double bound = peakBound(omega, 0.0, dt);
            for (double p : peaks) EXPECT_NEAR(p, 1.0, bound);
            EXPECT_NEAR(meanAmplitudeRatio(peaks), 1.0, 2 * bound / double(peaks.size() - 1));
        }
    }
    // The raw largest sample alone would be off by up to 1 − cos(φ/2) ~ φ²/8: 2.0e-3 at 49.67
    // frames per period, 300 times the parabola's 6.0e-6 — the refinement is what resolves
    // amplitude ratios of 1e-5.
    EXPECT_LT(peakBound(omega, 0.0, 2 * std::numbers::pi / omega / 49.67), 6.1e-6);
    // Damped: consecutive peaks of e^{−at} sin(ωt + φ) are e^{−a T} apart exactly; each peak's bias
    // is the same function of its sampling phase plus the decay's aω²dt³/8, so the mean ratio is
    // within 2 peakBound / (peaks − 1) (10 % over it for the terms beyond leading order, which
    // here are a²ω²dt⁴/18 ~ 1e-9 against peakBound ~ 1e-5).
    for (double a : {0.1, 0.5, 2.0}) {
        for (double phase : {0.0, 0.9, 2.2}) {
            SCOPED_TRACE("a " + std::to_string(a) + ", phase " + std::to_string(phase));
            const double dt = 0.02;
            const std::vector<double> u = sampled(a, omega, phase, dt, 520);
            const std::vector<double> peaks = periodPeaks(u, dt, upwardZeroCrossings(u, dt));
            ASSERT_GE(peaks.size(), 8u);
            const double exact = std::exp(-a * 2 * std::numbers::pi / omega);
            EXPECT_NEAR(meanAmplitudeRatio(peaks), exact,
                        1.1 * 2 * peakBound(omega, a, dt) * exact / double(peaks.size() - 1));
        }
    }
    EXPECT_TRUE(std::isnan(meanAmplitudeRatio({1.0})));
    EXPECT_TRUE(std::isnan(meanAmplitudeRatio({1.0, -0.5})));
}

/// Symplectic Euler on m u'' + c u' + k u = 0 in double, recording u every `perFrame` steps.
std::vector<double> symplecticEuler(const DampedOscillator& o, double h, int perFrame, int frames) {
    double u = o.u0, v = o.v0;
    std::vector<double> out{u};
    for (int f = 0; f < frames; ++f) {
        for (int s = 0; s < perFrame; ++s) {
            v += h * (-(o.damping * v + o.stiffness * u) / o.mass);
            u += h * v;
        }
        out.push_back(u);
    }
    return out;
}

/// The estimators, run on `samples` (one per frame of dt) of a discrete map's trajectory, find the
/// map's own period and amplitude ratio per period within their bounds (the ratio's 10 % over
/// 2 peakBound / (peaks − 1) for the terms beyond leading order, as in PeaksAndAmplitudeRatio...).
void expectEstimatorsFind(const std::vector<double>& samples, double dt, double period, double ratio) {
    const std::vector<double> t = upwardZeroCrossings(samples, dt);
    ASSERT_GE(t.size(), 10u);
    const double omega = 2 * std::numbers::pi / period, decay = -std::log(ratio) / period;
    EXPECT_NEAR(meanPeriod(t), period, 2 * crossingTimeBound(omega, decay, dt) / double(t.size() - 1));
    const std::vector<double> peaks = periodPeaks(samples, dt, t);
    EXPECT_NEAR(meanAmplitudeRatio(peaks), ratio,
                1.1 * 2 * peakBound(omega, decay, dt) * ratio / double(peaks.size() - 1));
}

TEST(BenchkitOscillator, SymplecticEulerPeriodAndDampingAreTheDiscreteMapsOwn) {
    // The discrete trajectory of symplectic Euler is itself a sampled damped sinusoid (eigenvalues
    // sqrt(1 − hγ) e^{±iθ}): its measured period and amplitude ratio must be the map's 2πh/θ and
    // (1 − hγ)^{π/θ} within the estimators' bounds, and differ from the continuous ones by the
    // known O(h²) amounts. This checks the formulas the GL test uses, independently of the GPU.
    const double dt = 0.02;
    for (double c : {0.0, 0.2}) {
        for (int substeps : {1, 4}) {
            SCOPED_TRACE("c " + std::to_string(c) + ", substeps " + std::to_string(substeps));
            const DampedOscillator o{1.0, 40.0, c, 0.0, 0.06};
            const double h = dt / substeps;
            const std::vector<double> u = symplecticEuler(o, h, substeps, 500);
            const double period = symplecticEulerPeriod(o, h),
                         ratio = symplecticEulerAmplitudeRatioPerPeriod(o, h);
            expectEstimatorsFind(u, dt, period, ratio);
            if (c == 0.0) {
                // 2 − 2cos θ = h²ω²: θ = 2 asin(hω/2), the period short by (hω)²/24 to leading order.
                const double hw = h * o.omega();
                EXPECT_NEAR(period, 2 * std::numbers::pi * h / (2 * std::asin(hw / 2)), 1e-15);
                EXPECT_NEAR(period / o.period() - 1, -hw * hw / 24, 0.1 * hw * hw / 24);
                EXPECT_EQ(ratio, 1.0); // |λ| = 1: no numerical damping
            }
        }
    }
    // hω >= 2: no oscillation, the map is unstable.
    EXPECT_TRUE(std::isnan(
        symplecticEulerPeriod(DampedOscillator{1.0, 40.0, 0.0, 0.0, 0.06}, 2.0 / std::sqrt(40.0))));
}

TEST(BenchkitOscillator, ImplicitEulerPeriodAndDampingAreTheDiscreteMapsOwn) {
    // Backward Euler solved exactly per step (what one Newton step gives on this linear system):
    // (1 + hγ + h²ω²) v' = v − hω² x, x' = x + h v'. Its frames must show the formulas' period and
    // amplitude ratio within the estimators' bounds; undamped the period is long by (hω)²/3 and
    // the ratio ≈ e^{−πhω}: heavy numerical damping at the frame step, unlike symplectic Euler.
    const double dt = 0.02;
    for (double c : {0.0, 0.2}) {
        for (int substeps : {1, 4}) {
            SCOPED_TRACE("c " + std::to_string(c) + ", substeps " + std::to_string(substeps));
            const DampedOscillator o{1.0, 40.0, c, 0.0, 0.06};
            const double h = dt / substeps, gamma = c / o.mass, w2 = o.omega() * o.omega();
            double u = 0.0, v = o.v0;
            std::vector<double> samples{u};
            for (int f = 0; f < 500; ++f) {
                for (int s = 0; s < substeps; ++s) {
                    v = (v - h * w2 * u) / (1.0 + h * gamma + h * h * w2);
                    u += h * v;
                }
                samples.push_back(u);
            }
            const double period = implicitEulerPeriod(o, h),
                         ratio = implicitEulerAmplitudeRatioPerPeriod(o, h);
            expectEstimatorsFind(samples, dt, period, ratio);
            if (c == 0.0) {
                const double hw = h * o.omega();
                EXPECT_NEAR(period / o.period() - 1, hw * hw / 3, 0.1 * hw * hw / 3);
                EXPECT_NEAR(std::log(ratio), -std::numbers::pi * hw, 0.1 * std::numbers::pi * hw);
            }
        }
    }
}

} // namespace
} // namespace glcollide::benchkit
