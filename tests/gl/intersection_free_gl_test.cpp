// The intersection-free response (decision 0024, docs/collisions.md "Intersection-free
// response"): from an intersection-free start no face pair that the scene's effects make collide
// intersects at the end of any substep, whatever the step. Checked two ways on every case: the
// engine's own robust TriTri (exact answers, decision 0007) at the start of every substep
// (CollisionStats::maxIntersectingPairs), and at the end by the exact oracle on the CPU over every
// valid face pair whose boxes overlap (cpu::twinCandidates + cpu::twinIntersections), which shares
// no code with the engine's passes.
// And that contact adds no energy (issue 23, item 3; decision 0024 "Energy guard"): in these closed
// scenes the total energy (kinetic, gravity, springs, the contacts' and the ground's penalty,
// computed on the CPU in double precision from the read-back state: Engine::energy(), which shares
// no code with energy_guard.comp) never ends a substep above its start by more than the float
// resolution that the guard's GPU sums allow (EnergyReport::resolution).

#include "cpu/collision_twin.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

namespace glcollide {
namespace {

/// Intersecting valid face pairs of the engine's current positions, by the exact CPU oracle.
std::size_t exactIntersectingPairs(const Engine& engine) {
    const Scene& scene = engine.scene();
    std::vector<std::uint32_t> faces, faceObject;
    const std::vector<std::uint32_t> first = engine.bodyFirstNodes();
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
        for (const auto& f : scene.bodies[b].faces) {
            for (int k = 0; k < 3; ++k) faces.push_back(first[b] + f[k]);
            faceObject.push_back(static_cast<std::uint32_t>(b));
        }
    std::vector<glm::vec3> x;
    for (const glm::dvec3& p : engine.readPositions()) x.emplace_back(p);
    cpu::PairRules rules;
    rules.betweenObjects = scene.effects.has(Effect::Collisions);
    rules.selfCollisions = scene.effects.has(Effect::SelfCollisions);
    const std::vector<cpu::FacePair> candidates =
        cpu::twinCandidates(faces, faceObject, x, scene.collision.thickness, rules);
    return cpu::twinIntersections(faces, x, candidates).size();
}

/// The most a frame of `substeps` substeps may raise the total energy: the guard compares float
/// sums off by at most the resolution at each end and lets a substep rise by the sum of both
/// (energy_guard.comp); the CPU's double sums of the same states differ from the GPU's by at most
/// the same amount again, plus the contacts the float evaluation may count differently at either
/// end (EnergyReport::contactAmbiguity); and each substep of the frame may keep its allowance.
double allowedRise(const EnergyReport& start, const EnergyReport& end, int substeps) {
    return 2.0 * substeps * (start.resolution + end.resolution) + start.contactAmbiguity +
           end.contactAmbiguity;
}

/// Checks the frame just stepped: its energy did not rise, and the guard's own GPU sum of the end
/// state agrees with the CPU's within the resolution of both. Returns the end's report.
EnergyReport expectNoEnergyGain(const Engine& engine, const EnergyReport& start, int frame) {
    const EnergyReport end = engine.energy();
    const CollisionStats& c = engine.lastStep().collision;
    EXPECT_TRUE(c.energyGuard);
    EXPECT_LE(end.total(), start.total() + allowedRise(start, end, engine.substepInfo().substeps))
        << "frame " << frame << ": kinetic " << end.kinetic << " potential " << end.potential << " contact "
        << end.contact << " (start " << start.total() << "); guard acted in " << c.energyGuardSubsteps
        << " substeps, pulled back " << c.energyGuardPulledBack << ", unremoved " << c.energyGuardUnremoved;
    const double contactTolerance = 2.0 * end.resolution + end.contactAmbiguity;
    EXPECT_NEAR(c.energyGuardTotal, end.total(), contactTolerance)
        << "frame " << frame << ": the guard's kinetic " << c.energyGuardKinetic << " penalty "
        << c.energyGuardContact << ", the CPU's kinetic " << end.kinetic << " penalty " << end.contact
        << " (of which ambiguous " << end.contactAmbiguity << ")";
    // Each part's terms are among the total's, so each part is within the same resolution.
    EXPECT_NEAR(c.energyGuardKinetic, end.kinetic, 2.0 * end.resolution) << "frame " << frame;
    EXPECT_NEAR(c.energyGuardContact, end.contact, contactTolerance) << "frame " << frame;
    EXPECT_EQ(c.energyGuardUnremoved, 0.0) << "frame " << frame;
    return end;
}

/// What a run of frames showed the safe step and the contacts do, each frame checked for energy gain.
struct FramesRun {
    std::uint32_t cutSubsteps = 0; ///< substeps the safe step cut
    std::uint32_t maxContacts = 0; ///< the most contacts of a frame's last substep
};

FramesRun runFramesWithoutEnergyGain(Engine& engine, int frames) {
    FramesRun run;
    EnergyReport last = engine.energy();
    for (int frame = 1; frame <= frames; ++frame) {
        engine.step();
        last = expectNoEnergyGain(engine, last, frame);
        run.cutSubsteps += engine.lastStep().collision.safeStepSubsteps;
        run.maxContacts = std::max(run.maxContacts, engine.lastStep().collision.contacts);
    }
    return run;
}

std::string pinnedBorder(int n) {
    std::ostringstream s;
    s << "[";
    bool firstIndex = true;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            if (i == 0 || j == 0 || i == n - 1 || j == n - 1) {
                s << (firstIndex ? "" : ", ") << i * n + j;
                firstIndex = false;
            }
    s << "]";
    return s.str();
}

// A 6 cm ball at `speed` (m/s, downwards) onto a cloth pinned along its border, implicit Euler at
// one substep per frame, for `frames` frames: no face pair ever intersects, no frame gains energy,
// nothing freezes, the safe step acts, and the ball's centre stays above the cloth's lowest node.
void expectTheBallStaysAboveThePinnedCloth(int speed, int frames) {
    const std::string json =
        R"({"format_version": 1, "name": "fast ball on pinned cloth", "effects": ["gravity", "springs", "collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1},
      "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 1000, "response": "intersection_free"},
      "objects": [
        {"name": "cloth", "generator": {"type": "cloth", "size": [0.6, 0.6], "resolution": [12, 12]},
         "transform": {"rotate_deg": [90, 0, 0]}, "mass": 0.1, "springs": {"stiffness": 300},
         "pinned": )" +
        pinnedBorder(12) + R"(},
        {"name": "ball", "generator": {"type": "sphere", "radius": 0.06, "subdivisions": 2}, "mass": 0.2,
         "springs": {"stiffness": 500}, "transform": {"translate": [0.013, 0.2, 0.007]}, "velocity": [0, -)" +
        std::to_string(speed) + R"(, 0]}]})";
    Engine engine(parseScene(json, ".", "fast ball"));
    ASSERT_EQ(exactIntersectingPairs(engine), 0u);
    const std::uint32_t ballFirst = engine.bodyFirstNodes()[1];
    std::uint32_t cutSubsteps = 0;
    EnergyReport energy = engine.energy();
    for (int frame = 1; frame <= frames; ++frame) {
        engine.step();
        energy = expectNoEnergyGain(engine, energy, frame);
        const CollisionStats& c = engine.lastStep().collision;
        ASSERT_EQ(c.maxIntersectingPairs, 0u) << "frame " << frame;
        EXPECT_EQ(c.safeStepFrozeAll, 0u) << "frame " << frame;
        cutSubsteps += c.safeStepSubsteps;
        // The ball's centre stays above the cloth's lowest node: it did not pass through.
        const std::vector<glm::dvec3> x = engine.readPositions();
        double clothLowest = 1e9, ballCentre = 0.0;
        for (std::uint32_t i = 0; i < ballFirst; ++i) clothLowest = std::min(clothLowest, x[i].y);
        for (std::size_t i = ballFirst; i < x.size(); ++i) ballCentre += x[i].y;
        ballCentre /= static_cast<double>(x.size() - ballFirst);
        EXPECT_GT(ballCentre, clothLowest) << "frame " << frame;
    }
    EXPECT_GT(cutSubsteps, 0u) << "the impact needs the safe step: the test must exercise it";
    EXPECT_EQ(exactIntersectingPairs(engine), 0u);
}

// The issue's fast ball: 12 m/s. Discrete detection lets it through (ContinuousEngineGl).
TEST(IntersectionFreeGl, AFastBallStaysAboveAPinnedCloth) {
    expectTheBallStaysAboveThePinnedCloth(12, 20);
}

// At 1,000 m/s the ball crosses the 0.2 m to the cloth in a fifth of a millisecond and would move
// 16.7 m in the substep: the CCD must see the whole sweep and the safe step stop it at the cloth.
TEST(IntersectionFreeGl, ABallAtAThousandMetresPerSecondStaysAboveAPinnedCloth) {
    expectTheBallStaysAboveThePinnedCloth(1000, 10);
}

// Steps `frames` frames of a scene that starts intersecting: the intersection is reported in frame 1,
// nothing freezes, and once a frame ends intersection-free no later substep intersects again.
struct RecoveryRun {
    bool free = false;             ///< the last frame reached an intersection-free start
    std::uint32_t backToStart = 0; ///< substeps the energy guard pulled back to their start
};
RecoveryRun runFromAnIntersectingStart(Engine& engine, int frames) {
    RecoveryRun run;
    for (int frame = 1; frame <= frames; ++frame) {
        engine.step();
        const CollisionStats& c = engine.lastStep().collision;
        EXPECT_EQ(c.safeStepFrozeAll, 0u) << "frame " << frame;
        if (frame == 1) {
            EXPECT_GT(c.maxIntersectingPairs, 0u) << "reported";
        }
        if (run.free) {
            EXPECT_EQ(c.maxIntersectingPairs, 0u) << "frame " << frame << ": intersecting again";
        }
        run.free = c.reachedIntersectionFree;
        run.backToStart += c.energyGuardBackToStart;
    }
    return run;
}

// Recovery from intersecting input (issue 23, item 5): two tet boxes that overlap by 4 mm (within
// the thickness) at the start. The scene is simulated, not refused; the intersecting pairs are
// reported; the CCD leaves their regions out (nothing freezes) and the response pushes them apart;
// once a substep starts intersection-free, every later one does too.
TEST(IntersectionFreeGl, AnIntersectingStartIsPushedApart) {
    const std::string json =
        R"({"format_version": 1, "name": "tangled", "effects": ["springs", "collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1},
      "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 500, "response": "intersection_free"},
      "objects": [
        {"name": "a", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]},
         "mass": 0.2, "springs": {"stiffness": 400}},
        {"name": "b", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]},
         "transform": {"translate": [0.096, 0.02, 0.01]}, "mass": 0.2, "springs": {"stiffness": 400}}]})";
    Engine engine(parseScene(json, ".", "tangled"));
    ASSERT_GT(exactIntersectingPairs(engine), 0u) << "the start must intersect";
    EXPECT_TRUE(runFromAnIntersectingStart(engine, 20).free);
    EXPECT_GT(engine.lastStep().collision.substepsUntilIntersectionFree, 0u);
    EXPECT_EQ(exactIntersectingPairs(engine), 0u);
}

