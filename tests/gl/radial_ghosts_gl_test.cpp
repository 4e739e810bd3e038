// Radial view-based culling on an open surface (issue 24, items 2 and 4; docs/culling.md, "Ghost
// triangles" and "Violated triangles"): a sleeve (the tube generator) is closed by a fan of ghost
// triangles over each opening, and the culling pass runs over the real and the ghost faces.
// Against independent answers: the ghost nodes against the double-precision mean of their loops
// (model::ghostNodePositions), the free mask against the twin (cpu::radialFreeFaces over the same
// real and ghost faces, bit for bit where the GPU evaluates the GLSL as written), the free faces
// against the exact TriTri oracle along the motion (a free face intersects nothing), and the
// observer check (RadialWinding) against its twin: a real face that crosses a ghost fan at the
// start of the substep (cpu::radialViolatedPairs, exact) is never free, and a surface that does not
// wind once around its observer frees nothing.

#include "cpu/collision_twin.hpp"
#include "cpu/radial_twin.hpp"
#include "model/flat_model.hpp"
#include "model/ghost_triangles.hpp"
#include "passes/collision/append_lists.hpp"
#include "passes/radial_culling.hpp"
#include "support/radial_culling_run.hpp"
#include "support/glsl_as_written.hpp"

#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

namespace glcollide {
namespace {

using test::closedByGhosts;
using test::ClosedByGhosts;
using test::CullingRun;
using test::expectFreeFacesIntersectNothing;
using test::runCulling;

constexpr std::uint32_t kAround = 24, kAlong = 10;

/// The tube generator's sleeve: radius 0.1 m, 0.4 m long around Y, 24 × 10 nodes (432 faces).
model::FlatModel sleeveModel() {
    const std::string json =
        R"({"format_version": 1, "effects": ["gravity"], "time": {"dt": 0.01, "frames": 1},
      "objects": [{"name": "sleeve", "generator": {"type": "tube", "radius": 0.1, "length": 0.4,
                   "resolution": [24, 10]}, "mass": 1}]})";
    return model::flatten(parseScene(json, ".", "sleeve"));
}

/// Decided winding numbers, one per observer, as RadialCullingPass::readWinding gives them.
std::vector<passes::RadialWinding> wound(std::initializer_list<std::int32_t> numbers) {
    std::vector<passes::RadialWinding> out;
    for (std::int32_t n : numbers) out.push_back({n, false});
    return out;
}

std::vector<glm::vec3> floats(const std::vector<glm::dvec3>& xs) {
    return {xs.begin(), xs.end()};
}

/// The ghost nodes against the double mean of their loops. A fixed-order float sum of n terms of
/// size <= m is within n * 2^-24 * m of the exact sum (Higham §4.2), the division adds one more
/// rounding of the mean: (n + 2) * 2^-24 * m bounds the error of the mean.
void expectGhostNodesAreLoopMeans(const passes::RadialCullingConfig& config,
                                  const std::vector<passes::RadialObserver>& gpu,
                                  const std::vector<glm::vec3>& x, bool end) {
    const passes::RadialGhosts& g = config.ghosts;
    ASSERT_EQ(gpu.size(), g.nodes.size());
    for (std::size_t k = 0; k < gpu.size(); ++k) {
        glm::dvec3 mean(0.0);
        double largest = 0.0;
        const std::uint32_t first = g.nodes[k].loopFirst, last = first + g.nodes[k].loopCount;
        for (std::uint32_t i = first; i < last; ++i) {
            const glm::dvec3 p(x[g.loopNodes[i]]);
            mean += p;
            largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        }
        mean /= static_cast<double>(last - first);
        const double bound = (last - first + 2.0) * std::ldexp(1.0, -24) * largest;
        const glm::vec3 got = end ? gpu[k].end : gpu[k].start;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], mean[c], bound) << "ghost node " << k << ", axis " << c;
    }
}

