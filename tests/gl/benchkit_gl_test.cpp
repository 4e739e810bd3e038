// The benchmark's experiments on llvmpipe, checked against what their ground truth must give:
// every broad phase misses nothing, robust agrees with the exact oracle, the free-flight error
// of symplectic Euler is the closed form g h T / 2, the oscillator's measured period and
// amplitude decay are symplectic Euler's discrete ones, and the reports carry every run.

#include "benchkit/experiments.hpp"
#include "benchkit/oscillator.hpp"
#include "benchkit/report.hpp"
#include "benchkit/suite.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glcollide/error.hpp>

#include <cmath>
#include <string>

namespace glcollide::benchkit {
namespace {

Experiment only(const std::string& experimentJson) {
    const Suite s = parseSuite(R"({"name": "t", "experiments": [)" + experimentJson + "]}", {}, "test suite");
    return s.experiments.at(0);
}

const RunResult& run(const ExperimentResult& r, const std::string& scene, const std::string& config) {
    for (const RunResult& x : r.runs)
        if (x.scene == scene && x.config == config) return x;
    throw std::runtime_error("no run " + scene + " / " + config);
}

const char* kBoxes = R"({"name": "boxes", "scene": {
  "format_version": 1, "effects": ["springs", "collisions"], "time": {"dt": 0.0001, "substeps": "auto"},
  "collision": {"response": "penalty"},
  "objects": [
    {"name": "a", "generator": {"type": "tet_box", "size": [1, 1, 1], "resolution": [4, 4, 4]}, "mass": 1, "springs": {"stiffness": 100}},
    {"name": "b", "generator": {"type": "tet_box", "size": [1, 1, 1], "resolution": [4, 4, 4]},
     "transform": {"translate": [0.85, 0.05, 0], "rotate_deg": [20, 20, 0]}, "mass": 1, "springs": {"stiffness": 100}}]}})";

TEST(BenchkitGl, EveryBroadPhaseFindsEveryExactlyIntersectingPair) {
    const ExperimentResult r = runExperiment(
        only(std::string(R"({"name": "b", "kind": "broad_phase", "frames": 1, "warmup_frames": 0,
      "scenes": [)") +
             kBoxes + R"(], "configs": [
        {"name": "all", "patch": {"collision": {"broad_phase": "all_pairs"}}},
        {"name": "masked", "patch": {"collision": {"broad_phase": "masked"}}},
        {"name": "d1", "patch": {"collision": {"octree_depth": 1}}},
        {"name": "d3", "patch": {"collision": {"octree_depth": 3}}}]})"),
        nullptr);
    // The four configurations, and the paper's fused TriTri after "all" and "masked".
    ASSERT_EQ(r.runs.size(), 6u);
    EXPECT_EQ(r.runs[1].config, "all (paper: fused TriTri)");
    EXPECT_EQ(r.runs[3].config, "masked (paper: fused TriTri)");
    const double exact = r.runs[0].metric("exact_intersecting_pairs");
    EXPECT_GT(exact, 10) << "the boxes must intersect, or the test proves nothing";
    for (const RunResult& x : r.runs) {
        SCOPED_TRACE(x.config);
        EXPECT_EQ(x.failure, "");
        EXPECT_EQ(x.metric("exact_intersecting_pairs"), exact); // same state: detection moves nothing
        EXPECT_EQ(x.error, 0.0);
        if (x.config.find("(paper") != std::string::npos) {
            // The paper's kernel tests with the fast test: its intersections are not checked here.
            EXPECT_EQ(x.metric("candidate_pairs"), r.runs[0].metric("candidate_pairs"));
            EXPECT_GT(x.time, 0.0);
            continue;
        }
        EXPECT_EQ(x.metric("false_negatives"), 0.0);
        EXPECT_EQ(x.metric("false_positives"), 0.0); // robust precision (the default)
        EXPECT_EQ(x.metric("candidate_pairs"), r.runs[0].metric("candidate_pairs"));
        EXPECT_GT(x.time, 0.0);
    }
}

