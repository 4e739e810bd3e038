// Radial view-based culling changes nothing but time (issue 24, item 4; decision 0025): with
// "culling": "radial" every frame is bit-identical to "culling": "none", and the exact tests find
// the same things — the CCD's pairs that may touch and TriTri's intersecting pairs, substep by
// substep. The scenes are built to fold and to defeat the observer: a soft ball of cloth that
// crumples on the ground (faces turn their backs on the centroid, the centroid leaves the
// squashed surface), a fast one, and a host that moves nodes between frames (the premise is then
// unknown, and the first substep must not cull). The very first substep culls when the start,
// checked standing still before it, has no intersecting pair, and does not when it has. Each case also checks
// that culling acted, so the comparison is not vacuous.

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <epoxy/gl.h>
#include <gtest/gtest.h>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace glcollide {
namespace {

std::string ballScene(const std::string& culling, double speed, double springStiffness, int substeps) {
    return R"({"format_version": 1, "name": "cloth ball", "effects": ["gravity", "springs", "ground", "self_collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": )" +
           std::to_string(substeps) + R"(},
      "ground": {"height": 0.0},
      "collision": {"broad_phase": "bvh", "thickness": 0.005, "stiffness": 500, "response": "intersection_free",
                    "culling": ")" +
           culling + R"("},
      "objects": [
        {"name": "ball", "generator": {"type": "sphere", "radius": 0.15, "subdivisions": 3},
         "transform": {"translate": [0, 0.2, 0]}, "mass": 0.1, "springs": {"stiffness": )" +
           std::to_string(springStiffness) + R"(}, "velocity": [0.5, )" + std::to_string(-speed) +
           R"(, 0]}]})";
}

/// Issue 24's sleeve: a tube of cloth open at both ends, hung from its top ring and spun about its
/// axis, so that it twists and wraps onto itself. Radial culling closes its openings with ghosts.
std::string sleeveScene(const std::string& culling, double spin) {
    return R"({"format_version": 1, "name": "sleeve", "effects": ["gravity", "springs", "self_collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 2},
      "collision": {"broad_phase": "bvh", "thickness": 0.004, "stiffness": 500, "response": "intersection_free",
                    "culling": ")" +
           culling + R"("},
      "objects": [
        {"name": "sleeve", "generator": {"type": "tube", "radius": 0.08, "length": 0.4, "resolution": [16, 12]},
         "transform": {"translate": [0, 0.5, 0]}, "mass": 0.05, "springs": {"stiffness": 40, "bend_stiffness": 0.2},
         "angular_velocity": [0, )" +
           std::to_string(spin) + R"(, 0],
         "pinned": {"inside": {"min": [-0.1, 0.699, -0.1], "max": [0.1, 0.701, 0.1]}}}]})";
}

/// scenes/elbow.json's limb, coarser (16 × 16 nodes, 480 faces): a tube bent by 90 degrees, hung
/// from its top ring and turned about +Z, so that the forearm swings up and the elbow flexes, then
/// falls back; with culling, watched by a skeleton
/// of two bones (docs/culling.md, "Skeletons").
std::string elbowScene(const std::string& culling) {
    const std::string skeleton = culling == "radial" ? R"(, "skeleton": [[[0, 0.27, 0], [0, 0.1, 0]],
        [[0.1273, -0.0273, 0], [0.2973, -0.0273, 0]]])"
                                                     : std::string();
    return R"({"format_version": 1, "name": "elbow", "effects": ["gravity", "springs", "self_collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 2},
      "collision": {"broad_phase": "bvh", "thickness": 0.004, "stiffness": 500, "response": "intersection_free",
                    "culling": ")" +
           culling + R"("},
      "objects": [
        {"name": "elbow", "generator": {"type": "tube", "radius": 0.06, "length": 0.6, "resolution": [16, 16],
                                        "bend_deg": 90},
         "transform": {"translate": [0, 0.6, 0]}, "mass": 0.05, "springs": {"stiffness": 40, "bend_stiffness": 0.05},
         "angular_velocity": [0, 0, 8],
         "pinned": {"inside": {"min": [-0.07, 0.899, -0.07], "max": [0.07, 0.901, 0.07]}})" +
           skeleton + "}]}";
}

