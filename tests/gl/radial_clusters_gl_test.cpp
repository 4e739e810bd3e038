// Radial view-based culling of a surface that no single observer sees from inside (issue 24;
// docs/culling.md, "Clusters"): a flat sheet, cut into clusters of its rest shape, each closed by a
// skirt and an apex behind it and watched by an observer of its own. Against independent answers:
// the ghost nodes and observers against the double-precision formulas (model::ghostNodePosition
// and model::loopFrame, which the shader mirrors in float), the free mask against the twin
// (cpu::radialFreeFaces over the same real and ghost faces with the GPU's ghost nodes and observers,
// bit for bit where the GPU evaluates the GLSL as written), and the free faces against the exact
// TriTri oracle along a fold of the sheet through itself: no free face intersects a face of its own
// cluster at any of eight times of the substep (the theorem's scope; pairs of two clusters are never
// culled).

#include "model/flat_model.hpp"
#include "model/surface_clusters.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/radial_culling.hpp"
#include "cpu/radial_twin.hpp"
#include "support/glsl_as_written.hpp"
#include "support/radial_culling_run.hpp"

#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace glcollide {
namespace {

/// A 1 m square sheet in the XY plane (faces toward +Z), 24 × 24 nodes: 1,058 faces.
model::FlatModel sheetModel() {
    const std::string json =
        R"({"format_version": 1, "effects": ["gravity"], "time": {"dt": 0.01, "frames": 1},
      "objects": [{"name": "sheet", "generator": {"type": "cloth", "size": [1, 1], "resolution": [24, 24]},
                   "mass": 1}]})";
    return model::flatten(parseScene(json, ".", "sheet"));
}

passes::RadialCullingConfig sheetClusters(const model::FlatModel& model) {
    return passes::radialCullingConfig(
        model,
        {std::numeric_limits<double>::infinity(), RadialObservers::Clusters, std::numbers::pi / 4.0, 64, {}});
}

std::vector<glm::vec3> floats(const std::vector<glm::dvec3>& xs) {
    return {xs.begin(), xs.end()};
}

/// The GPU's ghost nodes and observers at one end of the substep against the double formulas at
/// the float positions. Float sums of n <= 100 terms of size <= 2 m err by at most n · 2^-24 · 2 m
/// (about 1.2e-5 m); the direction's normalisation and the product with depth · radius (<= 3 · 2 ·
/// 0.7 m here) scale that by under 10: 2e-4 m bounds both with margin.
void expectGhostsWhereTheFormulasPutThem(const passes::RadialCullingConfig& config,
                                         const test::CullingRun& run, const std::vector<glm::vec3>& x,
                                         bool end) {
    constexpr double kTolerance = 2e-4;
    const std::vector<glm::dvec3> xd(x.begin(), x.end());
    const passes::RadialGhosts& g = config.ghosts;
    ASSERT_EQ(run.ghostNodes.size(), g.nodes.size());
    for (std::size_t k = 0; k < g.nodes.size(); ++k) {
        const passes::RadialGhostNode& n = g.nodes[k];
        const std::vector<std::uint32_t> loop(g.loopNodes.begin() + n.loopFirst,
                                              g.loopNodes.begin() + n.loopFirst + n.loopCount);
        const model::ClusterGhostNode node{0, n.kind, n.hang, static_cast<double>(n.depth)};
        const glm::dvec3 expected = model::ghostNodePosition(node, {loop}, xd);
        const glm::dvec3 got(end ? run.ghostNodes[k].end : run.ghostNodes[k].start);
        EXPECT_LT(glm::length(got - expected), kTolerance) << "ghost node " << k;
        if (n.observerOf == passes::kNoRadialObserver) continue;
        std::vector<glm::dvec3> at;
        for (std::uint32_t v : loop) at.push_back(xd[v]);
        const model::LoopFrame f = model::loopFrame(at);
        const glm::dvec3 observer = f.mean - static_cast<double>(n.observerDepth) * f.radius * f.axis;
        const glm::dvec3 gotObserver(end ? run.observers[n.observerOf].end
                                         : run.observers[n.observerOf].start);
        EXPECT_LT(glm::length(gotObserver - observer), kTolerance) << "observer " << n.observerOf;
    }
}

