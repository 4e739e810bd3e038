// Ground truth of the benchmark (src/cpu/oracle/ground_truth.cpp). exactIntersectingPairs is compared
// with brute force: the exact oracle on EVERY valid pair for soups small enough (so the box sweep
// and the double filter are checked to lose nothing), and twinIntersections(twinCandidates) with
// thickness 0 for meshes of a few thousand faces. deepestPenetration is compared with depths worked
// out by hand on axis-aligned boxes.

#include "cpu/collision_twin.hpp"
#include "cpu/oracle/exact_tri_tri.hpp"
#include "cpu/oracle/ground_truth.hpp"
#include "model/flat_model.hpp"
#include "scene/scene_detail.hpp"

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <random>

namespace glcollide::cpu {
namespace {

/// Faces, their objects and float positions: the input of exactIntersectingPairs.
struct Soup {
    std::vector<std::uint32_t> faceIndices, faceObject;
    std::vector<glm::vec3> positions;
};

/// The definition itself, without rules: every pair f < g whose closed triangles the exact oracle
/// says intersect, no box culling. Computed once per soup (GMP is slow), then filtered per rule.
std::vector<FacePair> bruteForceIntersections(const Soup& s) {
    const auto faces = static_cast<std::uint32_t>(s.faceObject.size());
    std::vector<FacePair> out;
    for (std::uint32_t f = 0; f < faces; ++f)
        for (std::uint32_t g = f + 1; g < faces; ++g) {
            Triangle a, b;
            for (std::size_t c = 0; c < 3; ++c) {
                a[c] = glm::dvec3(s.positions[s.faceIndices[3 * f + c]]);
                b[c] = glm::dvec3(s.positions[s.faceIndices[3 * g + c]]);
            }
            if (exactTrianglesIntersect(a, b)) out.push_back({f, g});
        }
    return out;
}

/// The pairs of a sorted list that are valid under `rules` (keeps the order).
std::vector<FacePair> validUnder(const std::vector<FacePair>& pairs, const Soup& s, const PairRules& rules) {
    std::vector<FacePair> out;
    for (const FacePair& p : pairs)
        if (validFacePair(s.faceIndices, s.faceObject, p[0], p[1], rules)) out.push_back(p);
    return out;
}

const PairRules kBetween{true, false}, kSelf{false, true}, kBoth{true, true};

/// `faces` triangles over a pool of `nodes` random points (so faces share nodes, which matters
/// for the self rule), spread over `objects` objects. `snap` > 0 rounds coordinates to multiples
/// of 1/snap: exact touching, shared planes and collinear corners become common.
Soup randomSoup(unsigned seed, std::uint32_t nodes, std::uint32_t faces, std::uint32_t objects, float extent,
                float snap) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(0.0f, extent);
    std::uniform_int_distribution<std::uint32_t> node(0, nodes - 1), object(0, objects - 1);
    Soup s;
    for (std::uint32_t n = 0; n < nodes; ++n) {
        glm::vec3 p(coord(rng), coord(rng), coord(rng));
        if (snap > 0.0f) p = glm::round(p * snap) / snap;
        s.positions.push_back(p);
    }
    for (std::uint32_t f = 0; f < faces; ++f) {
        for (int c = 0; c < 3; ++c) s.faceIndices.push_back(node(rng));
        s.faceObject.push_back(object(rng));
    }
    return s;
}

/// A crumpled triangle strip: a random walk of nodes with steps up to `step` in the unit cube,
/// face k = (k, k+1, k+2), cut into `objects` consecutive pieces. Small triangles that share nodes
/// with their neighbours and cross the strip elsewhere.
Soup ribbonSoup(unsigned seed, std::uint32_t faces, std::uint32_t objects, float step) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> offset(-step, step), start(0.0f, 1.0f);
    Soup s;
    s.positions.push_back({start(rng), start(rng), start(rng)});
    for (std::uint32_t n = 1; n < faces + 2; ++n)
        s.positions.push_back(
            glm::clamp(s.positions.back() + glm::vec3(offset(rng), offset(rng), offset(rng)), glm::vec3(0.0f),
                       glm::vec3(1.0f)));
    for (std::uint32_t f = 0; f < faces; ++f) {
        s.faceIndices.insert(s.faceIndices.end(), {f, f + 1, f + 2});
        s.faceObject.push_back(f * objects / faces);
    }
    return s;
}

