// Collision-detection benchmark: the three broad phases of CollisionDetection (AABB-octree at
// depth 1-3, the paper's masked scheme, all pairs; seeds/002) on two tet boxes pushed into each
// other, at about 2.4k, 4.8k and 12k surface faces per body. Per-pass GPU time (BBUpdate,
// BBCollision, TriTri) comes from GL_TIMESTAMP pairs (gl::GpuTimer) and is the manual time fed to
// Google Benchmark; the counters give the sizes: box pairs, candidate pairs, intersecting pairs,
// the number of triangle tests each mode runs, and tests per intersecting pair.
//
// Own flags (everything else goes to Google Benchmark):
//   --device=<selector>   EGL device: auto | software | <index> | cuda:<n>
// Run: bench/run_collision.sh (writes bench/results/<renderer-slug>-collision.json).

#include "cpu/collision_twin.hpp"
#include "cpu/flat_model.hpp"
#include "gl/gpu_timer.hpp"
#include "passes/collision_detection.hpp"
#include "scene/scene_detail.hpp"

#include <glcollide/gl_info.hpp>
#include <glcollide/headless_context.hpp>

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace glcollide {
namespace {

constexpr int kWarmUp = 1; // shader JIT (llvmpipe compiles at the first dispatch) and list growth

/// Two unit tet boxes of `cells`^3 cells (12 cells^2 surface faces each); the second is turned by
/// 20 degrees about (1, 1, 1) (no coplanar contact) and pushed 0.15 m into the first along x.
struct Case {
    int cells = 0;
    cpu::FlatModel model;
    passes::DeviceBuffers buffers;
};

std::unique_ptr<Case> makeCase(int cells) {
    auto c = std::make_unique<Case>();
    c->cells = cells;
    Scene scene;
    scene.bodies.push_back(detail::generateTetBox({1, 1, 1}, {cells, cells, cells}));
    Body b = detail::generateTetBox({1, 1, 1}, {cells, cells, cells});
    const glm::dmat4 rotate = glm::rotate(glm::dmat4(1.0), glm::radians(20.0), glm::normalize(glm::dvec3(1, 1, 1)));
    for (glm::dvec3& p : b.positions) p = glm::dvec3(rotate * glm::dvec4(p, 1.0)) + glm::dvec3(0.85 + 0.2, 0.05, 0.0);
    scene.bodies.push_back(std::move(b));
    c->model = cpu::flatten(scene);
    std::vector<glm::vec4> p;
    for (const glm::dvec3& x : c->model.positions) p.emplace_back(glm::vec3(x), 1.0f);
    c->buffers.nodeCount = static_cast<std::uint32_t>(p.size());
    c->buffers.faceCount = static_cast<std::uint32_t>(c->model.faceCount());
    c->buffers.positions = gl::Buffer("positions", p.size() * sizeof(glm::vec4), p.data());
    c->buffers.faces = gl::Buffer("faces", c->model.faceIndices.size() * sizeof(std::uint32_t), c->model.faceIndices.data());
    return c;
}

std::unique_ptr<Case> g_case;
bool g_failed = false;

/// Triangle tests a mode runs: octree = candidates; masked = valid pairs in overlapping leaf-box
/// pairs (from the twin's leaf boxes); all pairs = valid pairs.
double testedPairs(BroadPhase mode, const passes::CollisionDetection& d, const Case& c,
                   const passes::CollisionCounts& counts) {
    if (mode == BroadPhase::Octree) return counts.candidates;
    const auto& objects = c.model.objects;
    if (mode == BroadPhase::AllPairs) return double(objects[0].faceCount) * double(objects[1].faceCount);
    std::vector<glm::vec3> p;
    for (const glm::dvec3& x : c.model.positions) p.emplace_back(x);
    const cpu::OctreeLayout& layout = d.layout();
    const auto boxes = cpu::twinLeafBoxes(layout, c.model.faceIndices, p, 0.01);
    double tests = 0;
    for (std::uint32_t i = 0; i < layout.boxCount; ++i)
        for (std::uint32_t j = i + 1; j < layout.boxCount; ++j)
            if (i / layout.boxesPerObject != j / layout.boxesPerObject && cpu::boxesOverlap(boxes[i], boxes[j]))
                tests += double(layout.boxFaces.offsets[i + 1] - layout.boxFaces.offsets[i]) *
                         double(layout.boxFaces.offsets[j + 1] - layout.boxFaces.offsets[j]);
    return tests;
}

void collision(benchmark::State& state) {
    const int cells = static_cast<int>(state.range(0));
    const auto mode = static_cast<BroadPhase>(state.range(1));
    const int depth = static_cast<int>(state.range(2));
    const auto precision = static_cast<TriTriPrecision>(state.range(3));
    try {
        if (!g_case || g_case->cells != cells) {
            g_case.reset();
            g_case = makeCase(cells);
        }
        passes::CollisionConfig config;
        config.betweenObjects = true;
        config.settings.broadPhase = mode;
        config.settings.octreeDepth = depth;
        config.settings.precision = precision;
        config.settings.thickness = 0.01;
        passes::CollisionDetection detection(config, g_case->model);
        const std::vector<std::string> names = detection.passNames();
        gl::GpuTimer timer(names.size());
        for (int i = 0; i < kWarmUp; ++i) detection.detect(g_case->buffers, nullptr, 0);
        std::vector<double> passMs(names.size(), 0.0);
        passes::CollisionCounts counts;
        for (auto _ : state) {
            timer.beginFrame();
            counts = detection.detect(g_case->buffers, &timer, 0);
            const std::vector<double> ms = timer.resolveMilliseconds();
            double total = 0.0;
            for (std::size_t k = 0; k < ms.size(); ++k) {
                passMs[k] += ms[k];
                total += ms[k];
            }
            state.SetIterationTime(total * 1e-3);
        }
        using benchmark::Counter;
        double sum = 0.0;
        for (std::size_t k = 0; k < names.size(); ++k) {
            state.counters[names[k] + "_ms"] = Counter(passMs[k], Counter::kAvgIterations);
            sum += passMs[k];
        }
        state.counters["gpu_ms"] = Counter(sum, Counter::kAvgIterations);
        state.counters["faces_per_body"] = g_case->model.objects[0].faceCount;
        state.counters["box_pairs"] = counts.boxPairs;
        state.counters["candidates"] = counts.candidates;
        state.counters["intersections"] = counts.intersections;
        state.counters["exact_fallbacks"] = counts.exactFallbacks;
        state.counters["reruns"] = counts.reruns;
        const double tests = testedPairs(mode, detection, *g_case, counts);
        state.counters["tri_tests"] = tests;
        state.counters["tests_per_intersection"] = counts.intersections ? tests / counts.intersections : 0.0;
        if (counts.intersections == 0) {
            g_failed = true;
            state.SkipWithError("the bodies do not intersect: the scene is wrong");
        }
    } catch (const std::exception& e) {
        g_failed = true;
        state.SkipWithError(e.what());
    }
}

void registerCases() {
    const int robust = static_cast<int>(TriTriPrecision::Robust);
    const int octree = static_cast<int>(BroadPhase::Octree), masked = static_cast<int>(BroadPhase::Masked),
              all = static_cast<int>(BroadPhase::AllPairs);
    auto add = [](const std::string& name, std::vector<std::int64_t> args) {
        benchmark::RegisterBenchmark(name.c_str(), collision)
            ->Args(args)
            ->ArgNames({"cells", "mode", "depth", "precision"})
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(3);
    };
    // 14 cells: 2352 faces per body; 20: 4800; 32: 12288 (mode 0 octree, 1 masked, 2 all pairs).
    for (int cells : {14, 20, 32}) {
        for (int depth = 1; depth <= 3; ++depth) add("Octree", {cells, octree, depth, robust});
        add("Octree", {cells, octree, 2, static_cast<int>(TriTriPrecision::Fast)});
        if (cells <= 20) {
            add("Masked", {cells, masked, 2, robust});
            add("AllPairs", {cells, all, 2, robust});
        }
    }
    // 92 cells: 101 568 faces per body, 203 136 in all (the 200k+ size): octree only (all
    // pairs would test 10^10 face pairs per call, minutes on llvmpipe).
    for (int depth = 2; depth <= 3; ++depth) add("Octree", {92, octree, depth, robust});
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
    bench::recordContext(context, "GPU time of one detect() = sum of per-pass GL_TIMESTAMP pairs");
    benchmark::AddCustomContext("scene", "two unit tet boxes, the second turned 20 deg about (1,1,1) and pushed "
                                         "0.15 m into the first; collisions between objects, thickness 0.01 m");
    registerCases();
    const std::size_t ran = benchmark::RunSpecifiedBenchmarks();
    g_case.reset();
    benchmark::Shutdown();
    return bench::exitCode(argv[0], ran, g_failed);
}

} // namespace
} // namespace glcollide

int main(int argc, char** argv) { return glcollide::bench::guardedMain(argc, argv, glcollide::run); }
