// User observers of radial culling (issue 24; docs/culling.md, "User observers"): a point the scene
// gives an object ("observer"), tied to four of its nodes by model::observerFrame. Against
// independent answers: the GPU's observer at both ends of a substep against the double formula
// Σ w_k·x_k at the float positions, and against the affine map itself when the object moves
// affinely (the frame must carry the point exactly); an observer inside a ball frees faces, one
// placed outside it (a case built to defeat the observer) frees none, whatever its faces' signs —
// the observer check (winding number 0) switches the surface off; and objects that cannot carry one
// are refused with the object named.

#include "model/flat_model.hpp"
#include "model/observer_frame.hpp"
#include "passes/radial_culling.hpp"
#include "support/radial_culling_run.hpp"

#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <string>
#include <vector>

namespace glcollide {
namespace {

/// A closed cloth ball of radius 0.15 m (320 faces) centred at the origin.
model::FlatModel ballModel() {
    const std::string json =
        R"({"format_version": 1, "effects": ["gravity"], "time": {"dt": 0.01, "frames": 1},
      "objects": [{"name": "ball", "generator": {"type": "sphere", "radius": 0.15, "subdivisions": 2},
                   "mass": 1}]})";
    return model::flatten(parseScene(json, ".", "ball"));
}

passes::RadialCullingConfig withObserver(const model::FlatModel& model, const glm::dvec3& point) {
    passes::RadialObserverSettings settings;
    settings.objectObservers = {point};
    return passes::radialCullingConfig(model, settings);
}

std::vector<glm::vec3> floats(const std::vector<glm::dvec3>& xs) {
    return {xs.begin(), xs.end()};
}

/// Σ w_k·x_k of the configuration's frame at positions x (double).
glm::dvec3 framePoint(const passes::RadialSurface& s, const std::vector<glm::vec3>& x) {
    glm::dvec3 p(0.0);
    for (std::size_t k = 0; k < 4; ++k)
        p += static_cast<double>(s.frameWeights[k]) * glm::dvec3(x[s.frameNodes[k]]);
    return p;
}

// The frame's four weights are rounded to float and the sum Σ w_k·x_k of four terms of size up to
// about 2 (weights) × 1.2 m (positions) is rounded in float: 1e-5 m bounds both with margin.
constexpr double kFloatTolerance = 1e-5;

TEST(RadialUserObserverGl, TheObserverMovesWithItsFrameAndAnAffineMotionCarriesItExactly) {
    const model::FlatModel model = ballModel();
    const glm::dvec3 point(0.04, -0.03, 0.02);
    const passes::RadialCullingConfig config = withObserver(model, point);
    ASSERT_EQ(config.surfaces.size(), 1u);
    ASSERT_TRUE(config.surfaces[0].framed);
    // x1: x0 turned, sheared, squashed and moved — an affine map, which the frame follows exactly.
    const glm::dmat3 m(glm::dvec3(0.9, 0.2, -0.1), glm::dvec3(-0.15, 0.7, 0.05), glm::dvec3(0.1, 0.0, 1.1));
    const glm::dvec3 shift(0.3, 0.5, -0.2);
    std::vector<glm::dvec3> moved;
    for (const glm::dvec3& x : model.positions) moved.push_back(m * x + shift);
    const std::vector<glm::vec3> x0 = floats(model.positions), x1 = floats(moved);
    const test::CullingRun run = test::runCulling(model, config, x0, x1);
    ASSERT_EQ(run.observers.size(), 1u);
    EXPECT_LT(glm::length(glm::dvec3(run.observers[0].start) - point), kFloatTolerance);
    EXPECT_LT(glm::length(glm::dvec3(run.observers[0].end) - (m * point + shift)), kFloatTolerance);
    EXPECT_LT(glm::length(glm::dvec3(run.observers[0].end) - framePoint(config.surfaces[0], x1)),
              kFloatTolerance);
    EXPECT_EQ(run.winding[0], (passes::RadialWinding{1, false}));
    EXPECT_EQ(run.freeCount, model.faceCount()) << "a convex ball seen from inside: every face free";

    // A motion that is not affine (every node pushed out by its own amount): the frame's formula.
    std::vector<glm::dvec3> bulged;
    for (std::size_t i = 0; i < model.positions.size(); ++i)
        bulged.push_back(model.positions[i] * (1.0 + 0.1 * static_cast<double>(i % 7) / 7.0));
    const std::vector<glm::vec3> x2 = floats(bulged);
    const test::CullingRun second = test::runCulling(model, config, x0, x2);
    EXPECT_LT(glm::length(glm::dvec3(second.observers[0].end) - framePoint(config.surfaces[0], x2)),
              kFloatTolerance);
}

// An observer outside the ball: the surface winds 0 times around it, and however its faces are
// classified, none may be freed (decision 0025, "Violated triangles and the observer check").
TEST(RadialUserObserverGl, AnObserverOutsideItsSurfaceFreesNothing) {
    const model::FlatModel model = ballModel();
    const passes::RadialCullingConfig config = withObserver(model, glm::dvec3(0.4, 0.0, 0.0));
    const std::vector<glm::vec3> x0 = floats(model.positions);
    const test::CullingRun run = test::runCulling(model, config, x0, x0);
    EXPECT_EQ(run.winding[0], (passes::RadialWinding{0, false}));
    EXPECT_EQ(run.freeCount, 0u);
    EXPECT_EQ(run.violatedStat, 1u) << "the failed premise is counted";
}

/// The error radialCullingConfig throws for `json`'s scene, with every object's observer.
std::string refusal(const std::string& json) {
    const Scene scene = parseScene(json, ".", "refused");
    passes::RadialObserverSettings settings;
    settings.ghostMaxPerimeter = scene.collision.ghostMaxPerimeter;
    for (const Body& b : scene.bodies) settings.objectObservers.push_back(b.observer);
    try {
        (void)passes::radialCullingConfig(model::flatten(scene), settings);
    } catch (const Error& e) {
        return e.what();
    }
    return "(accepted)";
}

TEST(RadialUserObserverGl, AnObjectThatCannotCarryAnObserverIsRefusedByName) {
    const std::string head =
        R"({"format_version": 1, "effects": ["gravity", "self_collisions"], "time": {"dt": 0.01, "frames": 1},
      "collision": {"culling": "radial", "ghost_max_perimeter": 0},
      "objects": [{"name": "ball", "generator": {"type": "sphere", "radius": 0.15, "subdivisions": 1}, "mass": 1}, )";
    // A flat sheet: its nodes span no volume.
    EXPECT_NE(
        refusal(head +
                R"({"name": "sheet", "generator": {"type": "cloth", "size": [1, 1], "resolution": [8, 8]},
                   "mass": 1, "observer": [0, 0, -0.2]}]})")
            .find("object 1's observer: the object's nodes span no volume"),
        std::string::npos);
    // A tube whose openings no ghost fan closes (ghost_max_perimeter 0): no closed surface.
    EXPECT_NE(
        refusal(head + R"({"name": "sleeve", "generator": {"type": "tube", "radius": 0.08, "length": 0.4,
                   "resolution": [16, 12]}, "mass": 1, "observer": [0, 0, 0]}]})")
            .find("object 1 has an observer, but its surface is not closed"),
        std::string::npos);
}

} // namespace
} // namespace glcollide