void expectSameAsBruteForce(const Soup& s, const char* what) {
    const std::vector<FacePair> all = bruteForceIntersections(s);
    for (const PairRules& rules : {kBetween, kSelf, kBoth}) {
        const std::vector<FacePair> expected = validUnder(all, s, rules);
        EXPECT_FALSE(expected.empty()) << what << ": the soup should have intersections to find";
        EXPECT_EQ(exactIntersectingPairs(s.faceIndices, s.faceObject, s.positions, rules), expected)
            << what << " between=" << rules.betweenObjects << " self=" << rules.selfCollisions;
    }
}

TEST(GroundTruthPairs, RandomSoupsMatchTheOracleOnEveryPair) {
    // Large triangles over a shared node pool (dense: most boxes overlap), and small ones in a strip.
    expectSameAsBruteForce(randomSoup(1, 300, 160, 3, 1.0f, 0.0f), "random soup");
    expectSameAsBruteForce(ribbonSoup(2, 200, 3, 0.15f), "random ribbon");
}

TEST(GroundTruthPairs, GridSnappedSoupsWithTouchingAndCoplanarFaces) {
    // Corners on a 5^3 lattice: many pairs touch at a point or an edge or share a plane, exactly
    // the pairs a box test or a floating-point filter would get wrong by one ulp.
    for (unsigned seed = 10; seed <= 11; ++seed)
        expectSameAsBruteForce(randomSoup(seed, 120, 160, 2, 1.0f, 4.0f), "grid-snapped soup");
}

TEST(GroundTruthPairs, NearlyCoplanarSoupAtTheFilterBoundary) {
    // Triangles on the plane z = 0.5 with corners nudged by at most a few ulps: every orientation
    // is within the double filter's error bound or barely outside it, so the filter has to defer
    // to the oracle exactly when it is unsure.
    std::mt19937 rng(7);
    Soup s = randomSoup(7, 200, 160, 2, 1.0f, 0.0f);
    std::uniform_int_distribution<int> ulps(-3, 3);
    for (glm::vec3& p : s.positions) {
        p.z = 0.5f;
        for (int k = ulps(rng); k != 0; k += (k > 0 ? -1 : 1)) p.z = std::nextafter(p.z, k > 0 ? 1.0f : 0.0f);
    }
    expectSameAsBruteForce(s, "nearly coplanar soup");
}

TEST(GroundTruthPairs, NoRulesMeansNoPairs) {
    const Soup s = randomSoup(3, 50, 50, 2, 1.0f, 0.0f);
    EXPECT_TRUE(exactIntersectingPairs(s.faceIndices, s.faceObject, s.positions, PairRules{}).empty());
}

/// Bodies flattened, with each face's object and float positions.
Soup soupOf(const std::vector<Body>& bodies) {
    Scene scene;
    scene.bodies = bodies;
    const model::FlatModel m = model::flatten(scene);
    Soup s;
    s.faceIndices = m.faceIndices;
    for (std::uint32_t o = 0; o < m.objects.size(); ++o)
        s.faceObject.insert(s.faceObject.end(), m.objects[o].faceCount, o);
    for (const glm::dvec3& p : m.positions) s.positions.push_back(glm::vec3(p));
    return s;
}

Body translated(Body body, const glm::dvec3& offset) {
    for (glm::dvec3& p : body.positions) p += offset;
    return body;
}

/// Thickness 0 makes twinCandidates' boxes the bare float boxes (lo - 0.0f == lo exactly).
std::vector<FacePair> twinReference(const Soup& s, const PairRules& rules) {
    return twinIntersections(s.faceIndices, s.positions,
                             twinCandidates(s.faceIndices, s.faceObject, s.positions, 0.0, rules));
}

TEST(GroundTruthPairs, TetBoxesPushedIntoEachOtherMatchTheTwin) {
    const Body box = detail::generateTetBox({1.0, 1.0, 1.0}, {6, 6, 6}); // 432 faces
    // Overlapping at an odd offset (faces cross), and exactly face to face (touching, coplanar).
    for (const glm::dvec3& offset : {glm::dvec3(0.8, 0.1, 0.05), glm::dvec3(1.0, 0.25, 0.0)}) {
        const Soup s = soupOf({box, translated(box, offset)});
        const std::vector<FacePair> both = twinReference(s, kBoth);
        for (const PairRules& rules : {kBetween, kSelf, kBoth}) {
            const std::vector<FacePair> expected = validUnder(both, s, rules);
            EXPECT_EQ(exactIntersectingPairs(s.faceIndices, s.faceObject, s.positions, rules), expected)
                << "offset " << offset.x << " between=" << rules.betweenObjects
                << " self=" << rules.selfCollisions;
            // A tet box has no self-intersections: coplanar neighbours on one side share no point
            // unless they share a node, which the self rule excludes.
            if (!rules.betweenObjects)
                EXPECT_TRUE(expected.empty());
            else
                EXPECT_FALSE(expected.empty());
        }
    }
}

