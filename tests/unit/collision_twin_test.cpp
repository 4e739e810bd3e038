// The collision twin's building blocks (src/cpu/collision_twin.cpp): closed box overlap, float
// inflation (model::halfThicknessFloat, src/model/face_box.hpp), pair rules, leaf boxes.

#include "cpu/collision_twin.hpp"
#include "model/face_box.hpp"
#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"
#include "scene/scene_detail.hpp"

#include "model_of.hpp"

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include <limits>
#include <random>
#include <vector>

namespace glcollide {
namespace {

using test::modelOf;

TEST(CollisionTwin, ClosedBoxOverlapAndEmptyBoxes) {
    const cpu::FloatBox a{{0, 0, 0}, {1, 1, 1}}, touching{{1, 0.5f, 0.5f}, {2, 2, 2}},
        apart{{1.0001f, 0, 0}, {2, 1, 1}};
    EXPECT_TRUE(cpu::boxesOverlap(a, touching)); // closed: touching faces overlap
    EXPECT_TRUE(cpu::boxesOverlap(touching, a));
    EXPECT_FALSE(cpu::boxesOverlap(a, apart));
    constexpr float kInf = std::numeric_limits<float>::infinity();
    const cpu::FloatBox empty{glm::vec3(kInf), glm::vec3(-kInf)};
    EXPECT_FALSE(cpu::boxesOverlap(a, empty));
    EXPECT_FALSE(cpu::boxesOverlap(empty, empty));
}

TEST(CollisionTwin, FaceBoxIsInflatedByHalfTheThicknessInFloat) {
    const std::vector<std::uint32_t> faces = {0, 1, 2};
    const std::vector<glm::vec3> p = {{0.1f, 0.2f, 0.3f}, {1.0f, -1.0f, 0.5f}, {0.5f, 0.5f, 2.0f}};
    const float half = model::halfThicknessFloat(0.02);
    EXPECT_EQ(half, 0.01f);
    const cpu::FloatBox b = cpu::faceBox(faces, p, 0, half);
    EXPECT_EQ(b.lo, glm::vec3(0.1f - 0.01f, -1.0f - 0.01f, 0.3f - 0.01f));
    EXPECT_EQ(b.hi, glm::vec3(1.0f + 0.01f, 0.5f + 0.01f, 2.0f + 0.01f));
}

TEST(CollisionTwin, PairRules) {
    // Faces 0, 1 in object 0 sharing node 1; face 2 in object 0 sharing nothing; face 3 in object 1.
    const std::vector<std::uint32_t> faces = {0, 1, 2, 1, 3, 4, 5, 6, 7, 8, 9, 10};
    const std::vector<std::uint32_t> object = {0, 0, 0, 1};
    const cpu::PairRules none, between{true, false}, self{false, true}, both{true, true};
    EXPECT_FALSE(cpu::validFacePair(faces, object, 0, 3, none));
    EXPECT_TRUE(cpu::validFacePair(faces, object, 0, 3, between));
    EXPECT_FALSE(cpu::validFacePair(faces, object, 0, 3, self));
    EXPECT_FALSE(cpu::validFacePair(faces, object, 0, 2, between));
    EXPECT_TRUE(cpu::validFacePair(faces, object, 0, 2, self));
    EXPECT_FALSE(cpu::validFacePair(faces, object, 0, 1, both)); // shared node
    EXPECT_FALSE(cpu::validFacePair(faces, object, 2, 2, both)); // a face with itself
}

TEST(CollisionTwin, CandidatesAndIntersectionsOfAHandMadeCase) {
    // Object 0: a triangle in z = 0. Object 1: one triangle piercing it, one touching it within
    // the thickness, one far away.
    const std::vector<glm::vec3> p = {{0, 0, 0},
                                      {1, 0, 0},
                                      {0, 1, 0}, // face 0
                                      {0.2f, 0.2f, -0.5f},
                                      {0.3f, 0.2f, 0.5f},
                                      {0.2f, 0.3f, 0.5f}, // face 1: pierces face 0
                                      {0.2f, 0.2f, 0.004f},
                                      {0.4f, 0.2f, 0.1f},
                                      {0.2f, 0.4f, 0.1f}, // face 2: box within h/2 + h/2
                                      {5, 5, 5},
                                      {6, 5, 5},
                                      {5, 6, 5}}; // face 3: far
    const std::vector<std::uint32_t> faces = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    const std::vector<std::uint32_t> object = {0, 1, 1, 1};
    const auto candidates = cpu::twinCandidates(faces, object, p, 0.01, {true, false});
    EXPECT_EQ(candidates, (std::vector<cpu::FacePair>{{0, 1}, {0, 2}}));
    EXPECT_EQ(cpu::twinIntersections(faces, p, candidates), (std::vector<cpu::FacePair>{{0, 1}}));
    // Self only: faces 1 and 2 (object 1, no shared node) have overlapping boxes.
    EXPECT_EQ(cpu::twinCandidates(faces, object, p, 0.01, {false, true}),
              (std::vector<cpu::FacePair>{{1, 2}}));
}

TEST(CollisionTwin, LeafBoxesContainTheirFaceBoxes) {
    const model::FlatModel m = modelOf({detail::generateSphere(0.5, 2)});
    const model::OctreeLayout o = model::buildOctree(m, 2);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> jitter(-0.05f, 0.05f);
    std::vector<glm::vec3> p;
    for (const glm::dvec3& x : m.positions)
        p.push_back(glm::vec3(x) + glm::vec3(jitter(rng), jitter(rng), jitter(rng)));
    const auto boxes = cpu::twinLeafBoxes(o, m.faceIndices, p, 0.01);
    const float half = model::halfThicknessFloat(0.01);
    std::size_t empty = 0;
    for (std::uint32_t b = 0; b < o.boxCount; ++b)
        if (o.boxFaces.offsets[b] == o.boxFaces.offsets[b + 1]) {
            ++empty;
            EXPECT_GT(boxes[b].lo.x, boxes[b].hi.x);
        }
    EXPECT_GT(empty, 0u); // a sphere leaves the inner cells of a 4^3 grid empty
    for (std::uint32_t f = 0; f < m.faceCount(); ++f) {
        const cpu::FloatBox fb = cpu::faceBox(m.faceIndices, p, f, half);
        const cpu::FloatBox& lb = boxes[o.faceBox[f]];
        EXPECT_TRUE(glm::all(glm::lessThanEqual(lb.lo, fb.lo)) && glm::all(glm::lessThanEqual(fb.hi, lb.hi)));
    }
}
} // namespace
} // namespace glcollide