// Two sheets laid in one plane (decision 0024, "Coplanar input"): the same cloth twice (every node on
// a node of the other) and the second shifted 0.1 mm within their plane. Every vertex lies in the
// other sheet's plane, so no vertex had a side to keep: before, no contact pushed them (the
// coincident sheets fell through the whole run with 1,060 intersecting pairs; the shifted ones froze,
// every substep pulled back to its start by the energy guard). The side rule for such vertices parts
// them: intersection-free within a few substeps, never intersecting again, falling under gravity (not
// frozen), and free by the exact CPU oracle at the end.
TEST(IntersectionFreeGl, SheetsLaidInOnePlaneArePushedApart) {
    for (const char* height : {"0.3", "0.3001"}) {
        SCOPED_TRACE(std::string("second sheet's centre at y = ") + height + " m (the first's: 0.3 m)");
        const std::string json =
            std::string(
                R"({"format_version": 1, "name": "sheets in one plane", "effects": ["gravity", "springs", "collisions"],
          "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1},
          "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 1000, "response": "intersection_free"},
          "objects": [
            {"name": "a", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [8, 8]},
             "transform": {"translate": [0, 0.3, 0]}, "mass": 0.05, "springs": {"stiffness": 300}},
            {"name": "b", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [8, 8]},
             "transform": {"translate": [0, )") +
            height + R"(, 0]}, "mass": 0.05, "springs": {"stiffness": 300}}]})";
        // The cloth generator lies in the xy plane: both sheets are vertical, at z = 0, and the
        // shift (along y) keeps them in that plane.
        Engine engine(parseScene(json, ".", "sheets in one plane"));
        ASSERT_GT(exactIntersectingPairs(engine), 0u) << "the start must intersect";
        const auto centreHeight = [&engine] {
            double y = 0.0;
            const std::vector<glm::dvec3> x = engine.readPositions();
            for (const glm::dvec3& p : x) y += p.y;
            return y / static_cast<double>(x.size());
        };
        const double startHeight = centreHeight();
        const RecoveryRun run = runFromAnIntersectingStart(engine, 12);
        EXPECT_TRUE(run.free);
        EXPECT_LE(engine.lastStep().collision.substepsUntilIntersectionFree, 4u);
        EXPECT_EQ(exactIntersectingPairs(engine), 0u);
        EXPECT_LE(run.backToStart, 1u)
            << "the recovery's first substep may return to its start, no later one";
        // Free fall for 0.2 s would be 0.196 m; the sheets, parted and falling, must have dropped
        // most of that (frozen, they dropped nothing).
        EXPECT_LT(centreHeight(), startHeight - 0.1);
    }
}

// Steps `frames` frames checking that no frame gains energy; counts the substeps in which the
// energy guard acted after frame `restFrom` (the bodies should be at rest by then).
struct RestingRun {
    std::uint32_t guardActionsAtRest = 0;
    EnergyReport end;
};
RestingRun runToRest(Engine& engine, int frames, int restFrom) {
    RestingRun run;
    run.end = engine.energy();
    for (int frame = 1; frame <= frames; ++frame) {
        engine.step();
        run.end = expectNoEnergyGain(engine, run.end, frame);
        if (frame > restFrom) run.guardActionsAtRest += engine.lastStep().collision.energyGuardSubsteps;
    }
    return run;
}

// Restitution is for impacts, not for resting contact (decision 0024): a tet box landing on a
// bouncy ground (e = 0.5) under implicit Euler at one substep per frame bounces, then rests; once
// at rest the energy guard has nothing to take out. The band's response acts before the solve, on
// a resting node's velocity of about 0 (after the solve, reflecting the few mm/s that gravity adds
// raised the energy of resting piles every substep), and its friction is bounded by the solve's
// ground penalty too (without it the box, not approaching the ground, slid on forever).
TEST(IntersectionFreeGl, RestingOnABouncyGroundNeedsNoGuard) {
    const std::string json =
        R"({"format_version": 1, "name": "box on bouncy ground", "effects": ["gravity", "springs", "ground", "collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1},
      "ground": {"height": 0.0, "restitution": 0.5, "friction": 0.5},
      "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 2000, "response": "intersection_free"},
      "objects": [
        {"name": "box", "generator": {"type": "tet_box", "size": [0.1, 0.1, 0.1], "resolution": [2, 2, 2]},
         "transform": {"translate": [0, 0.07, 0]}, "mass": 0.5, "springs": {"stiffness": 300}}]})";
    Engine engine(parseScene(json, ".", "bouncy ground"));
    const RestingRun run = runToRest(engine, 120, 60);
    EXPECT_EQ(run.guardActionsAtRest, 0u) << "the guard acted in the last 60 frames, with the boxes at rest";
    EXPECT_LT(run.end.kinetic, 1e-6) << "at rest after 2 s";
}

