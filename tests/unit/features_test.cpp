// Feature ownership and closed flags of the flattened faces (src/model/features.cpp): owned-feature
// bits (GLC_OWN_*), closed surfaces, the octree layout's per-object closed flags, and the orphan
// table FeaturePairs reads (model::orphanTable) against the CPU twin's per-pair rule.

#include "cpu/contact_twin.hpp"
#include "model/features.hpp"
#include "model/flat_model.hpp"
#include "model/octree_layout.hpp"
#include "scene/scene_detail.hpp"

#include "model_of.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
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
// FeaturePairs' expansion of `pairs` through the orphan table, as feature_pairs.comp reads it: the
// owned feature pairs (cpu::featurePairs) plus each pair's entry's bits, in the pair's own order.
cpu::FeaturePairList expandWithTable(const std::vector<std::uint32_t>& faces,
                                     const std::vector<std::uint32_t>& owned,
                                     const std::vector<std::uint32_t>& table,
                                     const std::vector<cpu::IndexPair>& pairs) {
    cpu::FeaturePairList out = cpu::featurePairs(faces, owned, pairs);
    for (const auto& [a, b] : pairs) {
        const std::uint32_t lower = std::min(a, b), higher = std::max(a, b);
        std::uint32_t bits = 0;
        for (std::uint32_t i = table[lower]; i < table[lower + 1]; i += 2)
            if (table[i] == higher) bits = table[i + 1];
        for (std::uint32_t k = 0; k < 3; ++k) {
            if (bits & (1u << (model::kOrphanLowerCorner + k)))
                out.vertexFace.push_back({faces[3 * lower + k], higher});
            if (bits & (1u << (model::kOrphanHigherCorner + k)))
                out.vertexFace.push_back({faces[3 * higher + k], lower});
        }
        for (std::uint32_t e = 0; e < 3; ++e)
            for (std::uint32_t g = 0; g < 3; ++g)
                if (bits & (1u << (model::kOrphanEdgePair + 3 * e + g)))
                    out.edgeEdge.push_back(a == lower ? cpu::IndexPair{3 * lower + e, 3 * higher + g}
                                                      : cpu::IndexPair{3 * higher + g, 3 * lower + e});
    }
    std::sort(out.vertexFace.begin(), out.vertexFace.end());
    std::sort(out.edgeEdge.begin(), out.edgeEdge.end());
    return out;
}

// Every face pair that self-collisions can make a candidate: faces of one object sharing no node,
// in both orders (the broad phases list (lower, higher), the table must not depend on it).
std::vector<cpu::IndexPair> everySelfPair(const model::FlatModel& m, bool bothOrders) {
    std::vector<cpu::IndexPair> pairs;
    const auto shares = [&](std::uint32_t f, std::uint32_t g) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (m.faceIndices[3 * f + i] == m.faceIndices[3 * g + j]) return true;
        return false;
    };
    for (const model::ObjectRange& r : m.objects)
        for (std::uint32_t f = r.firstFace; f < r.firstFace + r.faceCount; ++f)
            for (std::uint32_t g = f + 1; g < r.firstFace + r.faceCount; ++g)
                if (!shares(f, g)) {
                    pairs.push_back({f, g});
                    if (bothOrders) pairs.push_back({g, f});
                }
    return pairs;
}

// The table is built from the features (each orphan's one carrier); the twin tests each candidate
// by FeaturePairs' rule. Over every face pair of closed and open meshes, with the faces in the
// generators' order and shuffled (ownership follows face order), both give the same lists; and
// over random halves of those pairs too, where an orphan is listed only if its carrier is among
// them — so a table that names another carrier than the rule's differs there (over every pair,
// a vertex-face entry (vertex, face) looks the same whichever candidate appends it).
TEST(OrphanTable, HoldsExactlyTheOrphansTheTwinFindsForEveryFacePair) {
    std::vector<std::pair<std::string, model::FlatModel>> meshes;
    meshes.emplace_back("sphere, cloth, tube", modelOf({detail::generateSphere(0.3, 2),
                                                        detail::generateCloth(1.0, 1.0, 6, 5, false, false),
                                                        detail::generateTube(0.1, 0.4, 8, 4)}));
    meshes.emplace_back("tet box", modelOf({detail::generateTetBox({1, 1, 1}, {3, 2, 2})}));
    model::FlatModel shuffled =
        modelOf({detail::generateSphere(0.3, 2), detail::generateCloth(1.0, 1.0, 6, 5, false, false)});
    std::mt19937 rng(7);
    for (std::size_t o = 0; o < shuffled.objects.size(); ++o) { // faces shuffled within each object
        const model::ObjectRange& r = shuffled.objects[o];
        std::vector<std::uint32_t> order(r.faceCount);
        std::iota(order.begin(), order.end(), 0u);
        std::shuffle(order.begin(), order.end(), rng);
        std::vector<std::uint32_t> faces(shuffled.faceIndices.begin() + 3 * r.firstFace,
                                         shuffled.faceIndices.begin() + 3 * (r.firstFace + r.faceCount));
        for (std::uint32_t i = 0; i < r.faceCount; ++i)
            for (std::uint32_t k = 0; k < 3; ++k)
                shuffled.faceIndices[3 * (r.firstFace + i) + k] = faces[3 * order[i] + k];
    }
    meshes.emplace_back("shuffled sphere and cloth", shuffled);
    for (const auto& [what, m] : meshes) {
        const std::vector<std::uint32_t> owned = model::ownedFeatures(m.faceIndices);
        const std::vector<std::uint32_t> table = model::orphanTable(m.faceIndices, m.nodeCount());
        for (const int subset : {0, 1, 2, 3}) { // 0: every pair, 1: both orders, 2..3: random halves
            std::vector<cpu::IndexPair> pairs = everySelfPair(m, subset == 1);
            if (subset >= 2) {
                std::shuffle(pairs.begin(), pairs.end(), rng);
                pairs.resize(pairs.size() / 2);
            }
            const cpu::FeaturePairList twin =
                cpu::ccdFeaturePairs(m.faceIndices, owned, model::featureOwners(m.faceIndices), pairs);
            const cpu::FeaturePairList plain = cpu::featurePairs(m.faceIndices, owned, pairs);
            ASSERT_GT(twin.vertexFace.size(), plain.vertexFace.size())
                << what << ": the mesh must have orphans";
            ASSERT_GT(twin.edgeEdge.size(), plain.edgeEdge.size()) << what << ": the mesh must have orphans";
            const cpu::FeaturePairList viaTable = expandWithTable(m.faceIndices, owned, table, pairs);
            EXPECT_EQ(viaTable.vertexFace, twin.vertexFace) << what << ", pairs " << subset;
            EXPECT_EQ(viaTable.edgeEdge, twin.edgeEdge) << what << ", pairs " << subset;
        }
        const std::size_t entries = (table.size() - m.faceCount() - 1) / 2;
        std::printf("%s: %zu faces, %zu orphan-carrying face pairs (%.2f per face)\n", what.c_str(),
                    std::size_t{m.faceCount()}, entries,
                    static_cast<double>(entries) / static_cast<double>(m.faceCount()));
        // Only pairs that share no node carry orphans, each listed under its lower face, increasing.
        for (std::uint32_t f = 0; f < m.faceCount(); ++f)
            for (std::uint32_t i = table[f]; i < table[f + 1]; i += 2) {
                EXPECT_GT(table[i], f);
                if (i > table[f]) {
                    EXPECT_GT(table[i], table[i - 2]);
                }
                EXPECT_NE(table[i + 1], 0u);
            }
    }
}

} // namespace
} // namespace glcollide
