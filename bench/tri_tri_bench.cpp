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

std::string gitCommit() {
    std::string out;
    if (FILE* pipe = popen("git -C '" GLCOLLIDE_BENCH_SOURCE_DIR "' rev-parse --short HEAD 2>/dev/null", "r")) {
        char buf[64];
        while (std::fgets(buf, sizeof buf, pipe)) out += buf;
        pclose(pipe);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    return out.empty() ? std::string(GLCOLLIDE_BENCH_CONFIGURE_COMMIT) + " (configure time)" : out;
}

int run(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    std::string device;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg.rfind("--device=", 0) == 0) {
            device = std::string(arg.substr(9));
        } else {
            std::cerr << argv[0] << ": unknown argument " << arg << " (own flag: --device=<selector>)\n";
            return 2;
        }
    }
    HeadlessContext context({.device = device, .debug = false});
    benchmark::AddCustomContext("gl_renderer", context.glInfo().renderer);
    benchmark::AddCustomContext("gl_version", context.glInfo().version);
    benchmark::AddCustomContext("egl_device", context.deviceDescription());
    benchmark::AddCustomContext("git_commit", gitCommit());
    benchmark::AddCustomContext("glcollide_build_type", GLCOLLIDE_BENCH_BUILD_TYPE);
    benchmark::AddCustomContext("timing", "GPU time of one dispatch over all pairs (GL_TIMESTAMP pair)");
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
    if (ran == 0) {
        std::cerr << argv[0] << ": no benchmark matched\n";
        return 1;
    }
    return g_failed ? 1 : 0;
}

} // namespace
} // namespace glcollide

int main(int argc, char** argv) {
    try {
        return glcollide::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << argv[0] << ": " << e.what() << '\n';
        return 1;
    }
}
