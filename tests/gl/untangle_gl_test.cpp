// Untangling (decision 0024, "Deep intersections"): intersections deeper than the contact
// thickness, which no contact reaches, are pushed apart by the intersecting pairs themselves.
// One step of the GPU kernels against the CPU twin (cpu::untangleStep, double), and whole runs
// checked by the exact CPU oracle (cpu::exactIntersectingPairs, GMP: no intersecting face pair)
// and by the winding-number penetration test (cpu::deepestPenetration: no node inside another
// closed body — apart, not one inside the other).

#include "cpu/oracle/ground_truth.hpp"
#include "cpu/untangle_twin.hpp"
#include "model/features.hpp"
#include "passes/untangle.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <string>

namespace glcollide {
namespace {

/// The scene's faces, objects and closed flags in the engine's global numbering.
struct Topology {
    std::vector<std::uint32_t> faceIndices, faceObject, nodeObject;
    std::vector<bool> objectClosed;
};

Topology topology(const Engine& engine) {
    Topology t;
    const Scene& scene = engine.scene();
    const std::vector<std::uint32_t> first = engine.bodyFirstNodes();
    for (std::uint32_t b = 0; b < scene.bodies.size(); ++b) {
        const std::uint32_t firstFace = static_cast<std::uint32_t>(t.faceObject.size());
        for (const auto& f : scene.bodies[b].faces) {
            for (int k = 0; k < 3; ++k) t.faceIndices.push_back(first[b] + f[k]);
            t.faceObject.push_back(b);
        }
        t.nodeObject.insert(t.nodeObject.end(), scene.bodies[b].positions.size(), b);
        t.objectClosed.push_back(model::isClosedSurface(
            t.faceIndices, firstFace, static_cast<std::uint32_t>(scene.bodies[b].faces.size())));
    }
    return t;
}

std::size_t intersectingPairs(const Engine& engine, const Topology& t) {
    std::vector<glm::vec3> x;
    for (const glm::dvec3& p : engine.readPositions()) x.emplace_back(p);
    cpu::PairRules rules;
    rules.betweenObjects = engine.scene().effects.has(Effect::Collisions);
    rules.selfCollisions = engine.scene().effects.has(Effect::SelfCollisions);
    return cpu::exactIntersectingPairs(t.faceIndices, t.faceObject, x, rules).size();
}

double deepestPenetration(const Engine& engine, const Topology& t) {
    return cpu::deepestPenetration(t.faceIndices, t.faceObject, t.nodeObject, engine.readPositions(),
                                   t.objectClosed)
        .depth;
}

// Two tet boxes, 10 cm, B's corner about 3 cm inside A, B turned by a few degrees so that no
// piercing lies on an edge (there the float kernel and the double twin may disagree on which of
// the two faces around the edge holds it: a choice of direction, never of an answer). Nothing but
// collisions: at rest and without forces x1 = x0 until Untangle (the first substep has no
// contacts yet), so one step moves exactly the twin's displacement.
constexpr const char* kTurnedBoxes =
    R"({"name": "a", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]}, "mass": 0.2},
    {"name": "b", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]},
     "transform": {"translate": [0.0713, 0.0689, 0.0127], "rotate_deg": [7, 11, 3]}, "mass": 0.2})";

Scene scene(const std::string& effects, const std::string& time, const std::string& objects) {
    const std::string json =
        R"({"format_version": 1, "name": "untangle", "effects": [)" + effects + R"(], "time": )" + time +
        R"(, "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 500, "response": "intersection_free"},
        "objects": [)" +
        objects + "]}";
    return parseScene(json, ".", "untangle");
}

