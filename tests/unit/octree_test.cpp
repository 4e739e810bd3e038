// AABB-octree layout (src/cpu/octree.cpp): cell mapping, face->box assignment and CSR order,
// owned-feature bits, closed flags; and the collision twin's building blocks
// (src/cpu/collision_twin.cpp): closed box overlap, float inflation, pair rules, leaf boxes.

#include "cpu/collision_twin.hpp"
#include "cpu/flat_model.hpp"
#include "cpu/octree.hpp"
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <set>

namespace glcollide {
namespace {

cpu::FlatModel modelOf(const std::vector<Body>& bodies) {
    Scene scene;
    scene.bodies = bodies;
    return cpu::flatten(scene);
}

TEST(Octree, CellsClampAndFlatAxes) {
    const glm::dvec3 lo(0.0), hi(1.0, 2.0, 4.0);
    EXPECT_EQ(cpu::octreeCell({0.0, 0.0, 0.0}, lo, hi, 2), 0u);
    EXPECT_EQ(cpu::octreeCell({1.0, 2.0, 4.0}, lo, hi, 2), 7u); // the upper border is clamped in
    EXPECT_EQ(cpu::octreeCell({0.75, 0.1, 0.1}, lo, hi, 2), 1u);  // x fastest
    EXPECT_EQ(cpu::octreeCell({0.1, 1.5, 0.1}, lo, hi, 2), 2u);
    EXPECT_EQ(cpu::octreeCell({0.1, 0.1, 3.0}, lo, hi, 2), 4u);
    EXPECT_EQ(cpu::octreeCell({-5.0, 9.0, 0.5}, lo, hi, 4), 0u + 4u * 3u + 16u * 0u);
    // A flat axis maps to cell 0 on that axis.
    EXPECT_EQ(cpu::octreeCell({0.9, 7.0, 0.9}, glm::dvec3(0.0, 7.0, 0.0), glm::dvec3(1.0, 7.0, 1.0), 2), 1u + 4u);
}

TEST(Octree, DepthOutOfRangeThrows) {
    const cpu::FlatModel m = modelOf({detail::generateTetBox({1, 1, 1}, {1, 1, 1})});
    EXPECT_THROW(cpu::buildOctree(m, 0), Error);
    EXPECT_THROW(cpu::buildOctree(m, 4), Error);
}

TEST(Octree, FacesGoToTheCellOfTheirRestCentroid) {
    const cpu::FlatModel m = modelOf({detail::generateTetBox({1, 2, 3}, {3, 4, 5}),
                                      detail::generateSphere(0.5, 2)});
    for (int depth = 1; depth <= 3; ++depth) {
        const cpu::OctreeLayout o = cpu::buildOctree(m, depth);
        const std::uint32_t n = 1u << depth;
        EXPECT_EQ(o.cellsPerAxis, n);
        EXPECT_EQ(o.boxesPerObject, n * n * n);
        EXPECT_EQ(o.boxCount, 2 * n * n * n);
        ASSERT_EQ(o.boxFaces.offsets.size(), o.boxCount + 1u);
        ASSERT_EQ(o.boxFaces.items.size(), m.faceCount());
        std::set<std::uint32_t> cellsUsed;
        for (std::size_t obj = 0; obj < m.objects.size(); ++obj) {
            const cpu::ObjectRange& r = m.objects[obj];
            EXPECT_EQ(o.firstBox[obj], obj * o.boxesPerObject);
            glm::dvec3 lo(1e300), hi(-1e300);
            for (std::uint32_t k = 3 * r.firstFace; k < 3 * (r.firstFace + r.faceCount); ++k) {
                lo = glm::min(lo, m.positions[m.faceIndices[k]]);
                hi = glm::max(hi, m.positions[m.faceIndices[k]]);
            }
            for (std::uint32_t f = r.firstFace; f < r.firstFace + r.faceCount; ++f) {
                const glm::dvec3 c = (m.positions[m.faceIndices[3 * f]] + m.positions[m.faceIndices[3 * f + 1]] +
                                      m.positions[m.faceIndices[3 * f + 2]]) / 3.0;
                EXPECT_EQ(o.faceObject[f], obj);
                EXPECT_EQ(o.faceBox[f], o.firstBox[obj] + cpu::octreeCell(c, lo, hi, n));
                cellsUsed.insert(o.faceBox[f]);
            }
        }
        EXPECT_GT(cellsUsed.size(), std::size_t{8}); // the faces spread over many cells
        // CSR rows: exactly the faces assigned to the box, in increasing face index.
        for (std::uint32_t b = 0; b < o.boxCount; ++b) {
            const auto first = o.boxFaces.items.begin() + o.boxFaces.offsets[b];
            const auto last = o.boxFaces.items.begin() + o.boxFaces.offsets[b + 1];
            EXPECT_TRUE(std::is_sorted(first, last));
            for (auto it = first; it != last; ++it) EXPECT_EQ(o.faceBox[*it], b);
        }
    }
}

TEST(Octree, OwnedBitsOfTwoTrianglesSharingAnEdge) {
    // Face 0 (0,1,2) owns everything it has; face 1 (2,1,3) shares edge {1,2} and nodes 1, 2:
    // it owns node 3 (corner 2), edge {1,3} (its edge 12) and edge {3,2} (its edge 20).
    const std::vector<std::uint32_t> faces = {0, 1, 2, 2, 1, 3};
    const std::vector<std::uint32_t> owned = cpu::ownedFeatures(faces);
    ASSERT_EQ(owned.size(), 2u);
    EXPECT_EQ(owned[0], cpu::kOwnVertex0 | cpu::kOwnVertex1 | cpu::kOwnVertex2 | cpu::kOwnEdge01 |
                            cpu::kOwnEdge12 | cpu::kOwnEdge20);
    EXPECT_EQ(owned[1], cpu::kOwnVertex2 | cpu::kOwnEdge12 | cpu::kOwnEdge20);
}

TEST(Octree, EveryVertexAndEdgeIsOwnedExactlyOnceByItsLowestFace) {
    const cpu::FlatModel m = modelOf({detail::generateTetBox({1, 1, 1}, {3, 2, 2}),
                                      detail::generateCloth(1.0, 1.0, 5, 4, false, false)});
    const std::vector<std::uint32_t> owned = cpu::ownedFeatures(m.faceIndices);
    std::map<std::uint32_t, std::vector<std::uint32_t>> nodeOwners, nodeFaces;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> edgeOwners, edgeFaces;
    const std::uint32_t vertexBits[3] = {cpu::kOwnVertex0, cpu::kOwnVertex1, cpu::kOwnVertex2};
    const std::uint32_t edgeBits[3] = {cpu::kOwnEdge01, cpu::kOwnEdge12, cpu::kOwnEdge20};
    for (std::uint32_t f = 0; f < m.faceCount(); ++f)
        for (std::uint32_t k = 0; k < 3; ++k) {
            const std::uint32_t a = m.faceIndices[3 * f + k], b = m.faceIndices[3 * f + (k + 1) % 3];
            const auto edge = std::minmax(a, b);
            nodeFaces[a].push_back(f);
            edgeFaces[edge].push_back(f);
            if (owned[f] & vertexBits[k]) nodeOwners[a].push_back(f);
            if (owned[f] & edgeBits[k]) edgeOwners[edge].push_back(f);
        }
    for (const auto& [node, faces] : nodeFaces) {
        ASSERT_EQ(nodeOwners[node].size(), 1u) << "node " << node;
        EXPECT_EQ(nodeOwners[node][0], *std::min_element(faces.begin(), faces.end()));
    }
    for (const auto& [edge, faces] : edgeFaces) {
        ASSERT_EQ(edgeOwners[edge].size(), 1u);
        EXPECT_EQ(edgeOwners[edge][0], *std::min_element(faces.begin(), faces.end()));
    }
}

TEST(Octree, ClosedFlags) {
    const cpu::FlatModel m = modelOf({detail::generateTetBox({1, 1, 1}, {2, 2, 2}),
                                      detail::generateCloth(1.0, 1.0, 4, 4, false, false),
                                      detail::generateSphere(0.3, 1)});
    const cpu::OctreeLayout o = cpu::buildOctree(m, 1);
    EXPECT_EQ(o.closed, (std::vector<std::uint8_t>{1, 0, 1}));
    // One face removed: its three edges now have one face each.
    std::vector<std::uint32_t> faces = m.faceIndices;
    EXPECT_TRUE(cpu::isClosedSurface(faces, m.objects[0].firstFace, m.objects[0].faceCount));
    EXPECT_FALSE(cpu::isClosedSurface(faces, m.objects[0].firstFace + 1, m.objects[0].faceCount - 1));
    EXPECT_FALSE(cpu::isClosedSurface(faces, 0, 0)); // no faces: bounds no volume
}

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
    const float half = cpu::halfThicknessFloat(0.02);
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
    const std::vector<glm::vec3> p = {
        {0, 0, 0}, {1, 0, 0}, {0, 1, 0},                 // face 0
        {0.2f, 0.2f, -0.5f}, {0.3f, 0.2f, 0.5f}, {0.2f, 0.3f, 0.5f}, // face 1: pierces face 0
        {0.2f, 0.2f, 0.004f}, {0.4f, 0.2f, 0.1f}, {0.2f, 0.4f, 0.1f}, // face 2: box within h/2 + h/2
        {5, 5, 5}, {6, 5, 5}, {5, 6, 5}};                // face 3: far
    const std::vector<std::uint32_t> faces = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    const std::vector<std::uint32_t> object = {0, 1, 1, 1};
    const auto candidates = cpu::twinCandidates(faces, object, p, 0.01, {true, false});
    EXPECT_EQ(candidates, (std::vector<cpu::FacePair>{{0, 1}, {0, 2}}));
    EXPECT_EQ(cpu::twinIntersections(faces, p, candidates), (std::vector<cpu::FacePair>{{0, 1}}));
    // Self only: faces 1 and 2 (object 1, no shared node) have overlapping boxes.
    EXPECT_EQ(cpu::twinCandidates(faces, object, p, 0.01, {false, true}), (std::vector<cpu::FacePair>{{1, 2}}));
}

TEST(CollisionTwin, LeafBoxesContainTheirFaceBoxes) {
    const cpu::FlatModel m = modelOf({detail::generateSphere(0.5, 2)});
    const cpu::OctreeLayout o = cpu::buildOctree(m, 2);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> jitter(-0.05f, 0.05f);
    std::vector<glm::vec3> p;
    for (const glm::dvec3& x : m.positions) p.push_back(glm::vec3(x) + glm::vec3(jitter(rng), jitter(rng), jitter(rng)));
    const auto boxes = cpu::twinLeafBoxes(o, m.faceIndices, p, 0.01);
    const float half = cpu::halfThicknessFloat(0.01);
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
