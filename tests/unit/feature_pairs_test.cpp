// The Representative-Triangle expansion's twin (cpu::featurePairs, src/cpu/contact_twin.cpp) and
// what ownership costs (cpu::ownershipCoverage, src/cpu/feature_coverage.cpp), on hand-built
// meshes whose feature pairs are counted by hand. GL-free; the GPU expansion is compared with this
// twin in tests/gl/contact_response_gl_test.cpp and collision_detection_gl_test.cpp.

#include "cpu/collision_twin.hpp"
#include "cpu/contact_twin.hpp"
#include "cpu/feature_coverage.hpp"
#include "model/features.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace glcollide {
namespace {

using Pairs = std::vector<std::array<std::uint32_t, 2>>;

// A closed tetrahedron surface on nodes first..first+3 (4 faces, 6 edges).
void addTetrahedron(std::vector<std::uint32_t>& faces, std::uint32_t first) {
    const std::uint32_t n0 = first, n1 = first + 1, n2 = first + 2, n3 = first + 3;
    faces.insert(faces.end(), {n0, n2, n1, n0, n1, n3, n1, n2, n3, n0, n3, n2});
}

// Every face pair between objects A (faces [0, a)) and B (faces [a, total)).
Pairs allPairsBetween(std::uint32_t a, std::uint32_t total) {
    Pairs p;
    for (std::uint32_t f = 0; f < a; ++f)
        for (std::uint32_t g = a; g < total; ++g) p.push_back({f, g});
    return p;
}

// The (node, face) and undirected-edge pairs the expansion covers, as sets, checking that no pair
// comes twice.
struct Covered {
    std::set<std::array<std::uint32_t, 2>> vertexFace;
    std::set<std::array<std::uint64_t, 2>> edgeEdge; // edge keys (model::edgeKey)
};
Covered covered(const std::vector<std::uint32_t>& faces, const cpu::FeaturePairList& pairs) {
    Covered c;
    for (const auto& p : pairs.vertexFace) EXPECT_TRUE(c.vertexFace.insert(p).second) << p[0] << " " << p[1];
    for (const auto& [ea, eb] : pairs.edgeEdge) {
        const auto a = model::faceEdge(faces, ea / 3, static_cast<int>(ea % 3));
        const auto b = model::faceEdge(faces, eb / 3, static_cast<int>(eb % 3));
        EXPECT_TRUE(c.edgeEdge.insert({model::edgeKey(a[0], a[1]), model::edgeKey(b[0], b[1])}).second);
    }
    return c;
}

TEST(FeaturePairs, TwoTetrahedraGiveEveryVertexFaceAndEdgeEdgePairOnce) {
    std::vector<std::uint32_t> faces;
    addTetrahedron(faces, 0);
    addTetrahedron(faces, 4);
    const Pairs candidates = allPairsBetween(4, 8); // 16 face pairs
    const cpu::FeaturePairList pairs = cpu::featurePairs(faces, model::ownedFeatures(faces), candidates);
    // Each of 4 vertices against each of the other's 4 faces, both ways: 32 (a face-pair expansion
    // without ownership tests 6 per candidate, 96). Each of 6 edges against each of 6: 36 (not 144).
    EXPECT_EQ(pairs.vertexFace.size(), 32u);
    EXPECT_EQ(pairs.edgeEdge.size(), 36u);
    const Covered c = covered(faces, pairs);
    for (std::uint32_t v = 0; v < 8; ++v)
        for (std::uint32_t f = v < 4 ? 4u : 0u; f < (v < 4 ? 8u : 4u); ++f)
            EXPECT_TRUE(c.vertexFace.count({v, f})) << "vertex " << v << " face " << f;
    EXPECT_TRUE(std::is_sorted(pairs.vertexFace.begin(), pairs.vertexFace.end()));
    // Edge-edge pairs name the lower face's edge first (candidates are (lower, higher)).
    for (const auto& [ea, eb] : pairs.edgeEdge) EXPECT_LT(ea / 3, eb / 3);
}

// Open cloth: a quad of two triangles has one interior edge and four boundary edges. A boundary
// edge has one face, which owns it: every edge and every vertex of the quad is expanded, nothing
// is lost at the boundary.
TEST(FeaturePairs, BoundaryEdgesOfAnOpenSurfaceAreOwnedByTheirOneFace) {
    std::vector<std::uint32_t> faces = {0, 1, 2, 2, 1, 3}; // quad: nodes 0..3, shared edge {1, 2}
    addTetrahedron(faces, 4);                              // faces 2..5
    const std::vector<std::uint32_t> owned = model::ownedFeatures(faces);
    const cpu::FeaturePairList pairs = cpu::featurePairs(faces, owned, allPairsBetween(2, 6));
    EXPECT_EQ(pairs.vertexFace.size(),
              4u * 4u + 4u * 2u);              // quad vertices x tet faces + tet vertices x quad faces
    EXPECT_EQ(pairs.edgeEdge.size(), 5u * 6u); // 5 quad edges x 6 tet edges
    const Covered c = covered(faces, pairs);
    for (const std::uint64_t quadEdge : {model::edgeKey(0, 1), model::edgeKey(1, 2), model::edgeKey(2, 0),
                                         model::edgeKey(1, 3), model::edgeKey(3, 2)})
        EXPECT_TRUE(c.edgeEdge.count({quadEdge, model::edgeKey(4, 6)})) << quadEdge;
}

// The known limitation: vertex 0 is owned by face 0 = (0, 1, 2); face 2 = (2, 5, 6) shares node 2
// with face 0, so the self-collision rules exclude the pair (0, 2) and vertex 0 is never tested
// against face 2, although it lies 0.005 m above it (thickness 0.01) and face 1 = (0, 3, 4), which
// also contains vertex 0, makes a valid pair with face 2 (a face-pair expansion without ownership
// would test vertex 0 there).
TEST(FeaturePairs, AVertexNearAFaceAdjacentToItsOwnerFaceIsNeverTested) {
    const std::vector<std::uint32_t> faces = {0, 1, 2, 0, 3, 4, 2, 5, 6};
    const std::vector<std::uint32_t> object(3, 0u);
    const std::vector<glm::vec3> x = {{0.0f, 0.005f, 0.0f}, {0.0f, 0.5f, 0.5f},  {1.0f, 0.0f, 0.0f},
                                      {0.0f, 0.5f, -1.0f},  {0.3f, 0.6f, -1.0f}, {-1.0f, 0.0f, 1.0f},
                                      {-1.0f, 0.0f, -1.0f}};
    const double h = 0.01;
    const cpu::PairRules self{false, true};
    ASSERT_FALSE(cpu::validFacePair(faces, object, 0, 2, self));
    ASSERT_TRUE(cpu::validFacePair(faces, object, 1, 2, self));
    const Pairs candidates = cpu::twinCandidates(faces, object, x, h, self);
    EXPECT_EQ(candidates, (Pairs{{1, 2}}));
    const std::vector<std::uint32_t> owned = model::ownedFeatures(faces);
    EXPECT_EQ(owned[1] & (GLC_OWN_VERTEX0 | GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2),
              GLC_OWN_VERTEX1 | GLC_OWN_VERTEX2);
    const cpu::FeaturePairList pairs = cpu::featurePairs(faces, owned, candidates);
    EXPECT_EQ(
        std::count(pairs.vertexFace.begin(), pairs.vertexFace.end(), std::array<std::uint32_t, 2>{0, 2}), 0);
    const cpu::OwnershipCoverage c = cpu::ownershipCoverage(faces, object, x, h, self);
    EXPECT_EQ(c.vertexFaceNear, 1u);
    EXPECT_EQ(c.vertexFaceLost, 1u);
    EXPECT_EQ(c.edgeEdgeNear, 0u); // no edge within 0.01 m of an edge without a common node
}

// A grid cloth folded into a hairpin: a flat bottom sheet, a half circle of radius `gap`/2 and a
// top sheet `gap` above the bottom (gap < thickness). Every top vertex is within the thickness of
// the bottom sheet; only near the fold do owner faces share nodes with the faces they are near.
// Measures how many near feature pairs ownership loses there (docs/collisions.md quotes it).
TEST(FeaturePairs, OwnershipLossesOnAFoldedClothAreConfinedToTheFold) {
    const std::uint32_t along = 40, across = 10; // cells
    const double cell = 0.02, gap = 0.006, h = 0.01;
    const double pi = 3.14159265358979323846, r = gap / 2, length = along * cell;
    const double flat = (length - pi * r) / 2; // each sheet's length
    std::vector<glm::vec3> x;
    for (std::uint32_t j = 0; j <= across; ++j)
        for (std::uint32_t i = 0; i <= along; ++i) {
            const double s = i * cell;
            double px = s, py = 0.0;
            if (s > flat && s <= flat + pi * r) {
                const double t = (s - flat) / r;
                px = flat + r * std::sin(t);
                py = r - r * std::cos(t);
            } else if (s > flat + pi * r) {
                px = flat - (s - flat - pi * r);
                py = gap;
            }
            x.emplace_back(static_cast<float>(px), static_cast<float>(py), static_cast<float>(j * cell));
        }
    std::vector<std::uint32_t> faces;
    const auto node = [&](std::uint32_t i, std::uint32_t j) { return j * (along + 1) + i; };
    for (std::uint32_t j = 0; j < across; ++j)
        for (std::uint32_t i = 0; i < along; ++i)
            faces.insert(faces.end(), {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j),
                                       node(i + 1, j + 1), node(i, j + 1)});
    const std::vector<std::uint32_t> object(faces.size() / 3, 0u);
    const cpu::OwnershipCoverage c = cpu::ownershipCoverage(faces, object, x, h, {false, true});
    std::printf("folded cloth, %zu faces: vertex-face near %llu lost %llu, edge-edge near %llu lost %llu\n",
                faces.size() / 3, static_cast<unsigned long long>(c.vertexFaceNear),
                static_cast<unsigned long long>(c.vertexFaceLost),
                static_cast<unsigned long long>(c.edgeEdgeNear),
                static_cast<unsigned long long>(c.edgeEdgeLost));
    // Each of the 11 x ~20 top-sheet vertices is within the thickness of the bottom sheet, 0.006 m
    // below: hundreds of near pairs.
    EXPECT_GT(c.vertexFaceNear, 200u);
    EXPECT_GT(c.edgeEdgeNear, 200u);
    // Losses happen (the limitation is real), only where owner faces and near faces share a node:
    // around the fold, a small fraction of the near pairs (measured: 1 of 2340 vertex-face and 40
    // of 6700 edge-edge pairs).
    EXPECT_GT(c.vertexFaceLost + c.edgeEdgeLost, 0u);
    EXPECT_LT(c.vertexFaceLost, c.vertexFaceNear / 4);
    EXPECT_LT(c.edgeEdgeLost, c.edgeEdgeNear / 4);
}

} // namespace
} // namespace glcollide