TEST(BenchkitGl, RobustAgreesWithTheOracleAndFastIsMeasured) {
    const ExperimentResult r = runExperiment(
        only(std::string(R"({"name": "n", "kind": "narrow_phase", "frames": 2, "warmup_frames": 0,
      "scenes": [)") +
             kBoxes + R"(], "configs": [
        {"name": "fast", "patch": {"collision": {"precision": "fast"}}},
        {"name": "robust", "patch": {"collision": {"precision": "robust"}}}],
      "case_families": ["hard"]})"),
        nullptr);
    ASSERT_EQ(r.runs.size(), 4u);
    EXPECT_EQ(run(r, "boxes", "robust").error, 0.0);
    EXPECT_EQ(run(r, "pairs: hard", "robust").error, 0.0);
    // The hard cases are built to break epsilon tests: docs/narrow-phase.md measures 92 of 330
    // disagreements for fast; any nonzero count shows the comparison is live.
    EXPECT_GT(run(r, "pairs: hard", "fast").error, 0.0);
    EXPECT_EQ(run(r, "pairs: hard", "fast").metric("pairs"), run(r, "pairs: hard", "robust").metric("pairs"));
}

TEST(BenchkitGl, FreeFlightErrorIsTheSymplecticEulerClosedForm) {
    // Symplectic Euler under constant g: x_N = x0 + v0 t + g t^2/2 + g h t/2, so the largest node
    // error over frames is |g| h T / 2 at the last frame T. Float rounding of positions of a few
    // metres is ~1e-6 m, far below 1 % of the 5e-3 .. 2e-2 m errors here.
    const ExperimentResult r =
        runExperiment(only(R"({"name": "i", "kind": "integration", "reference": "ballistic",
      "frames": 30, "warmup_frames": 0,
      "scenes": [{"name": "cloth", "scene": {"format_version": 1, "effects": ["gravity", "springs"],
        "time": {"dt": 0.016666666666666666, "substeps": 2},
        "objects": [{"generator": {"type": "cloth", "size": [1, 1], "resolution": [4, 4]}, "velocity": [1, 4, 0],
                     "mass": 0.3, "springs": {"stiffness": 1}}]}}],
      "configs": [{"name": "2"}, {"name": "4", "substep_factor": 2}, {"name": "8", "substep_factor": 4}]})"),
                      nullptr);
    ASSERT_EQ(r.runs.size(), 3u);
    const double T = 30.0 / 60.0;
    for (const RunResult& x : r.runs) {
        SCOPED_TRACE(x.config);
        const double h = (1.0 / 60.0) / x.substeps;
        EXPECT_NEAR(x.error, 0.5 * 9.81 * h * T, 0.01 * 0.5 * 9.81 * h * T);
    }
}

