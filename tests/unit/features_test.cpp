// Feature ownership and closed flags of the flattened faces (src/model/features.cpp): owned-feature
// bits (GLC_OWN_*), closed surfaces and the octree layout's per-object closed flags.

#include "model/features.hpp"
#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"
#include "scene/scene_detail.hpp"

#include "model_of.hpp"

#include <gtest/gtest.h>

#include <map>
#include <utility>
#include <vector>

namespace glcollide {
namespace {

using test::modelOf;

TEST(Octree, OwnedBitsOfTwoTrianglesSharingAnEdge) {
    // Face 0 (0,1,2) owns everything it has; face 1 (2,1,3) shares edge {1,2} and nodes 1, 2:
    // it owns node 3 (corner 2), edge {1,3} (its edge 12) and edge {3,2} (its edge 20).
    const std::vector<std::uint32_t> faces = {0, 1, 2, 2, 1, 3};
    const std::vector<std::uint32_t> owned = model::ownedFeatures(faces);
    ASSERT_EQ(owned.size(), 2u);
    EXPECT_EQ(owned[0], GLC_OWN_VERTEX0 | GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2 | GLC_OWN_EDGE01 |
                            GLC_OWN_EDGE12 | GLC_OWN_EDGE20);
    EXPECT_EQ(owned[1], GLC_OWN_VERTEX2 | GLC_OWN_EDGE12 | GLC_OWN_EDGE20);
}

TEST(Octree, EveryVertexAndEdgeIsOwnedExactlyOnceByItsLowestFace) {
    const model::FlatModel m = modelOf(
        {detail::generateTetBox({1, 1, 1}, {3, 2, 2}), detail::generateCloth(1.0, 1.0, 5, 4, false, false)});
    const std::vector<std::uint32_t> owned = model::ownedFeatures(m.faceIndices);
    std::map<std::uint32_t, std::vector<std::uint32_t>> nodeOwners, nodeFaces;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> edgeOwners, edgeFaces;
    const std::uint32_t vertexBits[3] = {GLC_OWN_VERTEX0, GLC_OWN_VERTEX1, GLC_OWN_VERTEX2};
    const std::uint32_t edgeBits[3] = {GLC_OWN_EDGE01, GLC_OWN_EDGE12, GLC_OWN_EDGE20};
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
    const model::FlatModel m =
        modelOf({detail::generateTetBox({1, 1, 1}, {2, 2, 2}),
                 detail::generateCloth(1.0, 1.0, 4, 4, false, false), detail::generateSphere(0.3, 1)});
    const model::OctreeLayout o = model::buildOctree(m, 1);
    EXPECT_EQ(o.closed, (std::vector<std::uint8_t>{1, 0, 1}));
    // One face removed: its three edges now have one face each.
    std::vector<std::uint32_t> faces = m.faceIndices;
    EXPECT_TRUE(model::isClosedSurface(faces, m.objects[0].firstFace, m.objects[0].faceCount));
    EXPECT_FALSE(model::isClosedSurface(faces, m.objects[0].firstFace + 1, m.objects[0].faceCount - 1));
    EXPECT_FALSE(model::isClosedSurface(faces, 0, 0)); // no faces: bounds no volume
}
} // namespace
} // namespace glcollide