TEST(GroundTruthPairs, SpheresOverlappingMatchTheTwin) {
    // Curved surfaces: almost every overlapping box pair is rejected by the double filter.
    const Body sphere = detail::generateSphere(0.5, 3); // 1280 faces
    const Soup s = soupOf({sphere, translated(sphere, {0.9, 0.05, 0.0})});
    for (const PairRules& rules : {kBetween, kBoth}) {
        const std::vector<FacePair> expected = twinReference(s, rules);
        EXPECT_FALSE(expected.empty());
        EXPECT_EQ(exactIntersectingPairs(s.faceIndices, s.faceObject, s.positions, rules), expected);
    }
}

// ---- deepestPenetration ----

/// Nodes, faces and objects of some bodies, in double, plus free nodes of one extra object
/// without faces (probes placed by the test).
struct Model {
    std::vector<std::uint32_t> faceIndices, faceObject, nodeObject;
    std::vector<glm::dvec3> positions;
};

Model modelOf(const std::vector<Body>& bodies, const std::vector<glm::dvec3>& probes = {}) {
    Scene scene;
    scene.bodies = bodies;
    const model::FlatModel m = model::flatten(scene);
    Model model{m.faceIndices, {}, {}, m.positions};
    for (std::uint32_t o = 0; o < m.objects.size(); ++o) {
        model.faceObject.insert(model.faceObject.end(), m.objects[o].faceCount, o);
        model.nodeObject.insert(model.nodeObject.end(), m.objects[o].nodeCount, o);
    }
    for (const glm::dvec3& p : probes) {
        model.positions.push_back(p);
        model.nodeObject.push_back(static_cast<std::uint32_t>(bodies.size()));
    }
    return model;
}

Penetration penetrationOf(const Model& m, const std::vector<bool>& closed) {
    return deepestPenetration(m.faceIndices, m.faceObject, m.nodeObject, m.positions, closed);
}

// Depths below are differences of a few coordinates of size <= 1: the double distance is exact
// or within a few ulps of 1, so 1e-12 is ample; a wrong face or a wrong inside test would be off
// by at least 0.05.
constexpr double kTol = 1e-12;

const Body kUnitBox = detail::generateTetBox({1.0, 1.0, 1.0}, {2, 2, 2}); // [-0.5, 0.5]^3, node at origin

TEST(GroundTruthPenetration, ProbeAtAKnownDepthInsideAUnitBox) {
    // Depth = distance to the nearest face: 0.5 - 0.4 = 0.1 through the +x face.
    const Model m = modelOf({kUnitBox}, {{0.4, 0.0, 0.0}});
    const Penetration p = penetrationOf(m, {true, false});
    EXPECT_NEAR(p.depth, 0.1, kTol);
    EXPECT_EQ(p.node, m.positions.size() - 1);
    EXPECT_EQ(p.object, 0u);
}

TEST(GroundTruthPenetration, TheDeepestOfSeveralProbesWins) {
    // Depths 0.1 (x face), 0.2 (nearest is the y face at 0.5 - 0.3), 0.35 (z face, -0.5 + 0.35).
    const Model m = modelOf({kUnitBox}, {{0.4, 0.0, 0.0}, {0.0, 0.3, 0.1}, {0.1, 0.0, -0.15}});
    const Penetration p = penetrationOf(m, {true, false});
    EXPECT_NEAR(p.depth, 0.35, kTol);
    EXPECT_EQ(p.node, m.positions.size() - 1);
}

TEST(GroundTruthPenetration, ProbesOutsideGiveZero) {
    // Outside the box entirely, and inside a sphere's bounding box but outside the sphere (the
    // winding test, not the box cull, must reject the corner).
    const Body sphere = detail::generateSphere(0.5, 3);
    const Model m = modelOf({kUnitBox, translated(sphere, {3.0, 0.0, 0.0})},
                            {{0.6, 0.0, 0.0}, {0.0, -2.0, 0.3}, {3.0 + 0.45, 0.45, 0.4}});
    const Penetration p = penetrationOf(m, {true, true, false});
    EXPECT_EQ(p.depth, 0.0);
}

TEST(GroundTruthPenetration, ProbesOnTheSurfaceGiveZero) {
    // On a face, on an edge and on a corner of the box: the winding number is about 0.5 there and
    // may land on either side, but the distance to the surface is 0 either way (the face-region
    // distance is measured along the normal, exactly 0 for a point in an axis-aligned face).
    const Model m = modelOf({kUnitBox}, {{0.5, 0.1, -0.2}, {0.5, 0.5, 0.3}, {-0.5, -0.5, -0.5}});
    EXPECT_EQ(penetrationOf(m, {true, false}).depth, 0.0);
}

