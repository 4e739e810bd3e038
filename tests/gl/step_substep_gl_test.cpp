// Engine::stepSubstep (issue 25: the viewer's "one substep"): a frame's substeps taken one call at a
// time give the state one step() gives, bit for bit (the same dispatches in the same order), for a
// symplectic scene with the velocity-level response and an implicit one with the
// intersection-free response, its energy guard and radial culling; the frame's bookkeeping
// (frame, time, substepInFrame) follows the calls; FrameStep refuses.

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace glcollide {
namespace {

// Two cloths 5 mm apart, the upper one falling onto the lower, pinned one: symplectic Euler with
// the velocity-level (Bridson) response, 4 substeps per frame.
const char* kSymplectic = R"({"format_version": 1, "name": "two cloths", "effects":
    ["gravity", "springs", "damping", "collisions", "self_collisions"],
  "time": {"dt": 0.01, "substeps": 4},
  "damping": 0.05,
  "collision": {"broad_phase": "bvh", "response": "bridson", "thickness": 0.01, "stiffness": 100},
  "objects": [
    {"name": "below", "generator": {"type": "cloth", "size": [0.4, 0.4], "resolution": [6, 6]},
     "mass": 0.2, "springs": {"stiffness": 200}, "pinned": [0, 1, 2]},
    {"name": "above", "generator": {"type": "cloth", "size": [0.3, 0.3], "resolution": [5, 5]},
     "transform": {"translate": [0.02, 0.005, 0.01]}, "velocity": [0, -0.5, 0],
     "mass": 0.1, "springs": {"stiffness": 200}}]})";

// A sphere thrown at the ground: implicit Euler, the intersection-free response (safe step,
// energy guard, Newton steps) and radial culling, 3 substeps per frame.
const char* kImplicit = R"({"format_version": 1, "name": "ball", "effects":
    ["gravity", "springs", "ground", "self_collisions"],
  "time": {"dt": 0.016666666666666666, "integrator": "implicit_euler", "substeps": 3},
  "ground": {"height": 0.0},
  "collision": {"broad_phase": "bvh", "thickness": 0.005, "stiffness": 500, "response": "intersection_free",
                "culling": "radial"},
  "objects": [
    {"name": "ball", "generator": {"type": "sphere", "radius": 0.15, "subdivisions": 2},
     "transform": {"translate": [0, 0.17, 0]}, "mass": 0.1, "springs": {"stiffness": 300},
     "velocity": [0.5, -1.0, 0]}]})";

/// `frames` frames with step() on one engine and with single substeps on another: after every
/// frame the positions and velocities are equal (no tolerance: the same float arithmetic).
void expectSubstepsMakeTheFrame(const char* json, int frames) {
    const Scene scene = parseScene(json, ".", "substep test");
    Engine whole(scene, {false}), single(scene, {false});
    const int substeps = single.substepInfo().substeps;
    ASSERT_GT(substeps, 1);
    const double h = single.substepInfo().substepLength;
    std::uint32_t contacts = 0;
    for (int frame = 1; frame <= frames; ++frame) {
        whole.step();
        for (int s = 1; s <= substeps; ++s) {
            single.stepSubstep();
            const StepStats& st = single.lastStep();
            if (s < substeps) {
                EXPECT_EQ(st.frame, static_cast<std::uint64_t>(frame - 1));
                EXPECT_EQ(st.substepInFrame, s);
                // The same expression as the engine's: frame·dt + s·h, no tolerance needed.
                EXPECT_EQ(st.time, static_cast<double>(frame - 1) * scene.time.dt + s * h);
            } else {
                EXPECT_EQ(st.frame, static_cast<std::uint64_t>(frame));
                EXPECT_EQ(st.substepInFrame, 0);
                EXPECT_EQ(st.time, whole.lastStep().time);
            }
        }
        ASSERT_EQ(single.readPositions(), whole.readPositions()) << "frame " << frame;
        ASSERT_EQ(single.readVelocities(), whole.readVelocities()) << "frame " << frame;
        // The frame's statistics are the frame's, however it was stepped.
        EXPECT_EQ(single.lastStep().collision.candidatePairs, whole.lastStep().collision.candidatePairs);
        EXPECT_EQ(single.lastStep().collision.contacts, whole.lastStep().collision.contacts);
        EXPECT_EQ(single.lastStep().collision.energyGuardSubsteps,
                  whole.lastStep().collision.energyGuardSubsteps);
        EXPECT_EQ(single.lastStep().solver.totalIterations, whole.lastStep().solver.totalIterations);
        // Radial culling's check that the host moved no node dispatches at every call, once per
        // frame in step(): more dispatches, the same state.
        if (scene.collision.culling == Culling::Radial) {
            EXPECT_GT(single.lastStep().dispatchesPerSubstep, whole.lastStep().dispatchesPerSubstep);
        } else {
            EXPECT_EQ(single.lastStep().dispatchesPerSubstep, whole.lastStep().dispatchesPerSubstep);
        }
        contacts += whole.lastStep().collision.candidatePairs;
    }
    EXPECT_GT(contacts, 0u) << "the scene never came near a collision: the test would not test it";
}

TEST(StepSubstepGl, SubstepsOfASymplecticFrameWithCollisionsAreItsStep) {
    expectSubstepsMakeTheFrame(kSymplectic, 6);
}

TEST(StepSubstepGl, SubstepsOfAnImplicitIntersectionFreeFrameAreItsStep) {
    expectSubstepsMakeTheFrame(kImplicit, 6);
}

// step() in the middle of a frame finishes it: one substep then step() is one step().
TEST(StepSubstepGl, StepMidFrameFinishesTheFrame) {
    const Scene scene = parseScene(kSymplectic, ".", "substep test");
    Engine whole(scene, {false}), mixed(scene, {false});
    whole.step();
    mixed.stepSubstep();
    mixed.stepSubstep();
    mixed.step();
    EXPECT_EQ(mixed.lastStep().frame, 1u);
    EXPECT_EQ(mixed.lastStep().substepInFrame, 0);
    EXPECT_EQ(mixed.readPositions(), whole.readPositions());
    EXPECT_EQ(mixed.readVelocities(), whole.readVelocities());
}

TEST(StepSubstepGl, FrameStepRefusesWithAnError) {
    const Scene scene = parseScene(R"({"format_version": 1, "name": "free", "effects": ["gravity"],
      "time": {"dt": 0.01, "substeps": 4},
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [3, 3]},
                   "mass": 0.5}]})",
                                   ".", "frame step");
    EngineOptions options;
    options.gpuTiming = false;
    options.frameStep = true;
    Engine engine(scene, options);
    ASSERT_EQ(engine.pipeline(), std::vector<std::string>{"FrameStep"})
        << "the scene qualifies for FrameStep";
    try {
        engine.stepSubstep();
        FAIL() << "stepSubstep under FrameStep did not throw";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("frameStep"), std::string::npos) << e.what();
    }
    engine.step(); // the engine is still usable
    EXPECT_EQ(engine.lastStep().frame, 1u);
}

} // namespace
} // namespace glcollide