// Under implicit Euler nothing may change the velocity after the solve (decision 0024, "Velocity
// filters before the solve"): the ground's velocity response applied to the solved velocity of a
// box resting in the ground's band (its downward part removed at the bottom nodes only) left a
// velocity that no longer solved the system, and the box's springs gained energy in every
// substep: this box, resting after its drop, had the guard act in every substep from frame 9 on
// (156 of 180), pulling the step back each time. With the filters on the start velocity, before
// the solve, the solve's own dissipation holds it: the guard has nothing to take out at rest.
TEST(IntersectionFreeGl, ABoxRestingUnderImplicitEulerNeedsNoGuard) {
    const std::string json =
        R"({"format_version": 1, "name": "box at rest", "effects": ["gravity", "springs", "damping", "ground", "collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 2},
      "damping": 0.1,
      "ground": {"height": 0.0, "restitution": 0.0, "friction": 0.5},
      "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 1000, "response": "intersection_free"},
      "objects": [
        {"name": "box", "generator": {"type": "tet_box", "size": [0.3, 0.3, 0.3], "resolution": [3, 3, 3]},
         "transform": {"translate": [0, 0.2, 0], "rotate_deg": [0, 10, 0]}, "mass": 0.5,
         "springs": {"stiffness": 2000, "damping": 0.01}}]})";
    Engine engine(parseScene(json, ".", "box at rest"));
    const RestingRun run = runToRest(engine, 60, 20);
    EXPECT_EQ(run.guardActionsAtRest, 0u)
        << "the guard acted in frames 21-60, with the box at rest on the ground";
    EXPECT_LT(run.end.kinetic, 1e-4) << "at rest after 1 s";
}

