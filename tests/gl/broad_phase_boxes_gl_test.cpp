// Engine::readBroadPhaseBoxes (issue 25: the viewer's BVH / octree box overlay), for the BVH and the
// octree, against the faces' boxes computed on the CPU from readPositions(): at every depth the
// boxes are a cut through the tree, so every face's box lies inside one of them; every box of a
// level lies inside one box of the level above (a parent holds its children); the root level of
// the BVH is one box and its deepest level one box per face. Bad depths and scenes without boxes
// are errors.

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <string>
#include <vector>

namespace glcollide {
namespace {

std::string twoCloths(const std::string& broadPhase) {
    return R"({"format_version": 1, "name": "two cloths", "effects": ["gravity", "springs", "collisions", "self_collisions"],
      "time": {"dt": 0.01, "substeps": 4},
      "collision": {"broad_phase": ")" +
           broadPhase + R"(", "response": "bridson", "thickness": 0.01, "stiffness": 100},
      "objects": [
        {"name": "below", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [6, 6]},
         "mass": 0.2, "springs": {"stiffness": 200}, "pinned": [0, 1, 2]},
        {"name": "above", "generator": {"type": "cloth", "size": [0.3, 0.3], "resolution": [5, 5]},
         "transform": {"translate": [0.02, 0.005, 0.01]}, "velocity": [0, -0.2, 0],
         "mass": 0.1, "springs": {"stiffness": 200}}]})";
}

// Exact comparisons: positions and boxes are floats on the device, a box's corners are minima and
// maxima of them (widened by the thickness where the broad phase inflates), and the read-backs
// convert floats to doubles exactly.
bool inside(const BroadPhaseBox& inner, const BroadPhaseBox& outer) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) &&
           glm::all(glm::lessThanEqual(inner.hi, outer.hi));
}

bool insideOne(const BroadPhaseBox& b, const std::vector<BroadPhaseBox>& boxes) {
    for (const BroadPhaseBox& o : boxes)
        if (inside(b, o)) return true;
    return false;
}

std::vector<BroadPhaseBox> faceBoxes(const Engine& engine) {
    const std::vector<glm::dvec3> x = engine.readPositions();
    std::vector<BroadPhaseBox> boxes;
    const std::vector<std::uint32_t> firstNodes = engine.bodyFirstNodes();
    for (std::size_t b = 0; b < engine.scene().bodies.size(); ++b)
        for (const auto& f : engine.scene().bodies[b].faces) {
            BroadPhaseBox box{x[firstNodes[b] + f[0]], x[firstNodes[b] + f[0]]};
            for (int k = 1; k < 3; ++k) {
                box.lo = glm::min(box.lo, x[firstNodes[b] + f[k]]);
                box.hi = glm::max(box.hi, x[firstNodes[b] + f[k]]);
            }
            boxes.push_back(box);
        }
    return boxes;
}

class BroadPhaseBoxesGl : public ::testing::TestWithParam<std::string> {};

TEST_P(BroadPhaseBoxesGl, EveryLevelHoldsEveryFaceAndItsChildren) {
    Engine engine(parseScene(twoCloths(GetParam()), ".", "boxes"), {false});
    for (int frame = 0; frame < 3; ++frame) engine.step();
    engine.detectCollisions(); // the boxes of the positions readPositions() returns
    const std::vector<BroadPhaseBox> faces = faceBoxes(engine);
    ASSERT_EQ(faces.size(), engine.faceCount());
    const int maxDepth = engine.broadPhaseDepth();
    ASSERT_GE(maxDepth, 1);
    std::vector<BroadPhaseBox> above;
    for (int depth = 0; depth <= maxDepth; ++depth) {
        const std::vector<BroadPhaseBox> level = engine.readBroadPhaseBoxes(depth);
        ASSERT_FALSE(level.empty()) << "depth " << depth;
        for (std::size_t f = 0; f < faces.size(); ++f)
            ASSERT_TRUE(insideOne(faces[f], level)) << "face " << f << " at depth " << depth;
        for (std::size_t b = 0; b < level.size() && depth > 0; ++b)
            ASSERT_TRUE(insideOne(level[b], above)) << "box " << b << " at depth " << depth;
        if (GetParam() == "bvh") {
            if (depth == 0) {
                EXPECT_EQ(level.size(), 1u) << "the root";
            }
            if (depth == maxDepth) {
                EXPECT_EQ(level.size(), engine.faceCount()) << "the leaves";
            }
        } else {
            if (depth == 0) {
                EXPECT_EQ(level.size(), 2u) << "one root cell per object";
            }
            EXPECT_LE(level.size(), 2u << (3 * depth)) << "at most 8^depth cells per object";
        }
        above = level;
    }
    EXPECT_THROW((void)engine.readBroadPhaseBoxes(-1), Error);
    EXPECT_THROW((void)engine.readBroadPhaseBoxes(maxDepth + 1), Error);
}

INSTANTIATE_TEST_SUITE_P(BroadPhases, BroadPhaseBoxesGl, ::testing::Values("bvh", "octree"));

TEST(BroadPhaseBoxesErrorsGl, AllPairsAndNoCollisionsHaveNoBoxes) {
    Engine allPairs(parseScene(twoCloths("all_pairs"), ".", "all pairs"), {false});
    EXPECT_THROW((void)allPairs.readBroadPhaseBoxes(0), Error);
    EXPECT_THROW((void)allPairs.broadPhaseDepth(), Error);
    Engine free(parseScene(R"({"format_version": 1, "name": "free", "effects": ["gravity"],
      "time": {"dt": 0.01, "substeps": 1},
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [3, 3]},
                   "mass": 0.5}]})",
                           ".", "free"),
                {false});
    EXPECT_THROW((void)free.readBroadPhaseBoxes(0), Error);
}

} // namespace
} // namespace glcollide