/// A flat sheet of cloth (16 × 16 nodes, 450 faces) dropped tilted onto the ground, where it
/// folds onto itself. It is no closed surface, and a fan over its border closes it flat, with no
/// inside: radial culling cuts it into clusters of at most about 32 faces, each watched from behind.
std::string sheetScene(const std::string& culling) {
    const std::string clusters =
        culling == "radial" ? R"(, "observers": "clusters", "cluster_max_faces": 32)" : std::string();
    return R"({"format_version": 1, "name": "sheet", "effects": ["gravity", "springs", "ground", "self_collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1},
      "ground": {"height": 0.0},
      "collision": {"broad_phase": "bvh", "thickness": 0.004, "stiffness": 500, "response": "intersection_free",
                    "culling": ")" +
           culling + R"(")" + clusters + R"(},
      "objects": [
        {"name": "sheet", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [16, 16]},
         "transform": {"translate": [0, 0.12, 0], "rotate_deg": [60, 0, 25]}, "mass": 0.05,
         "springs": {"stiffness": 30, "bend_stiffness": 0.01}, "velocity": [0, -1.5, 0]}]})";
}

struct Totals {
    std::uint64_t culledTriTri = 0, culledCcd = 0, culledSubsteps = 0, substepsWithNonPositive = 0;
    std::uint32_t ghostFaces = 0, substepsViolated = 0;
    bool startFree = false;               ///< the start check found no intersecting pair
    std::uint32_t firstFrameCulled = 0;   ///< substeps of frame 1 that culled
    double firstFrameContactEnergy = 0.0; ///< J: penalty energy after frame 1, without culling
};

/// Steps both engines `frames` frames; every frame: bit-identical positions and the same exact
/// answers. `hostMove`: before that frame, both hosts move node 0 by 1 mm through the position
/// buffer (0: never).
Totals expectIdentical(const std::string& none, const std::string& radial, int frames, int hostMove = 0) {
    Engine a(parseScene(none, ".", "none")), b(parseScene(radial, ".", "radial"));
    Totals t;
    for (int frame = 1; frame <= frames; ++frame) {
        if (frame == hostMove) {
            for (Engine* e : {&a, &b}) {
                glm::vec4 p;
                glGetNamedBufferSubData(e->positionBuffer(), 0, sizeof p, &p);
                p.x += 0.001f;
                glNamedBufferSubData(e->positionBuffer(), 0, sizeof p, &p);
            }
        }
        a.step();
        b.step();
        const CollisionStats &ca = a.lastStep().collision, &cb = b.lastStep().collision;
        EXPECT_EQ(ca.radialSubsteps, 0u);
        EXPECT_EQ(ca.maxIntersectingPairs, cb.maxIntersectingPairs) << "frame " << frame;
        EXPECT_EQ(ca.intersectingPairs, cb.intersectingPairs) << "frame " << frame;
        EXPECT_EQ(ca.ccdVertexFaceHits, cb.ccdVertexFaceHits) << "frame " << frame;
        EXPECT_EQ(ca.ccdEdgeEdgeHits, cb.ccdEdgeEdgeHits) << "frame " << frame;
        EXPECT_EQ(ca.ccdEarliestToi, cb.ccdEarliestToi) << "frame " << frame;
        EXPECT_EQ(ca.safeStepCuts, cb.safeStepCuts) << "frame " << frame;
        const std::vector<glm::dvec3> xa = a.readPositions(), xb = b.readPositions();
        std::size_t differing = 0;
        for (std::size_t i = 0; i < xa.size(); ++i) differing += xa[i] != xb[i] ? 1u : 0u;
        EXPECT_EQ(differing, 0u) << "frame " << frame << ": nodes whose positions differ";
        if (frame == 1) {
            EXPECT_TRUE(cb.radialStartChecked) << "the start was not checked before the first substep";
            EXPECT_FALSE(ca.radialStartChecked) << "checked without culling";
            t.startFree = cb.radialStartFree;
            t.firstFrameCulled = cb.radialSubsteps;
            t.firstFrameContactEnergy = a.energy().contact;
        }
        if (frame == hostMove) {
            EXPECT_FALSE(cb.radialSubsteps == static_cast<std::uint32_t>(b.substepInfo().substeps))
                << "frame " << frame << ": the host moved a node, yet the first substep culled";
        }
        t.culledTriTri += cb.radialCulledTriTriInFrame;
        t.culledCcd += cb.radialCulledCcdInFrame;
        t.culledSubsteps += cb.radialSubsteps;
        t.substepsWithNonPositive += cb.radialSubsteps > 0 && cb.radialNonPositiveFaces > 0 ? 1u : 0u;
        t.ghostFaces = std::max(t.ghostFaces, cb.radialGhostFaces);
        t.substepsViolated += cb.radialSubstepsViolated;
        if (::testing::Test::HasFailure()) break; // the first frame that differs says enough
    }
    return t;
}