// The frame's `contacts` are the implicit solve's (its records). Two boxes side by side, half the
// thickness apart, nothing pulling them together and no friction: the penalty holds them apart,
// so the velocity filter before the solve acts on no contact — it counted only those it acts on,
// and reported 0 while the contact energy was positive.
TEST(IntersectionFreeGl, ContactsAtRestAreCountedWithoutFriction) {
    const std::string json =
        R"({"format_version": 1, "name": "boxes side by side", "effects": ["springs", "collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 2},
      "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 1000, "friction": 0.0,
                    "response": "intersection_free"},
      "objects": [
        {"name": "left", "generator": {"type": "tet_box", "size": [0.3, 0.3, 0.3], "resolution": [2, 2, 2]},
         "transform": {"translate": [0, 0.2, 0]}, "mass": 0.5, "springs": {"stiffness": 2000}},
        {"name": "right", "generator": {"type": "tet_box", "size": [0.3, 0.3, 0.3], "resolution": [2, 2, 2]},
         "transform": {"translate": [0.305, 0.2, 0]}, "mass": 0.5, "springs": {"stiffness": 2000}}]})";
    Engine engine(parseScene(json, ".", "boxes side by side"));
    for (int frame = 1; frame <= 5; ++frame) {
        engine.step();
        const std::uint32_t contacts = engine.lastStep().collision.contacts;
        if (engine.energy().contact > 0.0) {
            EXPECT_GT(contacts, 0u) << "frame " << frame << ": contact energy " << engine.energy().contact;
        }
        if (frame == 1) {
            EXPECT_GT(engine.energy().contact, 0.0) << "the boxes start within the thickness";
        }
    }
}

