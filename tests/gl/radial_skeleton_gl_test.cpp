// Skeletons of radial culling (issue 24; docs/culling.md, "Skeletons"): an object's "skeleton", one
// segment per bone; each face is watched by the bone nearest it at rest, each bone's faces closed by
// fans over all their loops. On the device, against independent answers: an elbow (a tube bent by
// 90 degrees, scenes/elbow.json's shape) is cut into one piece per bone, each wound once around its
// bone's first end; the GPU frees what the twin frees (where the GPU evaluates the GLSL as written)
// and most of the still elbow, where neither its centroid nor a segment between its openings frees
// anything (neither lies inside the bent tube); folded through itself, no face it frees intersects a
// face of its own piece at any of eight times of the substep (exact oracle); a bone outside its piece,
// or poking out of it, frees nothing of that piece.

#include "cpu/radial_twin.hpp"
#include "model/flat_model.hpp"
#include "passes/radial_culling.hpp"
#include "support/glsl_as_written.hpp"
#include "support/radial_culling_run.hpp"

#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <cstdio>
#include <utility>
#include <string>
#include <vector>

namespace glcollide {
namespace {

/// scenes/elbow.json's tube and skeleton (32 × 31 nodes, 1,920 faces), in place; with
/// `skeleton` false, no skeleton.
Scene elbowScene(bool skeleton) {
    const std::string bones = skeleton ? R"(, "skeleton": [[[0, 0.27, 0], [0, 0.1, 0]],
        [[0.1273, -0.0273, 0], [0.2973, -0.0273, 0]]])"
                                       : "";
    const std::string json = R"({"format_version": 1, "effects": ["springs", "self_collisions"],
      "time": {"dt": 0.01, "frames": 1}, "collision": {"culling": "radial"},
      "objects": [{"name": "elbow", "mass": 0.05, "springs": {"stiffness": 40},
                   "generator": {"type": "tube", "radius": 0.06, "length": 0.6, "resolution": [32, 31],
                                 "bend_deg": 90})" +
                             bones + "}]}";
    return parseScene(json, ".", "elbow");
}

passes::RadialCullingConfig skeletonConfig(const model::FlatModel& model, const Scene& scene) {
    passes::RadialObserverSettings settings;
    for (const Body& b : scene.bodies)
        settings.objectSkeletons.emplace_back(b.skeleton.begin(), b.skeleton.end());
    return passes::radialCullingConfig(model, settings);
}

std::vector<glm::vec3> floats(const std::vector<glm::dvec3>& xs) {
    return {xs.begin(), xs.end()};
}

/// The twin's free faces over the real and ghost faces, with the GPU's observers and bones.
std::vector<std::uint8_t> twinFree(const model::FlatModel& model, const passes::RadialCullingConfig& config,
                                   const test::CullingRun& run, const std::vector<glm::vec3>& x0,
                                   const std::vector<glm::vec3>& x1) {
    const test::ClosedByGhosts all = test::closedByGhosts(model, config, run, x0, x1);
    std::vector<glm::vec3> observers;
    cpu::RadialSegmentEnds ends;
    for (const passes::RadialObserver& o : run.observers) {
        observers.insert(observers.end(), {o.start, o.end});
        EXPECT_TRUE(o.segment.has_value());
        if (o.segment)
            ends.insert(ends.end(), {glm::vec4((*o.segment)[0], 1.0f), glm::vec4((*o.segment)[1], 1.0f)});
    }
    const std::vector<std::uint8_t> twin =
        cpu::radialFreeFaces(all.faces, all.x0, all.x1, all.observers, observers, ends);
    return {twin.begin(), twin.begin() + static_cast<std::ptrdiff_t>(model.faceCount())};
}

// As for user points (radial_user_observer_gl_test.cpp): four float weights up to about 2 times
// coordinates below 1 m, summed in float: 1e-5 m bounds the rounding with margin.
constexpr double kFloatTolerance = 1e-5;

TEST(RadialSkeletonGl, AStillElbowIsWatchedPieceByPieceByItsBones) {
    const Scene scene = elbowScene(true);
    const model::FlatModel model = model::flatten(scene);
    const passes::RadialCullingConfig config = skeletonConfig(model, scene);
    ASSERT_EQ(config.surfaces.size(), 2u);
    EXPECT_EQ(config.clusters, 2u);
    EXPECT_EQ(config.openClusters, 0u);
    for (std::uint32_t o : config.faceObserver) EXPECT_NE(o, passes::kNoRadialObserver);
    const std::vector<glm::vec3> x0 = floats(model.positions);
    const test::CullingRun run = test::runCulling(model, config, x0, x0);
    ASSERT_EQ(run.observers.size(), 2u);
    for (std::size_t o = 0; o < 2; ++o) {
        SCOPED_TRACE(o);
        const std::array<glm::dvec3, 2>& bone = scene.bodies[0].skeleton[o];
        EXPECT_EQ(run.winding[o], (passes::RadialWinding{1, false}));
        ASSERT_TRUE(run.observers[o].segment.has_value());
        // The first end at both ends of the substep, then the second end at both.
        EXPECT_LT(glm::length(glm::dvec3(run.observers[o].start) - bone[0]), kFloatTolerance);
        EXPECT_LT(glm::length(glm::dvec3(run.observers[o].end) - bone[0]), kFloatTolerance);
        EXPECT_LT(glm::length(glm::dvec3((*run.observers[o].segment)[0]) - bone[1]), kFloatTolerance);
        EXPECT_LT(glm::length(glm::dvec3((*run.observers[o].segment)[1]) - bone[1]), kFloatTolerance);
    }
    EXPECT_EQ(run.violatedStat, 0u);
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(run.free, twinFree(model, config, run, x0, x0));
    }
    std::printf("[elbow] still: %u of %zu faces free with the skeleton\n", run.freeCount, model.faceCount());
    // The cut runs along the ring in the middle of the arc (31 rings: ring 15), so its fan is flat
    // and seen face-on from both bones: every face is proven in front and free.
    EXPECT_EQ(run.freeCount, model.faceCount());
    RecordProperty("still_free_skeleton", static_cast<int>(run.freeCount));

