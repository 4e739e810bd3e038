// Dynamics benchmark: one explicit substep (NodeForce -> SpringUpdate -> NodeUpdate) of a square
// cloth at 64..512 nodes per side. Iteration time is the GPU time of the step from the engine's
// GL timestamp pairs (notes/platform.md §2.4), fed to Google Benchmark as manual time.
//
// Own flags (everything else goes to Google Benchmark):
//   --device=<selector>      EGL device: auto | software | <index> | cuda:<n> (default: env
//                            GLCOLLIDE_EGL_DEVICE, else auto)
//   --print-renderer-slug    print the file-name slug of GL_RENDERER (e.g. "llvmpipe",
//                            "nvidia-h100") and exit; bench/run_dynamics.sh names its output with it

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/headless_context.hpp>
#include <glcollide/scene.hpp>

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide {
namespace {

constexpr int kWarmUpSteps = 3;
// Pass names as Engine::pipeline() reports them; the counters use the same stems (DESIGN.md
// "Naming": a pass, its shader, its twin, its test and its timer share one stem).
constexpr std::array<std::string_view, 3> kPasses = {"NodeForce", "SpringUpdate", "NodeUpdate"};

/// The default hanging cloth (scenes/hanging_cloth.json) at `side` × `side` nodes, one substep
/// per frame of length `dt` seconds.
Scene clothScene(int side, double dt) {
    const std::string n = std::to_string(side);
    char dtText[64];
    std::snprintf(dtText, sizeof dtText, "%.17g", dt);
    const std::string json = R"({
      "format_version": 1,
      "name": "bench cloth )" + n + "x" + n + R"(",
      "effects": ["gravity", "springs", "damping"],
      "time": {"dt": )" + dtText + R"(, "substeps": 1, "frames": 1},
      "gravity": [0, -9.81, 0],
      "damping": 0.05,
      "objects": [{
        "name": "cloth",
        "generator": {"type": "cloth", "size": [1, 1], "resolution": [)" + n + ", " + n + R"(]},
        "transform": {"translate": [0, 1.5, 0]},
        "mass": 0.3,
        "springs": {"stiffness": 500, "damping": 0.5, "shear_stiffness": 200, "bend_stiffness": 20},
        "pinned": [0, )" + std::to_string(side - 1) + R"(]
      }]
    })";
    return parseScene(json, ".", "dynamics_bench cloth " + n);
}

/// An engine whose single substep per frame is stable: dt is what the engine's own stability rule
/// allows (it already has a 0.9 safety factor), so every step() is exactly one substep.
struct ClothCase {
    int side = 0;
    double dt = 0.0;
    std::unique_ptr<Engine> engine;
};

std::unique_ptr<ClothCase> makeClothCase(int side) {
    auto c = std::make_unique<ClothCase>();
    c->side = side;
    // The stability limit depends on the lumped masses and spring sums, which the engine computes
    // anyway: build once with a generous dt, read the limit, rebuild if it was too long.
    c->dt = 1.0 / 60.0;
    c->engine = std::make_unique<Engine>(clothScene(side, c->dt));
    const double limit = c->engine->substepInfo().maxStableSubstep;
    if (std::isfinite(limit) && c->dt > limit) {
        c->dt = 0.99 * limit; // 0.99: keep ceil(dt / limit) at 1 despite rounding
        c->engine.reset();    // free the first engine's buffers before allocating the second's
        c->engine = std::make_unique<Engine>(clothScene(side, c->dt));
    }
    for (int i = 0; i < kWarmUpSteps; ++i) c->engine->step(); // shader JIT, first-touch pages
    return c;
}

/// Nodes must stay finite and near the start: a blown-up run would time NaN arithmetic.
std::optional<std::string> checkState(const Engine& engine) {
    for (const glm::dvec3& p : engine.readPositions())
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) ||
            std::abs(p.x) > 10.0 || std::abs(p.y) > 10.0 || std::abs(p.z) > 10.0)
            return "cloth blew up (non-finite or far-away node)";
    return std::nullopt;
}

// One case at a time: benchmarks run in registration order, so the next size replaces the
// previous one and the engine of a size is built once however often the runner calls the function.
std::unique_ptr<ClothCase> g_case;
// Set when a benchmark is skipped with an error, so the exit status fails a CI smoke run.
bool g_failed = false;

