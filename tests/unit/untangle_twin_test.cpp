// The untangling step of decision 0024 ("Deep intersections") on the CPU: where the intersection
// segment of two triangles ends, and, iterated on small scenes whose objects intersect deeper than
// any contact thickness, whether the exact oracle (GMP) then finds no intersecting face pair and no
// node inside another closed body. The GPU kernels are compared with this twin in
// tests/gl/untangle_gl_test.cpp.
#include "cpu/oracle/exact_tri_tri.hpp"
#include "cpu/oracle/ground_truth.hpp"
#include "cpu/untangle_twin.hpp"
#include "model/features.hpp"
#include "model/flat_model.hpp"

#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cstdio>
#include <random>
#include <string>

namespace glcollide {
namespace {

using cpu::intersectionPiercings;
using cpu::Piercing;

TEST(UntangleTwin, PiercingsAreTheSegmentsEnds) {
    // A lies in z = 0; B stands in x = 0.2 and its edges 01 and 20 cross z = 0 at their middles.
    const std::array<glm::dvec3, 3> a = {glm::dvec3(-1, -1, 0), glm::dvec3(2, -1, 0), glm::dvec3(-1, 2, 0)};
    const std::array<glm::dvec3, 3> b = {glm::dvec3(0.2, 0, -1), glm::dvec3(0.2, 0.6, 1),
                                         glm::dvec3(0.2, -0.4, 1)};
    const std::vector<Piercing> p = intersectionPiercings(a, b);
    ASSERT_EQ(p.size(), 2u);
    EXPECT_FALSE(p[0].edgeOfFirst);
    EXPECT_EQ(p[0].edge, (std::array<int, 2>{0, 1}));
    EXPECT_EQ(p[1].edge, (std::array<int, 2>{2, 0}));
    // Exact in binary: the crossings are at s = 1/2; 1e-15 covers the rounding of 0.6 and 0.4.
    EXPECT_NEAR(p[0].s, 0.5, 1e-15);
    EXPECT_NEAR(glm::length(p[0].point - glm::dvec3(0.2, 0.3, 0)), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(p[1].point - glm::dvec3(0.2, -0.2, 0)), 0.0, 1e-15);
    // Barycentrics in A: the point is their combination.
    for (const Piercing& q : p) {
        const glm::dvec3 back = q.barycentric[0] * a[0] + q.barycentric[1] * a[1] + q.barycentric[2] * a[2];
        EXPECT_NEAR(glm::length(back - q.point), 0.0, 1e-15);
    }
}

TEST(UntangleTwin, CoplanarAndTouchingPairsHaveNoSegmentToShrink) {
    const std::array<glm::dvec3, 3> a = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};
    const std::array<glm::dvec3, 3> coplanar = {glm::dvec3(0.2, 0.2, 0), glm::dvec3(2, 0.2, 0),
                                                glm::dvec3(0.2, 2, 0)};
    EXPECT_TRUE(intersectionPiercings(a, coplanar).empty());
    // A vertex resting on A's interior: its edges end on A's plane, not across it.
    const std::array<glm::dvec3, 3> touching = {glm::dvec3(0.2, 0.2, 0), glm::dvec3(0.5, 0.2, 1),
                                                glm::dvec3(0.2, 0.5, 1)};
    EXPECT_TRUE(intersectionPiercings(a, touching).empty());
    cpu::UntangleInput in;
    in.positions = {a[0], a[1], a[2], touching[0], touching[1], touching[2]};
    in.inverseMass.assign(6, 1.0);
    in.faces = {{0, 1, 2}, {3, 4, 5}};
    in.faceObject = {0, 1};
    in.objectClosed = {false, false};
    in.pairs = {{0, 1}};
    in.step = 0.01;
    const cpu::UntangleResult r = cpu::untangleStep(in);
    EXPECT_EQ(r.unresolvedPairs, 1u);
    EXPECT_EQ(r.movedNodes, 0u);
}

/// A scene's bodies flattened, with what the oracle needs.
struct Model {
    model::FlatModel flat;
    std::vector<std::uint32_t> faceObject, nodeObject;
    std::vector<bool> objectClosed;
    cpu::PairRules rules{true, true}; ///< the pairs that count (and push)
};

Model modelOf(const std::string& objectsJson) {
    const std::string json =
        R"({"format_version": 1, "name": "t", "effects": ["collisions"], "objects": [)" + objectsJson + "]}";
    Model m;
    m.flat = model::flatten(parseScene(json, ".", "untangle"));
    for (std::uint32_t o = 0; o < m.flat.objects.size(); ++o) {
        const model::ObjectRange& r = m.flat.objects[o];
        m.faceObject.insert(m.faceObject.end(), r.faceCount, o);
        m.nodeObject.insert(m.nodeObject.end(), r.nodeCount, o);
        m.objectClosed.push_back(model::isClosedSurface(m.flat.faceIndices, r.firstFace, r.faceCount));
    }
    return m;
}

std::vector<cpu::FacePair> intersecting(const Model& m) {
    std::vector<glm::vec3> p;
    for (const glm::dvec3& x : m.flat.positions) p.emplace_back(x);
    return cpu::exactIntersectingPairs(m.flat.faceIndices, m.faceObject, p, m.rules);
}

/// Untangling steps until the oracle finds no intersecting pair; returns the steps taken (or
/// `most` + 1 when pairs remain).
int untangle(Model& m, double step, int most) {
    cpu::UntangleInput in;
    in.inverseMass = m.flat.inverseMasses;
    for (std::size_t f = 0; f < m.faceObject.size(); ++f) {
        in.faces.push_back(
            {m.flat.faceIndices[3 * f], m.flat.faceIndices[3 * f + 1], m.flat.faceIndices[3 * f + 2]});
    }
    in.faceObject = m.faceObject;
    in.objectClosed = m.objectClosed;
    in.step = step;
    for (int k = 0; k <= most; ++k) {
        const std::vector<cpu::FacePair> pairs = intersecting(m);
        if (pairs.empty()) return k;
        in.pairs.clear();
        in.pairs.assign(pairs.begin(), pairs.end());
        in.positions = m.flat.positions;
        const cpu::UntangleResult r = cpu::untangleStep(in);
        EXPECT_GT(r.movedNodes, 0u) << "step " << k << ": intersecting pairs but nothing moved";
        for (std::size_t i = 0; i < m.flat.positions.size(); ++i) m.flat.positions[i] += r.displacement[i];
    }
    return most + 1;
}

double deepest(const Model& m) {
    return cpu::deepestPenetration(m.flat.faceIndices, m.faceObject, m.nodeObject, m.flat.positions,
                                   m.objectClosed)
        .depth;
}

constexpr double kStep = 0.004; // m

// The steps a scene is given: its depth over the step, times 4 (the pushes of a node's pairs need
// not point the same way, and the nodes that pierce move first, dragging the rest after them).
int budget(double depth) {
    return static_cast<int>(4.0 * depth / kStep);
}

TEST(UntangleTwin, TwoBoxesOverlappingAtAnEdgeComeApart) {
    Model m = modelOf(
        R"({"name": "a", "mass": 0.1, "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]}},
        {"name": "b", "mass": 0.1, "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]},
         "transform": {"translate": [0.07, 0.07, 0.013]}})");
    ASSERT_TRUE(m.objectClosed[0] && m.objectClosed[1]);
    ASSERT_FALSE(intersecting(m).empty());
    EXPECT_GT(deepest(m), 0.02); // 3 cm overlap along x and y: the deepest node is 1.5 cm inside
    const int steps = untangle(m, kStep, budget(0.03));
    EXPECT_LE(steps, budget(0.03)) << "still intersecting";
    EXPECT_EQ(deepest(m), 0.0) << "apart, not one inside the other";
}