    // Without the skeleton: the centroid of the bent tube lies outside it (winding 0, nothing free);
    // one segment between the openings leaves the tube at the bend (nothing free either).
    const model::FlatModel plainModel = model::flatten(elbowScene(false));
    const test::CullingRun centroid = test::runCulling(
        plainModel, passes::radialCullingConfig(plainModel, passes::RadialObserverSettings{}), x0, x0);
    ASSERT_EQ(centroid.winding.size(), 1u);
    EXPECT_EQ(centroid.winding[0].number, 0);
    EXPECT_EQ(centroid.freeCount, 0u);
    passes::RadialObserverSettings chord;
    chord.objectObservers = {glm::dvec3(0, 0.27, 0)};
    chord.objectObserverEnds = {glm::dvec3(0.2973, -0.0273, 0)};
    const test::CullingRun segment =
        test::runCulling(plainModel, passes::radialCullingConfig(plainModel, chord), x0, x0);
    EXPECT_EQ(segment.freeCount, 0u);
}

// The elbow folded through itself within one substep: the top of the forearm's far part (x > 0.23)
// is shoved back by 0.12 m along −x and 0.05 m down, through the sides of the forearm's near part —
// faces of one piece intersect.
// No face the pass frees may be among them; the upper arm, far from the fold, stays free.
TEST(RadialSkeletonGl, AnElbowFoldedThroughItselfFreesNothingThatIntersectsItsPiece) {
    const Scene scene = elbowScene(true);
    const model::FlatModel model = model::flatten(scene);
    const passes::RadialCullingConfig config = skeletonConfig(model, scene);
    const std::vector<glm::vec3> x0 = floats(model.positions);
    std::vector<glm::vec3> x1 = x0;
    for (glm::vec3& p : x1)
        if (p.x > 0.23f && p.y > -0.0273f) p += glm::vec3(-0.12f, -0.05f, 0.0f);
    const test::CullingRun run = test::runCulling(model, config, x0, x1);
    EXPECT_EQ(run.violatedStat, 0u) << "the still start winds once around every bone";
    if (test::deviceEvaluatesGlslAsWritten()) {
        EXPECT_EQ(run.free, twinFree(model, config, run, x0, x1));
    }
    std::printf("[elbow] folded: %u of %zu faces free\n", run.freeCount, model.faceCount());
    EXPECT_GT(run.freeCount, model.faceCount() / 4) << "the upper arm and the bend stay free";
    EXPECT_LT(run.freeCount, model.faceCount());
    EXPECT_GT(test::expectFreeFacesIntersectNothing(model, x0, x1, run.free, config.faceObserver), 0u)
        << "the fold must really intersect within a piece, or the test shows nothing";
}

// Built to defeat the skeleton: the forearm's bone moved 0.2 m off the limb (its piece does not wind
// around it: the failed premise is counted and the piece frees nothing), and one that pokes out of
// the forearm's opening (the faces it passes through meet every footprint: nothing of the piece is
// free). The upper arm, watched by its own bone, stays free in both.
TEST(RadialSkeletonGl, ABoneOutsideItsPieceFreesNothingOfIt) {
    Scene scene = elbowScene(true);
    const model::FlatModel model = model::flatten(scene);
    const std::vector<glm::vec3> x0 = floats(model.positions);
    std::array<glm::dvec3, 2>& forearm = scene.bodies[0].skeleton[1];
    const std::array<glm::dvec3, 2> inside = forearm;
    for (const auto& [bone, windsOnce] :
         {std::pair{
              std::array<glm::dvec3, 2>{inside[0] + glm::dvec3(0, 0, 0.2), inside[1] + glm::dvec3(0, 0, 0.2)},
              false},
          std::pair{std::array<glm::dvec3, 2>{inside[0], inside[1] + glm::dvec3(0.1, 0, 0)}, true}}) {
        forearm = bone;
        const passes::RadialCullingConfig config = skeletonConfig(model, scene);
        ASSERT_EQ(config.surfaces.size(), 2u);
        const test::CullingRun run = test::runCulling(model, config, x0, x0);
        EXPECT_EQ(run.winding[0], (passes::RadialWinding{1, false}));
        EXPECT_EQ(run.winding[1].number == 1 && !run.winding[1].undecided, windsOnce);
        EXPECT_EQ(run.violatedStat, windsOnce ? 0u : 1u);
        std::uint32_t upperFree = 0, forearmFree = 0;
        for (std::size_t f = 0; f < model.faceCount(); ++f)
            (config.faceObserver[f] == 0 ? upperFree : forearmFree) += run.free[f];
        EXPECT_EQ(forearmFree, 0u);
        EXPECT_GT(upperFree, 0u);
    }
}

} // namespace
} // namespace glcollide