// A soft ball of cloth (1,280 faces) thrown onto the ground: it squashes and folds; faces turn
// their backs on the centroid, which is an observer in a poor place by the end.
TEST(RadialCullingGl, ACrumplingBallIsBitIdenticalWithAndWithoutCulling) {
    const Totals t = expectIdentical(ballScene("none", 6.0, 1.0, 1), ballScene("radial", 6.0, 1.0, 1), 45);
    EXPECT_TRUE(t.startFree);
    EXPECT_EQ(t.firstFrameCulled, 1u) << "a free start: the first substep culls";
    EXPECT_GT(t.culledSubsteps, 30u);
    EXPECT_GT(t.culledCcd, 0u);
    EXPECT_GT(t.culledTriTri, 0u);
    EXPECT_GT(t.substepsWithNonPositive, 0u) << "the ball must fold: some faces not positive";
}

// The same ball with a user observer (docs/culling.md, "User observers"): 4 cm off the centre, tied
// to four of the ball's nodes, so it moves with the ball as it squashes — the frames stay
// bit-identical and culling acts.
TEST(RadialCullingGl, ACrumplingBallWithAUserObserverIsBitIdenticalWithAndWithoutCulling) {
    std::string radial = ballScene("radial", 6.0, 1.0, 1);
    const std::string name = R"("name": "ball", )";
    radial.replace(radial.find(name), name.size(), name + R"("observer": [0.03, -0.02, 0.02], )");
    const Totals t = expectIdentical(ballScene("none", 6.0, 1.0, 1), radial, 30);
    EXPECT_GT(t.culledSubsteps, 20u);
    EXPECT_GT(t.culledCcd, 0u);
    EXPECT_GT(t.culledTriTri, 0u);
}

// Fast: 12 m/s into the ground, two substeps per frame.
TEST(RadialCullingGl, AFastBallIsBitIdenticalWithAndWithoutCulling) {
    const Totals t =
        expectIdentical(ballScene("none", 12.0, 40.0, 2), ballScene("radial", 12.0, 40.0, 2), 20);
    EXPECT_GT(t.culledSubsteps, 10u);
    EXPECT_GT(t.culledCcd, 0u);
}

// An open surface: the sleeve twists and wraps onto itself; ghost fans close its two openings (16
// ghost faces each), so it has an observer and its faces are culled.
TEST(RadialCullingGl, ATwistingSleeveIsBitIdenticalWithAndWithoutCulling) {
    const Totals t = expectIdentical(sleeveScene("none", 40.0), sleeveScene("radial", 40.0), 40);
    EXPECT_EQ(t.ghostFaces, 32u);
    EXPECT_GT(t.culledSubsteps, 60u);
    EXPECT_GT(t.culledCcd, 0u);
    EXPECT_GT(t.substepsWithNonPositive, 0u) << "the sleeve must twist: some faces not positive";
    RecordProperty("culled_ccd", static_cast<int>(t.culledCcd));
    RecordProperty("substeps_violated", static_cast<int>(t.substepsViolated));
}

// The same sleeve watched from a segment along its axis (decision 0025, "Segment observers"): its
// faces are judged from their feet on the segment, so faces that lean along the axis as it twists
// stay positive where the centroid saw their backs.
TEST(RadialCullingGl, ATwistingSleeveWithASegmentObserverIsBitIdenticalWithAndWithoutCulling) {
    std::string radial = sleeveScene("radial", 40.0);
    const std::string name = R"("name": "sleeve", )";
    radial.replace(radial.rfind(name), name.size(), name + R"("observer": [[0, -0.17, 0], [0, 0.17, 0]], )");
    const Totals t = expectIdentical(sleeveScene("none", 40.0), radial, 40);
    EXPECT_EQ(t.ghostFaces, 32u);
    EXPECT_GT(t.culledSubsteps, 60u);
    EXPECT_GT(t.culledCcd, 0u);
    RecordProperty("culled_ccd", static_cast<int>(t.culledCcd));
    RecordProperty("substeps_violated", static_cast<int>(t.substepsViolated));
}