TEST(UntangleTwin, ABoxSunkIntoAnotherFromAboveComesOut) {
    // A's side walls are parallel to the contour's direction of shrinking: ICM alone has no push
    // for them (the prism case); B's outward normal pushes them out.
    Model m = modelOf(
        R"({"name": "b", "mass": 0.1, "generator": {"type": "tet_box", "size": [0.2, 0.1, 0.2], "resolution": [4, 2, 4]}},
        {"name": "a", "mass": 0.1, "generator": {"type": "tet_box", "size": [0.06, 0.06, 0.06], "resolution": [2, 2, 2]},
         "transform": {"translate": [0.011, 0.06, 0.007]}})");
    ASSERT_FALSE(intersecting(m).empty());
    EXPECT_GT(deepest(m), 0.015); // A's bottom 2 cm under B's top
    const int steps = untangle(m, kStep, budget(0.02));
    EXPECT_LE(steps, budget(0.02)) << "still intersecting";
    EXPECT_EQ(deepest(m), 0.0);
}

TEST(UntangleTwin, ATentPokedThroughASheetIsPulledBack) {
    // Two open sheets 1 cm apart; the lower one's middle node lifted 3 cm, through the upper one.
    Model m = modelOf(
        R"({"name": "upper", "mass": 0.1, "generator": {"type": "cloth", "size": [0.2, 0.2], "resolution": [11, 11]}},
        {"name": "lower", "mass": 0.1, "generator": {"type": "cloth", "size": [0.2, 0.2], "resolution": [11, 11]},
         "transform": {"translate": [0.003, 0.002, -0.01]}})");
    ASSERT_FALSE(m.objectClosed[0] || m.objectClosed[1]);
    m.flat.positions[m.flat.objects[1].firstNode + 60].z = 0.02;
    ASSERT_FALSE(intersecting(m).empty());
    const int steps = untangle(m, kStep, budget(0.02));
    EXPECT_LE(steps, budget(0.02)) << "still intersecting";
    // Pulled back, not pushed through: the tip is below the upper sheet again.
    EXPECT_LT(m.flat.positions[m.flat.objects[1].firstNode + 60].z, m.flat.positions[60].z);
}