TEST(UntangleGl, OneStepMovesWhatTheTwinMoves) {
    Engine engine(scene(R"("collisions")", R"({"dt": 0.016666666666666666, "substeps": 1})", kTurnedBoxes));
    const Topology t = topology(engine);
    const std::vector<glm::dvec3> before = engine.readPositions();
    ASSERT_GT(intersectingPairs(engine, t), 0u);
    engine.step();
    const std::vector<glm::dvec3> after = engine.readPositions();
    const CollisionStats& c = engine.lastStep().collision;
    EXPECT_EQ(c.untangleSubsteps, 1u);

    cpu::UntangleInput in;
    in.positions = before;
    for (const Body& b : engine.scene().bodies)
        for (std::size_t i = 0; i < b.positions.size(); ++i)
            in.inverseMass.push_back(b.pinned.empty() || !b.pinned[i] ? 1.0 / b.masses[i] : 0.0);
    for (std::size_t f = 0; f < t.faceObject.size(); ++f) {
        in.faces.push_back({t.faceIndices[3 * f], t.faceIndices[3 * f + 1], t.faceIndices[3 * f + 2]});
    }
    in.faceObject = t.faceObject;
    in.objectClosed = t.objectClosed;
    for (const auto& p : engine.readIntersectingPairs()) in.pairs.push_back({p[0], p[1]});
    ASSERT_FALSE(in.pairs.empty());
    in.step = passes::kUntangleStepPerThickness * 0.01;
    const cpu::UntangleResult twin = cpu::untangleStep(in);
    EXPECT_EQ(c.untangledNodes, twin.movedNodes);
    EXPECT_EQ(c.untangleUnresolvedPairs, twin.unresolvedPairs);
    ASSERT_GT(twin.movedNodes, 0u);

    // Parts per node, for the fixed-point bound.
    std::vector<int> parts(before.size(), 0);
    for (const auto& f : in.pairs)
        for (const std::uint32_t face : f)
            for (int k = 0; k < 3; ++k) parts[in.faces[face][k]] += 2;
    for (std::size_t i = 0; i < before.size(); ++i) {
        // Each part is rounded to 1/65536 per component (UntanglePass::kPushScale): the sum by at
        // most √3·parts/2/65536, the normalised push by twice that; the float evaluation of a part
        // (a few dozen operations on well-separated geometry) by about 1e-6 of it, covered by 1e-4;
        // the float position after adding by its rounding, 2⁻²⁴·0.2 m < 1e-7 m.
        const double tol = in.step * (std::sqrt(3.0) * parts[i] / 65536.0 + 1e-4) + 1e-7;
        EXPECT_LE(glm::length((after[i] - before[i]) - twin.displacement[i]), tol) << "node " << i;
    }
}

// The boxes under gravity-free implicit Euler at one substep per frame and with springs: the
// deepest node is 3 cm inside, a node moves at most 5 mm per substep (half the thickness), so
// they are apart after some 6–12 substeps; 24 (4× the depth over the step) are given.
void expectComesApart(Engine& engine, int within, int frames) {
    const Topology t = topology(engine);
    ASSERT_GT(deepestPenetration(engine, t), 0.02);
    int freeFrom = -1;
    for (int frame = 1; frame <= frames; ++frame) {
        engine.step();
        const CollisionStats& c = engine.lastStep().collision;
        if (freeFrom < 0 && c.reachedIntersectionFree) freeFrom = frame;
        if (freeFrom >= 0 && frame > freeFrom) {
            EXPECT_EQ(c.maxIntersectingPairs, 0u) << "frame " << frame << ": intersecting again";
        }
    }
    ASSERT_GE(freeFrom, 1) << "never intersection-free";
    EXPECT_LE(freeFrom, within);
    EXPECT_EQ(intersectingPairs(engine, t), 0u);
    EXPECT_EQ(deepestPenetration(engine, t), 0.0) << "apart, not one inside the other";
}

TEST(UntangleGl, BoxesIntersectingDeeperThanTheThicknessComeApartUnderImplicitEuler) {
    Engine engine(scene(
        R"("springs", "collisions")",
        R"({"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1})",
        R"({"name": "a", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]}, "mass": 0.2, "springs": {"stiffness": 400}},
    {"name": "b", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]},
     "transform": {"translate": [0.07, 0.07, 0.013]}, "mass": 0.2, "springs": {"stiffness": 400}})"));
    expectComesApart(engine, 24, 40);
}

TEST(UntangleGl, BoxesIntersectingDeeperThanTheThicknessComeApartUnderSymplecticEuler) {
    Engine engine(scene(
        R"("springs", "collisions")", R"({"dt": 0.016666666666666666, "substeps": 4})",
        R"({"name": "a", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]}, "mass": 0.2, "springs": {"stiffness": 400}},
    {"name": "b", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]},
     "transform": {"translate": [0.07, 0.07, 0.013]}, "mass": 0.2, "springs": {"stiffness": 400}})"));
    expectComesApart(engine, 24, 40); // frames of 4 substeps: 6 frames would do
}

