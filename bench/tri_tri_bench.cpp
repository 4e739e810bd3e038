// Narrow-phase benchmark: fast vs robust triangle-triangle tests (shaders/common/tri_tri.glsl via
// the TriTriQuery pass) on the random and near-degenerate sets of src/cpu/tri_tri_cases.cpp.
// Iteration time is the GPU time of one dispatch over all pairs of a set (GL_TIMESTAMP pair),
// fed to Google Benchmark as manual time; wall time around dispatch + glFinish is a counter.
// Counters per case: ns per pair (GPU and wall), intersecting fraction, robust's exact fallbacks
// per pair, and fast's disagreements with the exact oracle (count and fraction).
//
// Own flag: --device=<selector> (default: env GLCOLLIDE_EGL_DEVICE, else auto).
// bench/results/llvmpipe-tritri.json was written with
//   glcollide_bench_tritri --benchmark_min_time=1 --benchmark_out=... --benchmark_out_format=json

#include "cpu/tri_tri_cases.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/handles.hpp"
#include "gl/layout.hpp"
#include "passes/tri_tri_query_pass.hpp"

#include <glcollide/headless_context.hpp>

#include "bench_support.hpp"

#include <benchmark/benchmark.h>
#include <epoxy/gl.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide {
namespace {

constexpr std::size_t kPairs = 16384;

struct SetData {
    std::vector<cpu::FloatTriPair> pairs;
    std::vector<std::uint8_t> exact;
};

std::map<cpu::TriTriSet, SetData> g_sets;
std::map<passes::TriTriPrecision, std::unique_ptr<passes::TriTriQueryPass>> g_passes;
bool g_failed = false;

const SetData& setData(cpu::TriTriSet set) {
    auto it = g_sets.find(set);
    if (it != g_sets.end()) return it->second;
    SetData d;
    d.pairs = cpu::randomTriTriPairs(set, kPairs, 1000u + static_cast<std::uint32_t>(set));
    for (const auto& p : d.pairs) d.exact.push_back(cpu::exactPairIntersects(p) ? 1 : 0);
    return g_sets.emplace(set, std::move(d)).first->second;
}

const passes::TriTriQueryPass& pass(passes::TriTriPrecision precision) {
    auto& p = g_passes[precision];
    if (!p) p = std::make_unique<passes::TriTriQueryPass>(precision);
    return *p;
}

void triTri(benchmark::State& state, passes::TriTriPrecision precision, cpu::TriTriSet set) {
    const SetData& data = setData(set);
    const passes::TriTriQueryPass& p = pass(precision);
    // Answers and fallback count from one checked run (also compiles and warms up).
    const passes::TriTriQueryResult checked = p.run(data.pairs);
    std::size_t wrong = 0, hits = 0;
    for (std::size_t i = 0; i < data.exact.size(); ++i) {
        wrong += checked.intersect[i] != data.exact[i] ? 1 : 0;
        hits += data.exact[i];
    }
    if (precision == passes::TriTriPrecision::Robust && wrong != 0) {
        g_failed = true;
        state.SkipWithError("robust disagrees with the oracle");
        return;
    }
    const auto n = static_cast<std::uint32_t>(data.pairs.size());
    const gl::Buffer triangles("bench_triangles", data.pairs.size() * sizeof(cpu::FloatTriPair), data.pairs.data());
    const gl::Buffer results("bench_results", data.pairs.size() * sizeof(std::uint32_t));
    const std::uint32_t zero = 0;
    const gl::Buffer stats("bench_stats", sizeof(zero), &zero);
    triangles.bindStorage(GLC_BIND_QUERY_TRIANGLES);
    results.bindStorage(GLC_BIND_QUERY_RESULTS);
    stats.bindStorage(GLC_BIND_QUERY_STATS);
    gl::GpuTimer timer(1);
    double gpuMs = 0.0, wallMs = 0.0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        timer.beginFrame();
        timer.begin(0);
        p.dispatch(n);
        timer.end(0);
        glFinish();
        const auto t1 = std::chrono::steady_clock::now();
        const double ms = timer.resolveMilliseconds()[0];
        gpuMs += ms;
        wallMs += std::chrono::duration<double, std::milli>(t1 - t0).count();
        state.SetIterationTime(ms * 1e-3);
    }
    using benchmark::Counter;
    const double pairs = static_cast<double>(n);
    state.counters["pairs"] = pairs;
    state.counters["gpu_ns_per_pair"] = Counter(gpuMs * 1e6 / pairs, Counter::kAvgIterations);
    state.counters["wall_ns_per_pair"] = Counter(wallMs * 1e6 / pairs, Counter::kAvgIterations);
    state.counters["intersecting_fraction"] = static_cast<double>(hits) / pairs;
    state.counters["exact_fallbacks_per_pair"] = static_cast<double>(checked.exactFallbacks) / pairs;
    state.counters["disagreements_vs_oracle"] = static_cast<double>(wrong);
    state.counters["disagreement_fraction"] = static_cast<double>(wrong) / pairs;
}

int run(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    bench::Flags flags;
    if (!bench::parseFlags(argc, argv, flags)) return 2;
    HeadlessContext context({.device = flags.device, .debug = false});
    if (flags.printSlug) {
        std::cout << bench::rendererSlug(context.glInfo().renderer) << '\n';
        return 0;
    }
    bench::recordContext(context, "GPU time of one dispatch over all pairs (GL_TIMESTAMP pair)");
    for (auto precision : {passes::TriTriPrecision::Fast, passes::TriTriPrecision::Robust}) {
        for (cpu::TriTriSet set : cpu::kAllTriTriSets) {
            const std::string name = std::string("TriTri/") + passes::toString(precision) + "/" + cpu::toString(set);
            benchmark::RegisterBenchmark(name.c_str(), [precision, set](benchmark::State& s) { triTri(s, precision, set); })
                ->UseManualTime()
                ->Unit(benchmark::kMillisecond);
        }
    }
    const std::size_t ran = benchmark::RunSpecifiedBenchmarks();
    g_passes.clear(); // programs go before the context does
    benchmark::Shutdown();
    return bench::exitCode(argv[0], ran, g_failed);
}

} // namespace
} // namespace glcollide

int main(int argc, char** argv) { return glcollide::bench::guardedMain(argc, argv, glcollide::run); }