TEST(RadialGhostsGl, ASleeveClosedByGhostsFreesWhatTheTwinFreesAndNothingThatIntersects) {
    const model::FlatModel model = sleeveModel();
    const auto faces = static_cast<std::uint32_t>(model.faceCount());
    const passes::RadialCullingConfig config =
        passes::radialCullingConfig(model, std::numeric_limits<double>::infinity());
    // Both openings are closed: one observer, two ghost nodes, a fan of 24 ghost faces over each.
    ASSERT_EQ(config.surfaces.size(), 1u);
    EXPECT_EQ(config.ghosts.nodes.size(), 2u);
    EXPECT_EQ(config.ghosts.faceObserver.size(), 2 * kAround);
    // Without ghosts the open sleeve gets no observer at all.
    EXPECT_TRUE(passes::radialCullingConfig(model, 0.0).surfaces.empty());
    // A threshold between the perimeter (2π · 0.1 m ≈ 0.63 m) and nothing leaves both open.
    EXPECT_TRUE(passes::radialCullingConfig(model, 0.6).surfaces.empty());

    // The motion: every ring twisted about the axis by up to 0.6 rad, and a patch of one side near
    // the top shoved 0.26 m through the axis and out through the far wall (it crosses the far
    // side's faces late in the substep). The patch passes above the observer (the centroid, near
    // the middle): one through the observer would void condition (b) and free nothing.
    const std::vector<glm::vec3> x0 = floats(model.positions);
    std::vector<glm::vec3> x1 = x0;
    for (std::size_t i = 0; i < x1.size(); ++i) {
        const float angle = 0.6f * static_cast<float>(i / kAround) / (kAlong - 1);
        const float c = std::cos(angle), s = std::sin(angle);
        x1[i] = {c * x0[i].x - s * x0[i].z, x0[i].y, s * x0[i].x + c * x0[i].z};
        if (x0[i].x > 0.06f && x0[i].y > 0.08f && x0[i].y < 0.18f) x1[i].x -= 0.26f;
    }
    const CullingRun run = runCulling(model, config, x0, x1);
    expectGhostNodesAreLoopMeans(config, run.ghostNodes, x0, false);
    expectGhostNodesAreLoopMeans(config, run.ghostNodes, x1, true);
    ASSERT_EQ(run.winding, wound({1}));
    EXPECT_EQ(run.violatedStat, 0u);

    // The twin over the same real and ghost faces, with the GPU's ghost nodes and observer.
    const ClosedByGhosts all = closedByGhosts(model, config, run, x0, x1);
    EXPECT_TRUE(cpu::radialViolatedPairs(all.faces, faces, all.x0).empty());
    const std::vector<std::uint8_t> twin = cpu::radialFreeFaces(
        all.faces, all.x0, all.x1, all.observers, {run.observers[0].start, run.observers[0].end});
    const std::vector<std::uint8_t> twinReal(twin.begin(), twin.begin() + faces);
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(run.free, twinReal);
    }
    EXPECT_GT(run.freeCount, faces / 4) << "the ghosts must let culling free most of the sleeve";
    EXPECT_LT(run.freeCount, faces) << "the shoved patch must leave faces that are not free";

    // On every device: no face the GPU calls free intersects another face of the sleeve at any of
    // eight times of the substep (exact oracle), and the motion really does intersect.
    EXPECT_GT(expectFreeFacesIntersectNothing(model, x0, x1, run.free), 0u)
        << "the shove must really intersect, or the test shows nothing";

    // The same sleeve with every face wound the other way round: its closed surface winds inward
    // (negative signed volume), the classification turns its faces round, and it is culled like
    // its outward twin (decision 0025, "Orientation"; without the turn nothing would be free).
    model::FlatModel inward = model;
    for (std::size_t f = 0; f < inward.faceCount(); ++f)
        std::swap(inward.faceIndices[3 * f + 1], inward.faceIndices[3 * f + 2]);
    const passes::RadialCullingConfig inwardConfig =
        passes::radialCullingConfig(inward, std::numeric_limits<double>::infinity());
    ASSERT_EQ(inwardConfig.surfaces.size(), 1u);
    EXPECT_FALSE(config.surfaces[0].inward);
    EXPECT_TRUE(inwardConfig.surfaces[0].inward);
    const CullingRun turned = runCulling(inward, inwardConfig, x0, x1);
    EXPECT_GT(turned.freeCount, faces / 4) << "an inward-wound sleeve must be culled too";
    EXPECT_GT(expectFreeFacesIntersectNothing(inward, x0, x1, turned.free), 0u);
}