// An open cloth whose middle node was pushed 3 cm into a pinned box (its top face at z = 0.05):
// the box's outward normals push the cloth's edges out. Without springs (their pull would bring
// the node back by itself), so every move is the untangling's.
TEST(UntangleGl, AClothDentedIntoAPinnedBoxIsPushedOut) {
    Scene s = scene(
        R"("collisions", "self_collisions")", R"({"dt": 0.016666666666666666, "substeps": 1})",
        R"({"name": "box", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]}, "mass": 0.2},
    {"name": "cloth", "generator": {"type": "cloth", "size": [0.2, 0.2], "resolution": [11, 11]},
     "transform": {"translate": [0.004, 0.003, 0.065]}, "mass": 0.05})");
    s.bodies[0].pinned.assign(s.bodies[0].positions.size(), 1);
    s.bodies[1].positions[60].z = 0.02;
    Engine engine(s);
    expectComesApart(engine, 24, 40);
}

// Steps (at most twice `within` frames) until a substep starts intersection-free; expects that by
// frame `within`, and no intersecting pair by the oracle then.
void expectFreeWithin(Engine& engine, const Topology& t, int within) {
    int freeFrom = -1;
    for (int frame = 1; frame <= 2 * within && freeFrom < 0; ++frame) {
        engine.step();
        if (engine.lastStep().collision.reachedIntersectionFree) freeFrom = frame;
    }
    ASSERT_GE(freeFrom, 1) << "never intersection-free";
    EXPECT_LE(freeFrom, within);
    EXPECT_EQ(intersectingPairs(engine, t), 0u);
}

// Two open sheets 1 cm apart, the lower one's middle node lifted 3 cm, through the upper one:
// no closed object tells the side, the contour's shrinking does (the tent is pulled back, or the
// upper sheet lifted over it).
TEST(UntangleGl, ATentPokedThroughASheetIsPulledBack) {
    Scene s = scene(
        R"("collisions")", R"({"dt": 0.016666666666666666, "substeps": 1})",
        R"({"name": "upper", "generator": {"type": "cloth", "size": [0.2, 0.2], "resolution": [11, 11]}, "mass": 0.05},
    {"name": "lower", "generator": {"type": "cloth", "size": [0.2, 0.2], "resolution": [11, 11]},
     "transform": {"translate": [0.003, 0.002, -0.01]}, "mass": 0.05})");
    s.bodies[1].positions[60].z = 0.02;
    Engine engine(s);
    const Topology t = topology(engine);
    ASSERT_GT(intersectingPairs(engine, t), 0u);
    expectFreeWithin(engine, t, 16); // 2 cm through at 5 mm per substep: 4, times 4
    const std::vector<glm::dvec3> x = engine.readPositions();
    const std::uint32_t lower = engine.bodyFirstNodes()[1];
    EXPECT_LT(x[lower + 60].z, x[60].z) << "the tip is below the upper sheet again";
}

// A closed surface folded through itself (the top node of a sphere pulled 2 cm below its bottom),
// self-collisions only and no springs: within one closed surface the pairs shrink their contour
// (its outward normal would push the spike further out), until no pair intersects.
TEST(UntangleGl, ASelfTangledClosedSurfaceComesApart) {
    Scene s = scene(
        R"("self_collisions")", R"({"dt": 0.016666666666666666, "substeps": 1})",
        R"({"name": "ball", "generator": {"type": "sphere", "radius": 0.1, "subdivisions": 2}, "mass": 0.1})");
    std::size_t top = 0;
    for (std::size_t i = 0; i < s.bodies[0].positions.size(); ++i)
        if (s.bodies[0].positions[i].y > s.bodies[0].positions[top].y) top = i;
    s.bodies[0].positions[top].y = -0.12;
    Engine engine(s);
    const Topology t = topology(engine);
    ASSERT_GT(intersectingPairs(engine, t), 0u);
    expectFreeWithin(engine, t, 16); // 2 cm through at 5 mm per substep: 4, times 4
}

} // namespace
} // namespace glcollide