/// Every real face's observer and the twin's free faces over the real and ghost faces.
std::vector<std::uint8_t> twinFree(const model::FlatModel& model, const passes::RadialCullingConfig& config,
                                   const test::CullingRun& run, const std::vector<glm::vec3>& x0,
                                   const std::vector<glm::vec3>& x1) {
    const test::ClosedByGhosts all = test::closedByGhosts(model, config, run, x0, x1);
    std::vector<glm::vec3> observers;
    for (const passes::RadialObserver& o : run.observers) observers.insert(observers.end(), {o.start, o.end});
    const std::vector<std::uint8_t> twin =
        cpu::radialFreeFaces(all.faces, all.x0, all.x1, all.observers, observers);
    return {twin.begin(), twin.begin() + static_cast<std::ptrdiff_t>(model.faceCount())};
}

TEST(RadialClustersGl, AFlatSheetIsCutIntoClustersWatchedFromBehind) {
    const model::FlatModel model = sheetModel();
    const passes::RadialCullingConfig config = sheetClusters(model);
    // Flat: one cluster without a size limit; 64-face clusters here, every one closed.
    EXPECT_EQ(passes::radialCullingConfig(model, {std::numeric_limits<double>::infinity(),
                                                  RadialObservers::Clusters,
                                                  std::numbers::pi / 4.0,
                                                  0,
                                                  {}})
                  .clusters,
              1u);
    // "auto" cuts the flat sheet into clusters too (its border's fan closes it with no inside; a
    // sleeve, which its cuffs' fans close around an inside, keeps one observer: the engine's
    // RadialCullingGl.ATwistingSleeveIsBitIdenticalWithAndWithoutCulling counts its 32 fan faces).
    EXPECT_EQ(passes::radialCullingConfig(model, passes::RadialObserverSettings{}).clusters, config.clusters);
    EXPECT_GT(config.clusters, 10u);
    EXPECT_EQ(config.openClusters, 0u);
    EXPECT_EQ(config.surfaces.size(), config.clusters);
    for (std::uint32_t o : config.faceObserver) EXPECT_NE(o, passes::kNoRadialObserver);
    // Without clusters the sheet is one object closed by a flat fan over its border ("objects"),
    // or nothing at all when the border stays open.
    EXPECT_EQ(passes::radialCullingConfig(model, 0.0).surfaces.size(), 0u);

    // Standing still: every cluster wound once around its observer, the ghosts where the formulas put them,
    // and every face the twin frees is free on the GPU (bit for bit where GLSL runs as written).
    const std::vector<glm::vec3> x0 = floats(model.positions);
    const test::CullingRun run = test::runCulling(model, config, x0, x0);
    expectGhostsWhereTheFormulasPutThem(config, run, x0, false);
    expectGhostsWhereTheFormulasPutThem(config, run, x0, true);
    EXPECT_EQ(run.violatedStat, 0u);
    for (const passes::RadialWinding& w : run.winding) {
        EXPECT_EQ(w.number, 1) << "every cluster winds once around its observer";
        EXPECT_FALSE(w.undecided);
    }
    const std::vector<std::uint8_t> twin = twinFree(model, config, run, x0, x0);
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(run.free, twin);
    }
    std::printf("%u clusters, %u of %zu faces free at rest\n", config.clusters, run.freeCount,
                model.faceCount());
    EXPECT_GT(run.freeCount, model.faceCount() / 2) << "a flat sheet's clusters must free most of it";
}

// The sheet folded through itself within one substep: the part beyond x = 0.1 turns over onto the
// part before it and ends tilted across it, so faces of the clusters along the hinge intersect
// faces of their own cluster. No free face may be among them.
TEST(RadialClustersGl, ASheetFoldedThroughItselfFreesNothingThatIntersectsItsCluster) {
    const model::FlatModel model = sheetModel();
    const passes::RadialCullingConfig config = sheetClusters(model);
    const std::vector<glm::vec3> x0 = floats(model.positions);
    std::vector<glm::vec3> x1 = x0;
    for (glm::vec3& p : x1)
        if (p.x > 0.1f) p = {0.2f - p.x, p.y, 0.25f * p.y};
    const test::CullingRun run = test::runCulling(model, config, x0, x1);
    expectGhostsWhereTheFormulasPutThem(config, run, x1, true);
    EXPECT_EQ(run.violatedStat, 0u) << "the flat start winds once around every observer";
    const std::vector<std::uint8_t> twin = twinFree(model, config, run, x0, x1);
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(run.free, twin);
    }
    std::printf("%u of %zu faces free in the fold\n", run.freeCount, model.faceCount());
    EXPECT_GT(run.freeCount, model.faceCount() / 4) << "the clusters away from the fold stay free";
    EXPECT_LT(run.freeCount, model.faceCount());
    EXPECT_GT(test::expectFreeFacesIntersectNothing(model, x0, x1, run.free, config.faceObserver), 0u)
        << "the fold must really intersect within a cluster, or the test shows nothing";
}

} // namespace
} // namespace glcollide