/// The suites' oscillator body: a 2x2 cloth of 3 kg, nodes 0, 1 and 3 pinned, so node 2 (lumped
/// a third of the area: 1 kg) hangs on the 0.1 m spring to node 0 and a 30 m one to node 3,
/// started along the first at 0.06 m/s.
std::string oscillatorScene(const std::string& name, const std::string& springs,
                            const std::string& effects = "", const std::string& pinned = "[0, 1, 3]") {
    return R"({"name": ")" + name + R"(", "scene": {"format_version": 1, "effects": ["springs")" + effects +
           R"(], "time": {"dt": 0.02, "substeps": 1},
        "objects": [{"generator": {"type": "cloth", "size": [30, 0.1], "resolution": [2, 2]},
          "transform": {"translate": [15, 0.05, 0]}, "mass": 3, "velocity": [0, 0.06, 0],
          "springs": {)" +
           springs + R"(, "bend_stiffness": 0}, "pinned": )" + pinned + "}]}}";
}

TEST(BenchkitGl, OscillatorPeriodAndDampingAreSymplecticEulersDiscreteOnes) {
    // Symplectic Euler's frames are samples of the discrete map's own sinusoid: period 2πh/θ with
    // 2 − 2cos θ = h²ω² undamped (cos θ = (2 − hγ − h²ω²) / (2 sqrt(1 − hγ)) damped), amplitude
    // factor (1 − hγ)^{π/θ} per period (oscillator.hpp, unit-tested against a double-precision
    // run of the map). The GPU run must measure exactly those, within the estimators' sampling
    // bounds (period_resolution_s, amplitude_ratio_resolution, computed by the run) plus 1e-6 for
    // float: the state's rounding is ~ulp(0.1 m) = 7.5e-9 m against the 9.5 mm amplitude, the 30 m
    // perpendicular spring shifts the frequency by 3(A/w)²/16 = 2e-8.
    const ExperimentResult r = runExperiment(
        only(
            R"({"name": "o", "kind": "integration", "reference": "oscillator", "frames": 500, "warmup_frames": 0,
      "scenes": [)" +
            oscillatorScene("undamped", R"("stiffness": 40, "shear_stiffness": 0)") + ", " +
            oscillatorScene("damped", R"("stiffness": 40, "damping": 0.2, "shear_stiffness": 0)") + R"(],
      "configs": [{"name": "1", "patch": {"time": {"substeps": 1}}}, {"name": "2", "patch": {"time": {"substeps": 2}}}]})"),
        nullptr);
    ASSERT_EQ(r.runs.size(), 4u);
    for (const RunResult& x : r.runs) {
        SCOPED_TRACE(x.scene + " / " + x.config);
        ASSERT_EQ(x.failure, "");
        const DampedOscillator o{1.0, 40.0, x.scene == "damped" ? 0.2 : 0.0, 0.0, 0.06};
        // The free node's mass is the lumped third of 3 kg: the closed form's amplitude v0/ω_d.
        EXPECT_NEAR(x.metric("amplitude_exact_m"), o.amplitude(), 1e-15);
        EXPECT_EQ(x.metric("periods_measured"), 10.0);
        const double h = 0.02 / x.substeps;
        const double period = symplecticEulerPeriod(o, h);
        const double tolerance = x.metric("period_resolution_s") + 1e-6 * period;
        EXPECT_LT(x.metric("period_resolution_s"), 1.1e-5); // 49.7 frames per period, 10 periods
        EXPECT_NEAR(x.metric("period_s"), period, tolerance);
        // The test can tell: the continuous period is (hω)²/24 ~ 1.7e-4 .. 6.7e-4 away.
        EXPECT_GT(std::abs(x.metric("period_exact_s") - period), 10 * tolerance);
        EXPECT_NEAR(x.metric("period_error_relative"), (x.metric("period_s") - o.period()) / o.period(),
                    1e-12);
        const double ratio = symplecticEulerAmplitudeRatioPerPeriod(o, h);
        EXPECT_NEAR(x.metric("amplitude_ratio_per_period"), ratio,
                    x.metric("amplitude_ratio_resolution") + 1e-6);
        EXPECT_NEAR(x.metric("numerical_damping_per_period"),
                    o.amplitudeRatioPerPeriod() - x.metric("amplitude_ratio_per_period"), 1e-15);
        if (x.scene == "damped") {
            EXPECT_GT(o.amplitudeRatioPerPeriod() - ratio, 1.5e-5); // the numerical damping is resolved
        }
        EXPECT_LT(x.metric("max_off_axis_m"), 1e-5);
        EXPECT_GT(x.metric("gpu_ms_per_simulated_second"), 0.0);
        EXPECT_NEAR(x.metric("gpu_ms_per_simulated_second"), x.gpuMs.median / 0.02, 1e-9);
        EXPECT_TRUE(std::isfinite(x.metric("energy_drift_relative", std::nan(""))));
    }
}

TEST(BenchkitGl, OscillatorPeriodAndDampingAreImplicitEulersDiscreteOnes) {
    // Implicit Euler (Baraff & Witkin, one Newton step per substep: exact backward Euler on this
    // linear spring; CG on one free node with its 3x3 block preconditioner converges at once) has
    // period 2πh/θ, θ = atan(hω) undamped, and amplitude ratio (1 + hγ + h²ω²)^{−π/θ} per period
    // (oscillator.hpp, unit-tested against a double run of the map): 0.673 at one substep, where
    // symplectic Euler keeps 1. Same tolerances as symplectic Euler's test. At most 2 CG
    // iterations: one converges here, and each allowed one costs two dispatches per substep.
    const auto experiment = [] {
        return only(R"({"name": "o", "kind": "integration", "reference": "oscillator", "frames": 500,
      "warmup_frames": 0, "scenes": [)" +
                    oscillatorScene("undamped", R"("stiffness": 40, "shear_stiffness": 0)") + ", " +
                    oscillatorScene("damped", R"("stiffness": 40, "damping": 0.2, "shear_stiffness": 0)") +
                    R"(], "configs": [
        {"name": "1", "patch": {"time": {"integrator": "implicit_euler", "substeps": 1, "solver": {"tolerance": 1e-5, "max_iterations": 2}}}},
        {"name": "4", "patch": {"time": {"integrator": "implicit_euler", "substeps": 4, "solver": {"tolerance": 1e-5, "max_iterations": 2}}}}]})");
    };
    const ExperimentResult r = runExperiment(experiment(), nullptr);
    ASSERT_EQ(r.runs.size(), 4u);
    for (const RunResult& x : r.runs) {
        SCOPED_TRACE(x.scene + " / " + x.config);
        ASSERT_EQ(x.failure, "");
        const DampedOscillator o{1.0, 40.0, x.scene == "damped" ? 0.2 : 0.0, 0.0, 0.06};
        const double h = 0.02 / x.substeps;
        const double period = implicitEulerPeriod(o, h), ratio = implicitEulerAmplitudeRatioPerPeriod(o, h);
        const double tolerance = x.metric("period_resolution_s") + 1e-6 * period;
        EXPECT_NEAR(x.metric("period_s"), period, tolerance);
        EXPECT_GT(std::abs(x.metric("period_exact_s") - period), 10 * tolerance);
        EXPECT_NEAR(x.metric("amplitude_ratio_per_period"), ratio,
                    x.metric("amplitude_ratio_resolution") + 1e-6);
        // Heavy numerical damping: 0.30-0.33 of the amplitude per period at one substep, 0.086-0.095 at four.
        EXPECT_GT(x.metric("numerical_damping_per_period"), 0.08);
        EXPECT_LT(x.metric("max_off_axis_m"), 1e-5);
    }
}