// A ghost fan that folds past the observer within the substep: the top opening's ring is mirrored
// (x -> -x), so it passes through a line at mid-substep and its fan turns over: every face of that
// fan is not positive (the case the other tests never reach: a GPU that left ghost faces
// unclassified, or took them as positive, would differ from the twin only here), while most of
// the sleeve below stays free. The GPU's free faces must be the twin's over the real and ghost
// faces with the GPU's ghost nodes, and intersect nothing at eight times of the substep (exact
// oracle; the top band's faces, twisted by half a turn, do intersect each other).
TEST(RadialGhostsGl, AGhostFanFoldingPastTheObserverIsNotPositiveAndTheFreeFacesStaySafe) {
    const model::FlatModel model = sleeveModel();
    const auto faces = static_cast<std::uint32_t>(model.faceCount());
    const passes::RadialCullingConfig config =
        passes::radialCullingConfig(model, std::numeric_limits<double>::infinity());
    const std::vector<glm::vec3> x0 = floats(model.positions);
    std::vector<glm::vec3> x1 = x0;
    for (std::size_t i = (kAlong - 1) * kAround; i < kAlong * kAround; ++i) x1[i].x = -x0[i].x;
    const CullingRun run = runCulling(model, config, x0, x1);
    ASSERT_EQ(run.observers.size(), 1u);
    EXPECT_EQ(run.winding, wound({1}));

    const ClosedByGhosts all = closedByGhosts(model, config, run, x0, x1);
    const std::vector<glm::vec3> observer = {run.observers[0].start, run.observers[0].end};
    const std::vector<std::uint32_t> positive =
        cpu::radialPositiveMask(all.faces, all.x0, all.x1, all.observers, observer);
    std::uint32_t ghostsNotPositive = 0;
    for (std::size_t f = faces; f < all.observers.size(); ++f)
        ghostsNotPositive += (positive[f / 32] >> (f % 32) & 1u) == 0u;
    std::printf("%u of %zu ghost faces not positive, %u of %u real faces free\n", ghostsNotPositive,
                config.ghosts.faceObserver.size(), run.freeCount, faces);
    ASSERT_EQ(ghostsNotPositive, kAround) << "the top fan turns over: none of its faces can be positive";
    EXPECT_GT(run.freeCount, faces / 2) << "the sleeve below the fold stays free";
    const std::vector<std::uint8_t> twin =
        cpu::radialFreeFaces(all.faces, all.x0, all.x1, all.observers, observer);
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(run.free, std::vector<std::uint8_t>(twin.begin(), twin.begin() + faces));
    }
    EXPECT_GT(expectFreeFacesIntersectNothing(model, x0, x1, run.free), 0u)
        << "the half turn must really intersect, or the test shows nothing";
}

// A real face that crosses a ghost fan at the start of the substep: the closed surface is not
// embedded. The theorem needs no embedding, only that the surface winds once around the observer
// (RadialWinding, decision 0025 "The winding number"): then the crossing faces are never free, the
// faces away from them may be. Node 0 of the second ring is pulled up over the centre of the top
// opening: the faces from it down to the third ring pierce the top fan. And a surface that does not
// wind once (the same sleeve classified as if wound inward: -1) frees nothing.
TEST(RadialGhostsGl, AGhostCrossedByARealFaceAtTheStartIsNeverFree) {
    const model::FlatModel model = sleeveModel();
    const auto faces = static_cast<std::uint32_t>(model.faceCount());
    const passes::RadialCullingConfig config =
        passes::radialCullingConfig(model, std::numeric_limits<double>::infinity());
    std::vector<glm::vec3> x0 = floats(model.positions);
    x0[kAround] = {0.01f, 0.23f, 0.005f};

    // The start has no intersecting real faces (the engine's invariant; exact oracle) ...
    const std::vector<std::uint32_t> faceObject(faces, 0u);
    const auto atStart = cpu::twinIntersectionsAlongMotion(model.faceIndices, faceObject, x0, x0,
                                                           cpu::PairRules{false, true}, 1);
    ASSERT_TRUE(atStart.at(0).empty()) << atStart[0].size() << " real pairs intersect at the start";

    const CullingRun run = runCulling(model, config, x0, x0);
    // ... but real faces cross the ghost fan (the exact twin finds the pairs); the surface still
    // winds once around its observer (the GPU and the twin agree), so culling goes on, and no face
    // of a crossing pair is free.
    const ClosedByGhosts all = closedByGhosts(model, config, run, x0, x0);
    const std::vector<cpu::RadialFacePair> violated = cpu::radialViolatedPairs(all.faces, faces, all.x0);
    ASSERT_FALSE(violated.empty());
    const std::vector<glm::vec3> observer{run.observers[0].start};
    const std::vector<cpu::RadialWindingNumber> twin =
        cpu::radialWindingNumbers(all.faces, all.x0, all.observers, observer, {false});
    ASSERT_EQ(twin.size(), 1u);
    EXPECT_EQ(twin[0].number, run.winding.at(0).number);
    EXPECT_EQ(twin[0].undecided, run.winding.at(0).undecided);
    ASSERT_EQ(run.winding, wound({1}));
    EXPECT_EQ(run.violatedStat, 0u);
    for (const cpu::RadialFacePair& p : violated) {
        EXPECT_GE(p[1], faces) << "a violated pair has a ghost face";
        EXPECT_FALSE(run.free[p[0]]) << "face " << p[0] << " crosses ghost face " << p[1] - faces
                                     << ", yet is free";
    }
    EXPECT_GT(run.freeCount, 0u);
    EXPECT_LT(run.freeCount, faces);

    // Classified as if wound inward, the surface winds -1 around its observer: nothing is free.
    passes::RadialCullingConfig turned = config;
    turned.surfaces[0].inward = true;
    const CullingRun wrong = runCulling(model, turned, floats(model.positions), floats(model.positions));
    EXPECT_EQ(wrong.winding, wound({-1}));
    EXPECT_EQ(wrong.violatedStat, 1u);
    EXPECT_EQ(wrong.freeCount, 0u) << "a surface that does not wind once freed faces";

    // The same start without the pulled node: wound once, and every face free.
    const CullingRun straight = runCulling(model, config, floats(model.positions), floats(model.positions));
    EXPECT_EQ(straight.winding, wound({1}));
    EXPECT_EQ(straight.freeCount, faces);
}