// Every feature pair that the CCD may stop a step at is a contact the response acts on (decision
// 0018, addendum "Orphans"): a sleeve (1,216 faces) hung from its top ring and spun at 40 rad/s
// twists and wraps onto itself; before, the pairs whose owner faces share a node were the CCD's
// only, nothing pushed them apart, and from frame 9 on the safe step cut every node's step in every
// substep — the twisted sleeve froze in mid-air (kinetic energy 0, 44 of 60 substeps cut). Now the
// response pushes those pairs apart like any other: the cut acts in under 5 % of substeps.
TEST(IntersectionFreeGl, ATwistedSleeveIsNotFrozenByPairsThatNothingPushesApart) {
    const std::string json =
        R"({"format_version": 1, "name": "twisted sleeve", "effects": ["gravity", "springs", "self_collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 2},
      "collision": {"broad_phase": "bvh", "thickness": 0.004, "stiffness": 500, "response": "intersection_free"},
      "objects": [
        {"name": "sleeve", "generator": {"type": "tube", "radius": 0.08, "length": 0.5, "resolution": [32, 20]},
         "transform": {"translate": [0, 0.5, 0]}, "mass": 0.05, "springs": {"stiffness": 40, "bend_stiffness": 0.2},
         "angular_velocity": [0, 40, 0],
         "pinned": {"inside": {"min": [-0.1, 0.749, -0.1], "max": [0.1, 0.751, 0.1]}}}]})";
    Engine engine(parseScene(json, ".", "twisted sleeve"));
    const int frames = 30;
    const FramesRun run = runFramesWithoutEnergyGain(engine, frames);
    EXPECT_GT(run.maxContacts, 20u) << "the sleeve must wrap onto itself, or the test shows nothing";
    EXPECT_LE(run.cutSubsteps, static_cast<std::uint32_t>(2 * frames / 20))
        << "safe-step cuts in " << 2 * frames << " substeps";
    EXPECT_EQ(exactIntersectingPairs(engine), 0u);
}

// Approaching pairs within the margin enter the solve (decision 0024, "Approaching pairs in the
// solve"). A very soft tet ball (320 surface faces, 1 N/m springs, 500 N/m contacts on 0.3 g
// nodes: k·h²/m ≈ 500) thrown onto the ground squashes and comes to rest on itself. Each step from
// rest moves its nodes by g·h² = 2.7 mm, half the 5 mm thickness, into pairs that had no force
// where the solve was linearised; their penalty then raised the energy and the guard pulled the
// step back, in the end all the way to the start at rest: with time.solver.contact_margin 0 (as
// before, and the default) 25 of these 40 substeps went back to their start (llvmpipe), the ball
// frozen. With the approaching pairs of a margin of one thickness in the solve none does; every
// frame keeps the promises.
TEST(IntersectionFreeGl, ASoftBallComingToRestIsNotPulledBackToItsStart) {
    const std::string json =
        R"({"format_version": 1, "name": "soft ball", "effects": ["gravity", "springs", "ground", "self_collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1,
               "solver": {"contact_margin": 1}},
      "ground": {"height": 0.0, "friction": 0.5},
      "collision": {"broad_phase": "bvh", "response": "intersection_free", "thickness": 0.005, "stiffness": 500},
      "objects": [
        {"name": "ball", "generator": {"type": "sphere", "radius": 0.15, "subdivisions": 2},
         "transform": {"translate": [0, 0.2, 0]}, "mass": 0.1, "springs": {"stiffness": 1},
         "velocity": [0.5, -6, 0]}]})";
    Engine engine(parseScene(json, ".", "soft ball"));
    const int frames = 40;
    std::uint32_t backToStart = 0;
    EnergyReport last = engine.energy();
    for (int frame = 1; frame <= frames; ++frame) {
        engine.step();
        last = expectNoEnergyGain(engine, last, frame);
        backToStart += engine.lastStep().collision.energyGuardBackToStart;
        EXPECT_EQ(engine.lastStep().collision.maxIntersectingPairs, 0u) << "frame " << frame;
    }
    EXPECT_EQ(backToStart, 0u) << "substeps pulled back to their start at rest";
    EXPECT_LT(last.potential, 0.1 * 9.81 * 0.15) << "the ball came down";
    EXPECT_EQ(exactIntersectingPairs(engine), 0u);
}