TEST(BenchkitGl, UnstableOscillatorIsReportedAsDiverged) {
    // 129,600 N/m on 1 kg: ω = 360 rad/s, h ω = 6 at one substep of 1/60 s, beyond symplectic
    // Euler's limit 2: the state overflows within frames. 4 substeps (hω = 1.5) stay stable.
    const ExperimentResult r = runExperiment(
        only(
            R"({"name": "o", "kind": "integration", "reference": "oscillator", "frames": 30, "warmup_frames": 0,
      "scenes": [)" +
            oscillatorScene("stiff", R"("stiffness": 129600, "shear_stiffness": 0)") + R"(],
      "configs": [{"name": "1", "patch": {"time": {"substeps": 1, "dt": 0.016666666666666666}}},
                  {"name": "4", "patch": {"time": {"substeps": 4, "dt": 0.016666666666666666}}}]})"),
        nullptr);
    ASSERT_EQ(r.runs.size(), 2u);
    EXPECT_THAT(r.runs[0].failure, ::testing::StartsWith("diverged: "));
    EXPECT_EQ(r.runs[1].failure, "");
    EXPECT_LT(r.runs[1].metric("max_displacement_m"), 2 * r.runs[1].metric("amplitude_exact_m"));
    EXPECT_LT(r.runs[1].metric("frames_per_period"), 8.0); // too coarse to measure a period:
    EXPECT_TRUE(std::isnan(r.runs[1].metric("period_s", std::nan(""))));
}