// A bent limb watched by a skeleton: one piece per bone, each closed by fans over its cuts and its
// opening, culled on its own; the elbow flexes and its crease folds.
TEST(RadialCullingGl, AnElbowWithASkeletonIsBitIdenticalWithAndWithoutCulling) {
    const Totals t = expectIdentical(elbowScene("none"), elbowScene("radial"), 40);
    // Fans over the two openings (16 faces each) and, from both sides, over the cut (at least 16 each).
    EXPECT_GE(t.ghostFaces, 64u);
    EXPECT_GT(t.culledSubsteps, 60u);
    EXPECT_GT(t.culledCcd, 0u);
    EXPECT_GT(t.substepsWithNonPositive, 0u) << "the elbow must fold: some faces not positive";
    RecordProperty("culled_ccd", static_cast<int>(t.culledCcd));
    RecordProperty("substeps_violated", static_cast<int>(t.substepsViolated));
}

// An open sheet in clusters: it lands tilted and folds; every cluster is closed by ghosts of its
// own (a skirt and an apex behind it), so ghost faces exist, and culling must act.
TEST(RadialCullingGl, AFoldingSheetInClustersIsBitIdenticalWithAndWithoutCulling) {
    const Totals t = expectIdentical(sheetScene("none"), sheetScene("radial"), 45);
    EXPECT_GT(t.ghostFaces, 0u);
    EXPECT_GT(t.culledSubsteps, 30u);
    EXPECT_GT(t.culledCcd, 0u);
    EXPECT_GT(t.substepsWithNonPositive, 0u) << "the sheet must fold: some faces not positive";
    RecordProperty("culled_ccd", static_cast<int>(t.culledCcd));
    RecordProperty("substeps_violated", static_cast<int>(t.substepsViolated));
}

// The host moves a node between frames through the position buffer (as an embedding may): the
// start is not known to be intersection-free, so the next first substep does not cull.
TEST(RadialCullingGl, AHostWriteSwitchesCullingOffForTheNextSubstep) {
    const Totals t =
        expectIdentical(ballScene("none", 2.0, 40.0, 1), ballScene("radial", 2.0, 40.0, 1), 12, 6);
    EXPECT_EQ(t.culledSubsteps, 12u - 1u) << "all but the frame after the host's write";
}

/// Two cloth balls (radius 0.15 m, thickness 5 mm) side by side, the second's centre `secondX`
/// from the first's and turned 31° about z (so that faces, not two vertices, face each other).
std::string twoBallsScene(const std::string& culling, const std::string& secondX) {
    std::string s = ballScene(culling, 0.5, 40.0, 1);
    const std::string effects = R"("self_collisions"])";
    s.replace(s.find(effects), effects.size(), R"("self_collisions", "collisions"])");
    const std::string ball = R"({"name": "ball", )";
    const std::size_t at = s.find(ball);
    const std::string object = s.substr(at, s.rfind('}', s.size() - 3) - at + 1);
    std::string second = object;
    second.replace(second.find(R"("ball")"), 6, R"("other")");
    second.replace(second.find("[0, 0.2, 0]"), 11, "[" + secondX + R"(, 0.2, 0], "rotate_deg": [0, 0, 31])");
    s.insert(at + object.size(), ", " + second);
    return s;
}

// Two balls that overlap at the start (recovery pushes them apart): the start check finds their
// intersecting pairs, so the first substep must not cull; the frames stay bit-identical.
TEST(RadialCullingGl, AnIntersectingStartIsNotCulled) {
    const Totals t = expectIdentical(twoBallsScene("none", "0.25"), twoBallsScene("radial", "0.25"), 4);
    EXPECT_FALSE(t.startFree) << "the balls overlap: the start check must find intersecting pairs";
    EXPECT_EQ(t.firstFrameCulled, 0u);
}

// Two balls within the thickness of each other at the start, not intersecting: the first substep
// culls, and the start check's pairs (contacts at x0) must not reach the first solve, which
// without culling has no earlier detection to take contacts from.
TEST(RadialCullingGl, AStartWithContactsIsCulledAndBitIdentical) {
    const Totals t = expectIdentical(twoBallsScene("none", "0.3"), twoBallsScene("radial", "0.3"), 4);
    EXPECT_TRUE(t.startFree);
    EXPECT_EQ(t.firstFrameCulled, 1u);
    EXPECT_GT(t.firstFrameContactEnergy, 0.0) << "the balls must be within the thickness of each other";
}

TEST(RadialCullingGl, TheSceneRefusesRadialCullingWithoutItsPremise) {
    std::string s = ballScene("radial", 1.0, 40.0, 1);
    const std::string response = R"("response": "intersection_free")";
    s.replace(s.find(response), response.size(), R"("response": "bridson")");
    try {
        (void)parseScene(s, ".", "bridson");
        ADD_FAILURE() << "radial culling with the bridson response was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/collision/culling"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace glcollide