// A pile under symplectic Euler is held by its contacts, not frozen by the safe step (decision
// 0024, "Response iterations"). Under symplectic Euler Bridson's velocity response, iterated, is
// the contacts' only support; each iteration moves a node by the average of its contacts'
// corrections. With 4 iterations the soak pile's balls (scenes/soak_pile.json under this response)
// kept sinking into each other at 0.8 m/s inside the thickness until the safe step cut them, their
// gap halved each substep to 5 µm, below what the CCD can refute, and three of the four balls
// stayed frozen in mid-air from frame 22 on: the cut acted in every substep. The bound, the
// issue's 5 % for a fail-safe: the automatic 8 iterations cut none of these substeps on llvmpipe.
TEST(IntersectionFreeGl, APileUnderSymplecticEulerIsHeldByItsContactsNotFrozen) {
    const std::string ball =
        R"("generator": {"type": "sphere", "radius": 0.15, "subdivisions": 1}, "mass": 0.5,
         "springs": {"stiffness": 300, "damping": 0.01})";
    const std::string json =
        R"({"format_version": 1, "name": "pile", "effects": ["gravity", "springs", "damping", "ground", "collisions"],
      "time": {"dt": 0.016666666666666666, "substeps": "auto"}, "damping": 0.2,
      "ground": {"height": 0.0, "restitution": 0.2, "friction": 0.5},
      "collision": {"response": "intersection_free", "thickness": 0.01, "stiffness": 2000},
      "objects": [
        {"name": "a", "transform": {"translate": [0, 0.2, 0]}, )" +
        ball + R"(},
        {"name": "b", "transform": {"translate": [0.12, 0.55, 0.05]}, )" +
        ball + R"(},
        {"name": "c", "transform": {"translate": [-0.1, 0.9, -0.06]}, )" +
        ball + R"(},
        {"name": "d", "transform": {"translate": [0.02, 1.25, 0.1]}, )" +
        ball + R"(}]})";
    Engine engine(parseScene(json, ".", "pile"));
    const int frames = 45;
    const FramesRun run = runFramesWithoutEnergyGain(engine, frames);
    const std::uint32_t substeps = static_cast<std::uint32_t>(frames * engine.substepInfo().substeps);
    EXPECT_GT(run.maxContacts, 10u) << "the balls must land on each other, or the test shows nothing";
    EXPECT_LE(run.cutSubsteps, substeps / 20) << "safe-step cuts in " << substeps << " substeps";
    EXPECT_EQ(exactIntersectingPairs(engine), 0u);
}

// The same scene runs the same twice (decision 0024, "Energy guard": deterministic). The feature
// pair lists are appended by many invocations, so their order changes from run to run; the guard
// summed the contacts' energy in list order in float, and its decision, near its threshold, then
// depended on that order: two runs of the crumpled cloth under implicit Euler at one substep per
// frame parted at frame 10 in one of three tries, and the guard's contact sums differed in their
// last bits far more often. Now those terms are summed exactly: every frame's guard sums and
// positions must be bit-identical between two runs.
/// A cloth dropped onto the ground that crumples onto itself (implicit Euler, 1 substep per frame);
/// `solver`: the members of time.solver, e.g. `"newton_steps": 4` (empty: the defaults).
Scene crumplingCloth(const std::string& solver = "") {
    const std::string json =
        R"({"format_version": 1, "name": "crumpling cloth", "effects": ["gravity", "springs", "damping", "ground", "self_collisions"],
      "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 1, "solver": {)" +
        solver + R"(}},
      "damping": 0.05,
      "ground": {"height": 0.0, "restitution": 0.0, "friction": 0.8},
      "collision": {"broad_phase": "bvh", "response": "intersection_free", "thickness": 0.02, "stiffness": 100},
      "objects": [
        {"name": "cloth", "generator": {"type": "cloth", "size": [0.5, 0.5], "resolution": [16, 16]},
         "transform": {"translate": [0, 0.28, 0], "rotate_deg": [10, 0, 3]}, "mass": 0.1,
         "springs": {"stiffness": 60, "damping": 0.002, "shear_stiffness": 20, "bend_stiffness": 0.2}}]})";
    return parseScene(json, ".", "crumpling cloth");
}