void fail(benchmark::State& state, const std::string& why) {
    g_failed = true;
    state.SkipWithError(why.c_str());
}

void dynamicsCloth(benchmark::State& state) {
    const int side = static_cast<int>(state.range(0));
    try {
        if (!g_case || g_case->side != side) {
            g_case.reset();
            g_case = makeClothCase(side);
        }
    } catch (const std::exception& e) {
        fail(state, e.what());
        return;
    }
    Engine& engine = *g_case->engine;
    const SubstepInfo& sub = engine.substepInfo();
    if (sub.substeps != 1 || sub.stableSubsteps != 1) {
        fail(state, "expected exactly one stable substep per step");
        return;
    }
    const std::vector<std::string> pipeline = engine.pipeline();
    if (pipeline.size() != kPasses.size()) {
        fail(state, "unexpected pass list (expected NodeForce, SpringUpdate, NodeUpdate)");
        return;
    }
    for (std::size_t k = 0; k < kPasses.size(); ++k)
        if (pipeline[k] != kPasses[k]) {
            fail(state, "unexpected pass " + pipeline[k]);
            return;
        }

    std::array<double, kPasses.size()> passMs{};
    double wallMs = 0.0;
    for (auto _ : state) {
        engine.step();
        const StepStats& s = engine.lastStep();
        double gpuMs = 0.0;
        for (std::size_t k = 0; k < kPasses.size(); ++k) {
            passMs[k] += s.passes[k].gpuMilliseconds;
            gpuMs += s.passes[k].gpuMilliseconds;
        }
        wallMs += s.wallMilliseconds;
        state.SetIterationTime(gpuMs * 1e-3);
    }
    if (const std::optional<std::string> bad = checkState(engine)) {
        fail(state, *bad);
        return;
    }

    const double springs = engine.springCount();
    double gpuMsSum = 0.0;
    for (std::size_t k = 0; k < kPasses.size(); ++k) {
        state.counters[std::string(kPasses[k]) + "_ms"] =
            benchmark::Counter(passMs[k], benchmark::Counter::kAvgIterations);
        gpuMsSum += passMs[k];
    }
    using benchmark::Counter;
    state.counters["gpu_ms"] = Counter(gpuMsSum, Counter::kAvgIterations);
    state.counters["wall_ms"] = Counter(wallMs, Counter::kAvgIterations);
    // ns of GPU time per spring per step: the linearity check compares this across sizes.
    state.counters["gpu_ns_per_spring"] = Counter(gpuMsSum * 1e6 / springs, Counter::kAvgIterations);
    // kIsRate divides by the benchmark's time, which is the manual (GPU) time here.
    state.counters["springs_per_second"] = Counter(springs, Counter::kIsIterationInvariantRate);
    state.counters["nodes"] = engine.nodeCount();
    state.counters["springs"] = springs;
    state.counters["substeps"] = sub.substeps;
    state.counters["dt_s"] = g_case->dt;
}

BENCHMARK(dynamicsCloth)
    ->Name("DynamicsCloth")
    ->ArgName("side")
    ->Arg(64)
    ->Arg(128)
    ->Arg(256)
    ->Arg(512)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

int run(int argc, char** argv) {
    benchmark::Initialize(&argc, argv); // removes the --benchmark_* flags it knows
    bench::Flags flags;
    if (!bench::parseFlags(argc, argv, flags)) return 2;

    // One context for the whole program, current on this (the benchmark) thread.
    HeadlessContext context({.device = flags.device, .debug = false});
    if (flags.printSlug) {
        std::cout << bench::rendererSlug(context.glInfo().renderer) << '\n';
        return 0;
    }
    bench::recordContext(context, "GPU time of one substep = sum of per-pass GL_TIMESTAMP pairs");

    const std::size_t ran = benchmark::RunSpecifiedBenchmarks();
    g_case.reset(); // engine buffers go before the context does
    benchmark::Shutdown();
    // A filter that matches nothing or a skipped case must fail a smoke run, not pass silently.
    return bench::exitCode(argv[0], ran, g_failed);
}

} // namespace
} // namespace glcollide

int main(int argc, char** argv) { return glcollide::bench::guardedMain(argc, argv, glcollide::run); }