// Real data we did not make: DEDO's face mask (scenes/meshes/mask_0.obj; a rim and two ear-loop
// holes, its faces wound inward). All three loops closed by fans, it is one closed surface; at rest
// no real face crosses a fan (exact twin and GPU agree), the orientation turns it round, and with
// the observer at its nodes' centroid every face is free.
TEST(RadialGhostsGl, TheDedoMaskAtRestIsClosedByItsFansAndFree) {
    const Scene scene = loadScene(std::string(GLCOLLIDE_SOURCE_DIR) + "/scenes/mask_fold.json");
    const model::FlatModel model = model::flatten(scene);
    const passes::RadialCullingConfig config =
        passes::radialCullingConfig(model, std::numeric_limits<double>::infinity());
    ASSERT_EQ(config.surfaces.size(), 2u); // the ball and the mask
    const passes::RadialSurface& mask = config.surfaces[1];
    EXPECT_EQ(config.ghosts.nodes.size(), 3u) << "three loops, three ghost nodes";
    EXPECT_EQ(mask.ghostFaceCount, 94u + 41u + 41u);
    EXPECT_TRUE(mask.inward);
    const std::vector<glm::vec3> x0 = floats(model.positions);
    const CullingRun run = runCulling(model, config, x0, x0);
    const ClosedByGhosts all = closedByGhosts(model, config, run, x0, x0);
    const std::vector<cpu::RadialFacePair> violated =
        cpu::radialViolatedPairs(all.faces, model.faceCount(), all.x0);
    for (const cpu::RadialFacePair& p : violated)
        ADD_FAILURE() << "faces " << p[0] << " and " << p[1] << " cross";
    EXPECT_EQ(run.winding, wound({1, 1}));
    EXPECT_EQ(run.freeCount, model.faceCount());
}

TEST(RadialGhostsGl, InconsistentGhostTablesAreRefused) {
    const model::FlatModel model = sleeveModel();
    passes::RadialCullingConfig config =
        passes::radialCullingConfig(model, std::numeric_limits<double>::infinity());
    passes::RadialCullingConfig badNode = config;
    badNode.ghosts.loopNodes[0] = static_cast<std::uint32_t>(model.nodeCount());
    EXPECT_THROW(passes::RadialCullingPass{badNode}, Error);
    passes::RadialCullingConfig badFace = config;
    badFace.ghosts.faces[2] = static_cast<std::uint32_t>(model.nodeCount() + 2); // only 2 ghost nodes
    EXPECT_THROW(passes::RadialCullingPass{badFace}, Error);
    passes::RadialCullingConfig badCount = config;
    badCount.ghosts.faceObserver.pop_back();
    EXPECT_THROW(passes::RadialCullingPass{badCount}, Error);
}

} // namespace
} // namespace glcollide