TEST(IntersectionFreeGl, TheSameSceneRunsTheSameTwice) {
    const Scene scene = crumplingCloth();
    Engine first(scene), second(scene);
    std::uint32_t framesWithContactEnergy = 0;
    for (int frame = 1; frame <= 30; ++frame) {
        first.step();
        second.step();
        const CollisionStats &a = first.lastStep().collision, &b = second.lastStep().collision;
        ASSERT_EQ(a.energyGuardTotal, b.energyGuardTotal) << "frame " << frame;
        ASSERT_EQ(a.energyGuardContact, b.energyGuardContact) << "frame " << frame;
        ASSERT_EQ(a.energyGuardSubsteps, b.energyGuardSubsteps) << "frame " << frame;
        ASSERT_EQ(first.readPositions(), second.readPositions()) << "frame " << frame;
        if (a.energyGuardContact > 0.0) ++framesWithContactEnergy;
    }
    EXPECT_GT(framesWithContactEnergy, 10u)
        << "the cloth must lie in contact with itself: the sums must have terms";
}

// Newton steps until converged (time.solver.newton_tolerance; decision 0024): a step after the
// second is taken only while the last moved some node by more than the tolerance's part of the
// thickness. Checked against the engine with every step taken or with only two: a substep whose
// further steps were all skipped must end exactly where two steps end it (the skipped stages change
// no buffer), every planned step is either taken (line-searched) or counted as skipped, and at the
// default tolerance the crumpling cloth both takes third steps and skips them.
TEST(IntersectionFreeGl, NewtonStepsAfterConvergenceAreSkippedAndChangeNothing) {
    const auto withSteps = [](int newtonSteps, double tolerance) {
        std::ostringstream solver;
        solver << R"("newton_steps": )" << newtonSteps << R"(, "newton_tolerance": )" << tolerance;
        return crumplingCloth(solver.str());
    };
    // Two steps against up to four that stop once a step moved no node by the whole thickness.
    Engine two(withSteps(2, 0.25)), upToFour(withSteps(4, 1.0)), adaptive(withSteps(4, 0.25));
    int identicalFrames = 0;
    bool diverged = false;
    std::uint32_t taken = 0, skipped = 0;
    for (int frame = 1; frame <= 30; ++frame) {
        two.step();
        upToFour.step();
        adaptive.step();
        for (const Engine* e : {&upToFour, &adaptive}) {
            const SolverStats& s = e->lastStep().solver;
            const auto substeps = static_cast<std::uint32_t>(e->lastStep().substeps);
            // The cloth never starts a substep intersecting, so no step is skipped for recovery.
            ASSERT_EQ(e->lastStep().collision.maxIntersectingPairs, 0u) << "frame " << frame;
            EXPECT_EQ(s.lineSearchSteps + s.newtonStepsSkipped, 3u * substeps) << "frame " << frame;
            EXPECT_GE(s.lineSearchSteps, substeps)
                << "frame " << frame << ": the second step is always taken";
        }
        diverged = diverged || upToFour.lastStep().solver.lineSearchSteps > 1u; // one substep per frame
        if (!diverged) {
            ASSERT_EQ(upToFour.readPositions(), two.readPositions()) << "frame " << frame;
            ++identicalFrames;
        }
        taken += adaptive.lastStep().solver.lineSearchSteps - 1u; // steps after the second
        skipped += adaptive.lastStep().solver.newtonStepsSkipped;
    }
    EXPECT_GE(identicalFrames, 10) << "the comparison must cover frames with contact";
    EXPECT_GT(taken, 0u) << "some second steps moved a node by more than a quarter of the thickness";
    EXPECT_GT(skipped, 0u) << "and some did not";
}