TEST(GroundTruthPenetration, NodesOfTheSameObjectAreIgnored) {
    // The box's own interior node at the origin is 0.5 deep inside its own surface.
    const Model m = modelOf({kUnitBox});
    EXPECT_EQ(penetrationOf(m, {true}).depth, 0.0);
}

TEST(GroundTruthPenetration, OpenClothIsNeverPenetratedButItsNodesPenetrateABox) {
    // A 0.5 x 0.5 cloth with 5 x 5 nodes through the box's centre (node 12 at the origin).
    const Body cloth = detail::generateCloth(0.5, 0.5, 5, 5, true, false);
    const Model m = modelOf({kUnitBox, cloth}, {{0.0, 0.0, 0.01}});
    // Flagged open, neither the box (which holds the probe 0.49 deep) nor the cloth is penetrated.
    EXPECT_EQ(penetrationOf(m, {false, false}).depth, 0.0);
    // With the box closed, the probe (0.49 deep) and the cloth's centre node (0.5 deep) are in it.
    const Penetration p = penetrationOf(m, {true, false});
    EXPECT_NEAR(p.depth, 0.5, kTol);
    EXPECT_EQ(p.object, 0u);
    EXPECT_EQ(p.node, static_cast<std::uint32_t>(kUnitBox.positions.size()) + 12u);
}

TEST(GroundTruthPenetration, RandomProbesInAConvexPolyhedronMatchItsFacePlanes) {
    // An icosphere is convex: a point is inside iff it is below every face plane, and its distance
    // to the surface is then the smallest distance to those planes. This checks the patch
    // hierarchy (caps for far patches, branch and bound for the distance) against the definition.
    const glm::dvec3 centre(0.3, -0.2, 0.1);
    const Body sphere = translated(detail::generateSphere(0.5, 3), centre);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coord(-0.55, 0.55);
    int inside = 0;
    for (int k = 0; k < 120; ++k) {
        const glm::dvec3 probe = centre + glm::dvec3(coord(rng), coord(rng), coord(rng));
        double planeDepth = std::numeric_limits<double>::infinity();
        for (const auto& f : sphere.faces) {
            const glm::dvec3 a = sphere.positions[f[0]], b = sphere.positions[f[1]],
                             c = sphere.positions[f[2]];
            const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a)); // outward
            planeDepth = std::min(planeDepth, glm::dot(a - probe, n));
        }
        if (std::abs(planeDepth) < 1e-9) continue; // on the surface: either answer would do
        const double expected = std::max(planeDepth, 0.0);
        inside += expected > 0.0;
        EXPECT_NEAR(penetrationOf(modelOf({sphere}, {probe}), {true, false}).depth, expected, kTol)
            << "probe " << k;
    }
    EXPECT_GT(inside, 25); // about 39% of the cube of probes lies in the sphere
    EXPECT_LT(inside, 75);
}

TEST(GroundTruthPenetration, TwoBoxesOverlapping) {
    // B: a 0.6 box centred at (0.45, 0, 0), spanning x in [0.15, 0.75], y and z in [-0.3, 0.3].
    // A's only node inside B is (0.5, 0, 0), 0.25 from B's +x face; B's node (0.15, 0, 0) is inside
    // A, 0.35 from A's +x face, the deepest (B's other nodes in A are at most 0.2 deep).
    const Body b = translated(detail::generateTetBox({0.6, 0.6, 0.6}, {2, 2, 2}), {0.45, 0.0, 0.0});
    const Model m = modelOf({kUnitBox, b});
    const Penetration p = penetrationOf(m, {true, true});
    EXPECT_NEAR(p.depth, 0.35, kTol);
    EXPECT_EQ(p.object, 0u);
    ASSERT_LT(p.node, m.positions.size());
    EXPECT_NEAR(glm::length(m.positions[p.node] - glm::dvec3(0.15, 0.0, 0.0)), 0.0, kTol);
    // Only A closed: B's nodes in A count, 0.35. Only B closed: A's node (0.5, 0, 0), 0.25 deep.
    EXPECT_NEAR(penetrationOf(m, {true, false}).depth, 0.35, kTol);
    const Penetration intoB = penetrationOf(m, {false, true});
    EXPECT_NEAR(intoB.depth, 0.25, kTol);
    EXPECT_EQ(intoB.object, 1u);
}

} // namespace
} // namespace glcollide::cpu