TEST(BenchkitGl, OscillatorReferenceRejectsOtherBodies) {
    const auto errorOf = [](const std::string& scene) -> std::string {
        try {
            runExperiment(only(R"({"name": "o", "kind": "integration", "reference": "oscillator", "frames": 1,
              "scenes": [)" + scene +
                               R"(], "configs": [{"name": "c"}]})"),
                          nullptr);
        } catch (const Error& e) {
            return e.what();
        }
        return "no error";
    };
    const std::string k = R"("stiffness": 40, "shear_stiffness": 0)";
    EXPECT_THAT(errorOf(oscillatorScene("g", k, R"(, "gravity")")),
                ::testing::HasSubstr("effect gravity is on"));
    EXPECT_THAT(errorOf(oscillatorScene("two", k, "", "[0, 1]")), ::testing::HasSubstr("2 free nodes"));
    // The shear spring from node 2 to pinned node 1 runs diagonally.
    EXPECT_THAT(errorOf(oscillatorScene("shear", R"("stiffness": 40)")),
                ::testing::HasSubstr("neither along nor across the velocity"));
}

TEST(BenchkitGl, ReportsCarryEveryRun) {
    const Experiment x = only(R"({"name": "s", "kind": "scaling", "frames": 2, "warmup_frames": 0,
      "scenes": [
        {"name": "small", "scene": {"format_version": 1, "effects": ["gravity", "springs"],
          "objects": [{"generator": {"type": "cloth", "size": [1, 1], "resolution": [4, 4]}, "mass": 0.3, "springs": {"stiffness": 10}}]}},
        {"name": "large", "scene": {"format_version": 1, "effects": ["gravity", "springs"],
          "objects": [{"generator": {"type": "cloth", "size": [1, 1], "resolution": [16, 16]}, "mass": 0.3, "springs": {"stiffness": 10}}]}}],
      "configs": [{"name": "dynamics"}]})");
    const ExperimentResult r = runExperiment(x, nullptr);
    ASSERT_EQ(r.runs.size(), 2u);
    EXPECT_EQ(r.runs[1].faces, 2u * 15u * 15u);
    EXPECT_EQ(r.runs[0].passNames, (std::vector<std::string>{"SpringUpdate", "NodeUpdate"}));
    EXPECT_EQ(r.runs[0].frames, 2);
    EXPECT_EQ(r.runs[0].gpuMs.samples, 2u);
    EXPECT_THAT(textTable(r), ::testing::HasSubstr("large"));
    const std::vector<PlotFile> files = plots(r);
    ASSERT_EQ(files.size(), 1u);
    EXPECT_EQ(files[0].name, "s.svg");
    EXPECT_THAT(files[0].svg, ::testing::HasSubstr("dynamics"));
}