// Randomised drops: small tet boxes and a cloth thrown at each other fast (6 m/s), onto the
// ground, under symplectic Euler at its automatic substeps and implicit Euler at one substep per
// frame. Every substep starts intersection-free (the engine's exact TriTri) and so does the end
// (the CPU oracle). `self`: with self_collisions too (continuous
// detection's expansion gives the CCD the feature pairs that Representative-Triangle ownership
// alone misses, decision 0018 addendum).
// `newtonSteps` (implicit only): time.solver.newton_steps.
Scene randomDrop(unsigned seed, bool implicit, bool self = false, int newtonSteps = 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> offset(-0.05, 0.05), speed(-6.0, 6.0);
    std::ostringstream s;
    s << R"({"format_version": 1, "name": "random drop", "effects": ["gravity", "springs", "ground", "collisions")"
      << (self ? R"(, "self_collisions")" : "") << R"(],
      "time": {"dt": 0.016666666666666666, )"
      << (implicit ? R"("integrator": "implicit_euler", "substeps": 1, "solver": {"newton_steps": )" +
                         std::to_string(newtonSteps) + "}"
                   : std::string(R"("substeps": "auto")"))
      << R"(},
      "ground": {"height": 0.0},
      "collision": {"broad_phase": "bvh", "thickness": 0.01, "stiffness": 500, "response": "intersection_free"},
      "objects": [
        {"name": "cloth", "generator": {"type": "cloth", "size": [0.3, 0.3], "resolution": [7, 7]},
         "transform": {"translate": [0, 0.1, 0], "rotate_deg": [90, 0, 0]}, "mass": 0.05, "springs": {"stiffness": 100}})";
    for (int b = 0; b < 3; ++b) {
        s << R"(,
        {"name": "box)"
          << b << R"(", "generator": {"type": "tet_box", "size": [0.06, 0.06, 0.06], "resolution": [1, 1, 1]},
         "transform": {"translate": [)"
          << offset(rng) << ", " << 0.2 + 0.1 * b << ", " << offset(rng) << R"(]}, "velocity": [)"
          << speed(rng) << ", " << -std::abs(speed(rng)) << ", " << speed(rng)
          << R"(], "mass": 0.1, "springs": {"stiffness": 400}})";
    }
    s << "]}";
    return parseScene(s.str(), ".", "random drop " + std::to_string(seed));
}

// (seed, implicit Euler, self_collisions)
class IntersectionFreeDrops : public ::testing::TestWithParam<std::tuple<unsigned, bool, bool>> {};

// 12 frames of a drop: every substep starts intersection-free, the end is free (CPU oracle), and no
// frame gains energy beyond the guard's float allowance.
void expectDropKeepsThePromises(const Scene& scene) {
    Engine engine(scene);
    ASSERT_EQ(exactIntersectingPairs(engine), 0u);
    EnergyReport energy = engine.energy();
    for (int frame = 1; frame <= 12; ++frame) {
        engine.step();
        ASSERT_EQ(engine.lastStep().collision.maxIntersectingPairs, 0u) << "frame " << frame;
        energy = expectNoEnergyGain(engine, energy, frame);
    }
    EXPECT_EQ(exactIntersectingPairs(engine), 0u);
}

TEST_P(IntersectionFreeDrops, NoFacePairEverIntersectsAndNoEnergyIsGained) {
    const auto [seed, implicit, self] = GetParam();
    expectDropKeepsThePromises(randomDrop(seed, implicit, self));
}

// Seeds 13 and 17 (found among seeds 1–160) end their first implicit frame with a contact that the
// float shader and the double twin assign differently at a closest-feature boundary (seed 13: a
// cloth edge parallel to a box edge within the thickness, counted by the GPU as an edge-edge contact
// and left by the twin to the vertex-face pair): EnergyReport::contactAmbiguity must cover it.
INSTANTIATE_TEST_SUITE_P(Seeds, IntersectionFreeDrops,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 13u, 17u),
                                            ::testing::Bool(), ::testing::Bool()));

// The same drops with two Newton steps per substep (time.solver.newton_steps), and with up to four
// that stop once converged (time.solver.newton_tolerance at its default): the promises are the
// same, and the Newton step's detection and solve run in every substep (its contacts at x1).
class IntersectionFreeNewtonDrops : public ::testing::TestWithParam<std::tuple<unsigned, bool, int>> {};

TEST_P(IntersectionFreeNewtonDrops, NoFacePairEverIntersectsAndNoEnergyIsGained) {
    const auto [seed, self, newtonSteps] = GetParam();
    expectDropKeepsThePromises(randomDrop(seed, true, self, newtonSteps));
}

INSTANTIATE_TEST_SUITE_P(Seeds, IntersectionFreeNewtonDrops,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u, 4u), ::testing::Bool(),
                                            ::testing::Values(2, 4)));

} // namespace
} // namespace glcollide