TEST(UntangleTwin, AClothDentedIntoABoxIsPushedOut) {
    // The box's top face is at z = 0.05; the cloth lies 5 mm above it with its middle node 3 cm
    // inside the box.
    Model m = modelOf(
        R"({"name": "box", "mass": 0.1, "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]}},
        {"name": "cloth", "mass": 0.1, "generator": {"type": "cloth", "size": [0.2, 0.2], "resolution": [11, 11]},
         "transform": {"translate": [0.004, 0.003, 0.055]}})");
    m.flat.positions[m.flat.objects[1].firstNode + 60].z = 0.02;
    ASSERT_FALSE(intersecting(m).empty());
    EXPECT_GT(deepest(m), 0.025);
    const int steps = untangle(m, kStep, budget(0.03));
    EXPECT_LE(steps, budget(0.03)) << "still intersecting";
    EXPECT_EQ(deepest(m), 0.0);
}

// Random poses: box B turned by random angles about all three axes, its centre 6.5–8.5 cm from
// A's (10 cm boxes), 20 seeds. Each must come apart within budget(3.5 cm), with no node inside the
// other box. Boxes of one cell (every node on the surface: without springs here an inner node
// would never move) and pairs between the boxes only (without springs a surface pushed in many
// directions folds onto itself, which in the engine its springs undo).
TEST(UntangleTwin, RandomlyTurnedBoxesComeApart) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(0.0, 90.0), unit(-1.0, 1.0), distance(0.065, 0.085);
    int tangled = 0;
    for (int seed = 0; seed < 20; ++seed) {
        glm::dvec3 dir(unit(rng), unit(rng), unit(rng));
        dir = glm::normalize(dir);
        const glm::dvec3 at = distance(rng) * dir;
        const std::string b =
            R"({"name": "b", "mass": 0.1, "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [1, 1, 1]},
            "transform": {"translate": [)" +
            std::to_string(at.x) + ", " + std::to_string(at.y) + ", " + std::to_string(at.z) +
            R"(], "rotate_deg": [)" + std::to_string(angle(rng)) + ", " + std::to_string(angle(rng)) + ", " +
            std::to_string(angle(rng)) + "]}}";
        Model m = modelOf(
            R"({"name": "a", "mass": 0.1, "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [1, 1, 1]}},)" +
            b);
        m.rules.selfCollisions = false;
        if (intersecting(m).empty()) continue; // the turn left them apart: nothing to untangle
        ++tangled;
        const int steps = untangle(m, kStep, budget(0.035));
        EXPECT_LE(steps, budget(0.035)) << "seed " << seed << ": still intersecting";
        EXPECT_EQ(deepest(m), 0.0) << "seed " << seed;
    }
    EXPECT_GE(tangled, 15) << "too few seeds start intersecting to say much";
    std::printf("[ untangle ] %d of 20 random poses started intersecting\n", tangled);
}

// A closed surface folded through itself: the top node of a sphere pulled 2 cm below its bottom,
// so the faces around it pierce the bottom from inside. Within one closed surface its outward
// normal does not say which side is wrong (pushing along the bottom's normal would push the spike
// further out): such pairs shrink their contour instead.
TEST(UntangleTwin, AClosedSurfaceFoldedThroughItselfIsPulledBack) {
    Model m = modelOf(
        R"({"name": "ball", "mass": 0.1, "generator": {"type": "sphere", "radius": 0.1, "subdivisions": 2}})");
    m.rules.betweenObjects = false;
    ASSERT_TRUE(m.objectClosed[0]);
    std::size_t top = 0;
    for (std::size_t i = 0; i < m.flat.positions.size(); ++i)
        if (m.flat.positions[i].y > m.flat.positions[top].y) top = i;
    m.flat.positions[top].y = -0.12;
    ASSERT_FALSE(intersecting(m).empty());
    const int steps = untangle(m, kStep, budget(0.04));
    EXPECT_LE(steps, budget(0.04)) << "still intersecting";
}

} // namespace
} // namespace glcollide