TEST(BenchkitGl, BvhExperimentCandidatesAgreeEverywhere) {
    const Experiment x = only(R"({"name": "bvh", "kind": "bvh", "frames": 2, "warmup_frames": 1,
      "table_faces": [600], "scaling_faces": [300, 1200], "engine_configs": ["octree d2"],
      "configs": [
        {"name": "bvh", "patch": {"collision": {"broad_phase": "bvh", "bvh": {"rebuild": "substep"}}}},
        {"name": "all pairs", "patch": {"collision": {"broad_phase": "all_pairs"}}},
        {"name": "octree d2", "patch": {"collision": {"broad_phase": "octree", "octree_depth": 2}}}]})");
    const ExperimentResult r = runExperiment(x, nullptr);
    // Per size: three detection runs and one engine run.
    ASSERT_EQ(r.runs.size(), 3u * 4u);
    for (const RunResult& run : r.runs) {
        ASSERT_EQ(run.failure, "") << run.scene << " / " << run.config;
        if (run.metric("engine_step") == 1) {
            EXPECT_GT(run.metric("gpu_ms_per_substep"), 0.0);
            continue;
        }
        // The CPU brute force is the reference at these sizes, and every configuration matches it.
        EXPECT_EQ(run.metric("cpu_checked"), 1.0);
        EXPECT_EQ(run.metric("candidate_pairs"), run.metric("reference_candidate_pairs"));
        EXPECT_GT(run.metric("candidate_pairs"), 5.0 * run.faces) << run.scene; // the layers touch
        EXPECT_EQ(run.error, 0.0);
        if (run.config != "all pairs") { // all pairs has no buffers of its own
            EXPECT_GT(run.metric("broad_phase_bytes_per_face"), 0.0);
        }
        EXPECT_EQ(run.metric("feature_pairs_without_ownership"), 15.0 * run.metric("candidate_pairs"));
        EXPECT_GT(run.metric("feature_pairs_with_ownership"), 0.0);
        EXPECT_LT(run.metric("feature_pairs_with_ownership"), run.metric("feature_pairs_without_ownership"));
        // The GPU's Representative-Triangle expansion gives the CPU's counts with ownership.
        EXPECT_EQ(run.metric("vf_pairs_gpu"), run.metric("vf_pairs_with_ownership"));
        EXPECT_EQ(run.metric("ee_pairs_gpu"), run.metric("ee_pairs_with_ownership"));
        EXPECT_EQ(run.metric("feature_pairs_without_ownership_gpu"),
                  run.metric("feature_pairs_without_ownership"));
        EXPECT_GT(run.metric("feature_pairs_ms"), 0.0);
        if (run.config == "bvh") { // rebuilt every substep: every timed detection builds
            EXPECT_GT(run.metric("build_ms"), 0.0);
            EXPECT_EQ(run.metric("bvh_rebuilt_last"), 1.0);
            EXPECT_LE(run.metric("broad_phase_bytes_per_face"), 192.0);
        }
    }
    // The seed-table layout, its printed numbers, slopes, memory and feature-pair tables.
    std::vector<std::string> titles;
    for (const SummaryTable& t : r.tables) titles.push_back(t.title);
    EXPECT_THAT(titles, ::testing::Contains(::testing::HasSubstr("Seed Tables 1-3 layout")));
    EXPECT_THAT(titles, ::testing::Contains(::testing::HasSubstr("Cost exponent")));
    EXPECT_THAT(titles, ::testing::Contains(::testing::HasSubstr("Memory")));
    EXPECT_THAT(titles, ::testing::Contains(::testing::HasSubstr("Feature pairs")));
    bool equal = false, featuresEqual = false, octreeSlope = false, bvhSlope = false;
    for (const Metric& m : r.summary) {
        if (m.key == "candidates_equal_in_every_configuration") equal = m.value == 1.0;
        if (m.key == "feature_pairs_gpu_equal_cpu_in_every_run") featuresEqual = m.value == 1.0;
        if (m.key == "slope_detection/octree d2") octreeSlope = std::isfinite(m.value);
        if (m.key == "slope_detection/bvh") bvhSlope = std::isfinite(m.value);
    }
    EXPECT_TRUE(equal);
    EXPECT_TRUE(featuresEqual);
    EXPECT_TRUE(octreeSlope);
    EXPECT_TRUE(bvhSlope);
    EXPECT_THAT(textTable(r), ::testing::HasSubstr("23.94 ms"));
    const std::vector<PlotFile> files = plots(r);
    ASSERT_EQ(files.size(), 1u);
    EXPECT_EQ(files[0].name, "bvh.svg");
}

} // namespace
} // namespace glcollide::benchkit
