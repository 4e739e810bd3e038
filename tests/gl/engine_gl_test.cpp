// The engine composes its passes and buffers from the scene's effects, and allocates nothing
// for an effect a scene does not list.

#include <glcollide/engine.hpp>
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace glcollide {
namespace {

using Names = std::vector<std::string>;

Scene sceneWith(const std::string& effects, const std::string& extra = "") {
    const std::string json =
        R"({"format_version": 1, "name": "t", "effects": )" + effects + "," + extra + R"(
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [4, 4]},
                   "mass": 0.1)" +
        std::string(effects.find("springs") != std::string::npos ? R"(, "springs": {"stiffness": 10})" : "") +
        "}]}";
    return parseScene(json, ".", "engine test");
}

struct Case {
    const char* effects;
    const char* extra;
    Names passes;
    Names buffers;
};

TEST(EngineGl, PassesAndBuffersFollowTheEffects) {
    const Case cases[] = {
        {R"([])", "", {"NodeUpdate"}, {"positions", "velocities", "faces"}},
        {R"(["gravity"])", "", {"NodeForce", "NodeUpdate"}, {"positions", "velocities", "faces", "forces"}},
        {R"(["springs"])",
         "",
         {"SpringUpdate", "NodeUpdate"},
         {"positions", "velocities", "faces", "forces", "springs", "nodeSpringOffsets", "nodeSpringList",
          "heavyNodes"}},
        {R"(["gravity", "springs", "damping"])",
         R"("damping": 0.1,)",
         {"SpringUpdate", "NodeUpdate"}, // SpringUpdate adds gravity and damping in its dispatch
         {"positions", "velocities", "faces", "forces", "springs", "nodeSpringOffsets", "nodeSpringList",
          "heavyNodes"}},
        {R"(["ground"])", "", {"NodeUpdate"}, {"positions", "velocities", "faces"}},
        {R"(["wind", "springs"])",
         R"("wind": {"velocity": [1, 0, 0], "drag": 1},)",
         {"SpringUpdate", "NodeUpdate"},
         {"positions", "velocities", "faces", "forces", "springs", "nodeSpringOffsets", "nodeSpringList",
          "heavyNodes", "nodeFaceOffsets", "nodeFaceList"}},
    };
    for (const Case& c : cases) {
        Engine engine(sceneWith(c.effects, c.extra), {.frameStep = false}); // the per-substep passes
        EXPECT_EQ(engine.pipeline(), c.passes) << c.effects;
        Names buffers = c.buffers;
        buffers.emplace_back("health"); // EngineOptions::checkFinite (default on)
        EXPECT_EQ(engine.allocatedBuffers(), buffers) << c.effects;
        engine.step(); // every composition runs
        EXPECT_EQ(engine.lastStep().passes.size(), c.passes.size());
    }
}

TEST(EngineGl, ImplicitEulerReplacesSpringUpdateWithTheSolver) {
    const Names solverBuffers = {"solverResidual",   "solverPreconditioned", "solverDirection0",
                                 "solverDirection1", "solverProduct",        "solverBlockInverse",
                                 "solverPartialsR",  "solverPartialsPq",     "solverState"};
    const std::string implicit = R"("time": {"integrator": "implicit_euler"},)";
    {
        Engine engine(sceneWith(R"(["gravity", "springs", "damping"])", implicit + R"("damping": 0.1,)"));
        EXPECT_EQ(engine.pipeline(), (Names{"ImplicitSolve", "NodeUpdate"}));
        Names buffers = {"positions",         "velocities",     "faces",      "springs",
                         "nodeSpringOffsets", "nodeSpringList", "heavyNodes", "health"};
        buffers.insert(buffers.end(), solverBuffers.begin(), solverBuffers.end());
        EXPECT_EQ(engine.allocatedBuffers(), buffers);
        EXPECT_EQ(engine.substepInfo().substeps, 1); // "auto" means one substep per frame
        // 104 bytes per node of vectors, plus per-group partials and 32 bytes of state.
        EXPECT_LE(engine.solverBytes(), 128u * engine.nodeCount());
        engine.step();
        EXPECT_TRUE(engine.lastStep().solver.implicit);
        EXPECT_EQ(engine.lastStep().solver.unconvergedSubsteps, 0u);
        EXPECT_LE(engine.lastStep().solver.maxRelativeResidual, 1.0e-4);
        EXPECT_GE(engine.lastStep().solver.maxIterations, 1u);
        // Setup (with gravity and damping), then direction + update until the host's first
        // convergence check (every 16 iterations: after direction k = 15, 31, …) at or after the
        // iteration that converged, that last direction, NodeUpdate.
        const std::uint32_t converged = engine.lastStep().solver.maxIterations;
        const double checkedAt = converged - converged % 16 + 15;
        EXPECT_EQ(engine.lastStep().dispatchesPerSubstep, 1.0 + 2.0 * checkedAt + 1.0 + 1.0);
    }
    { // Gravity alone: no springs, the system is M·Δv = h·f.
        Engine engine(sceneWith(R"(["gravity"])", implicit));
        EXPECT_EQ(engine.pipeline(), (Names{"ImplicitSolve", "NodeUpdate"}));
        engine.step();
        for (const glm::dvec3& v : engine.readVelocities()) EXPECT_NEAR(v.y, -9.81 / 60.0, 1e-6);
    }
}

TEST(EngineGl, SmallScenesRunAFrameInOneDispatchWithTheSameResult) {
    // The default scene (1024 nodes, 66 substeps): FrameStep against SpringUpdate + NodeUpdate.
    Scene scene = defaultScene();
    Engine fused(scene, {.frameStep = true}), perSubstep(scene);
    EXPECT_EQ(fused.pipeline(), (Names{"FrameStep"}));
    EXPECT_EQ(perSubstep.pipeline(), (Names{"SpringUpdate", "NodeUpdate"}));
    for (int frame = 0; frame < 3; ++frame) {
        fused.step();
        perSubstep.step();
    }
    const int substeps = fused.substepInfo().substeps;
    EXPECT_EQ(fused.lastStep().dispatchesPerSubstep, 1.0 / substeps);
    EXPECT_EQ(perSubstep.lastStep().dispatchesPerSubstep, 2.0);
    // Same arithmetic (shared includes) in a different program: a compiler may contract or order
    // differently, so allow float rounding — u = 2^-24 of the 1.5 m coordinates per substep, 200
    // substeps, 8x margin (measured on llvmpipe: bit-identical).
    const std::vector<glm::dvec3> a = fused.readPositions(), b = perSubstep.readPositions();
    for (std::size_t i = 0; i < a.size(); ++i)
        ASSERT_LE(glm::length(a[i] - b[i]), 8.0 * 3 * substeps * 1.5 * 0x1p-24) << "node " << i;
    // Collisions, implicit Euler, large scenes and heavy rows keep the per-substep passes.
    Engine collisions(sceneWith(R"(["springs", "collisions"])"), {.frameStep = true});
    EXPECT_NE(collisions.pipeline().front(), "FrameStep");
    Engine implicit(sceneWith(R"(["springs"])", R"("time": {"integrator": "implicit_euler"},)"),
                    {.frameStep = true});
    EXPECT_EQ(implicit.pipeline(), (Names{"ImplicitSolve", "NodeUpdate"}));
}

/// A cloth of nx × ny nodes, tilted 60° with its lowest row 1 cm above the ground, thrown sideways
/// and down into the wind at `substeps` substeps per frame: springs, gravity, damping, wind and
/// the ground all act in the frame, and every node moves by centimetres.
Scene thrownClothInTheWind(int nx, int ny, int substeps) {
    const std::string json = R"({"format_version": 1, "name": "thrown cloth",
      "effects": ["gravity", "springs", "damping", "wind", "ground"],
      "time": {"substeps": )" +
                             std::to_string(substeps) +
                             R"(}, "damping": 0.1,
      "wind": {"velocity": [2, 0, 4], "drag": 1},
      "ground": {"height": 0, "restitution": 0.3, "friction": 0.5},
      "objects": [{"name": "cloth", "generator": {"type": "cloth", "size": [1, 1], "resolution": [)" +
                             std::to_string(nx) + ", " + std::to_string(ny) + R"(]},
                   "transform": {"translate": [0, 0.26, 0], "rotate_deg": [60, 0, 0]},
                   "velocity": [3, -2, 1], "angular_velocity": [0, 4, 0], "mass": 0.1,
                   "springs": {"stiffness": 1000, "damping": 0.001}}]})";
    return parseScene(json, ".", "thrown cloth");
}

// FrameStep's one work group of GLC_FRAME_STEP_GROUP = 1024 invocations takes every 1024th node,
// and a dispatch runs at most kFrameStepSubstepsPerDispatch = 1024 substeps, fewer where
// llvmpipe's loop limiter would end its invocations early. The default scene (1024 nodes, 66
// substeps) exercises neither stride nor split: these scenes have 1,025 and 4,096 (the largest
// FrameStep takes) nodes and 1,100 substeps per frame. This test found the loop limit: a
// 4,096-node frame beyond ~800 substeps in one dispatch was cut short (positions 2.6 cm off).
TEST(EngineGl, FrameStepMatchesThePerSubstepPassesBeyondOneWorkGroup) {
    constexpr int kSubsteps = 1100;
    for (const auto& [nx, ny] : {std::pair{25, 41}, std::pair{64, 64}}) {
        const Scene scene = thrownClothInTheWind(nx, ny, kSubsteps);
        Engine fused(scene, {.frameStep = true}), perSubstep(scene);
        const std::string what = std::to_string(nx * ny) + " nodes";
        ASSERT_EQ(fused.nodeCount(), static_cast<std::uint32_t>(nx * ny)) << what;
        EXPECT_EQ(fused.pipeline(), (Names{"FrameStep"})) << what;
        EXPECT_EQ(perSubstep.pipeline(), (Names{"SpringUpdate", "NodeUpdate"})) << what;
        EXPECT_TRUE(fused.warnings().empty())
            << what << ": 1,100 substeps are above the stability rule's count";
        const std::vector<glm::dvec3> start = perSubstep.readPositions();
        fused.step();
        perSubstep.step();
        // Several dispatches (1,024 substeps at most each, fewer for llvmpipe's loop limit), still
        // far fewer than two per substep.
        const double dispatches = fused.lastStep().dispatchesPerSubstep * kSubsteps;
        EXPECT_GE(dispatches, 2.0) << what;
        EXPECT_LE(dispatches, 8.0) << what;
        const std::vector<glm::dvec3> a = fused.readPositions(), b = perSubstep.readPositions();
        // The same shared GLSL in the same order (SpringUpdate's spring + external sum and
        // FrameStep's external + spring are one commutative float addition), so llvmpipe gives
        // identical bits. Another compiler may contract a·b + c into a fused multiply-add in one
        // program and not the other: u = 2^-24 relative per rounding, so per substep at most a few
        // u of the coordinates (< 0.7 m here) in each of three components; linear over the
        // substeps of one frame at a stable step, with a margin of 8 (the bound of
        // SmallScenesRunAFrameInOneDispatchWithTheSameResult): 1.1 mm.
        const double tolerance = 8.0 * 3 * kSubsteps * 0.7 * 0x1p-24;
        double largest = 0.0, smallestMove = 1e30;
        int grounded = 0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            largest = std::max(largest, glm::length(a[i] - b[i]));
            smallestMove = std::min(smallestMove, glm::length(b[i] - start[i]));
            if (b[i].y == 0.0) ++grounded;
        }
        std::printf("%s: %.0f dispatches; FrameStep vs the per-substep passes: largest difference %.3g m "
                    "(tolerance %.3g m); every node moved at least %.3g m, %d on the ground\n",
                    what.c_str(), dispatches, largest, tolerance, smallestMove, grounded);
        EXPECT_LE(largest, tolerance) << what;
        // The comparison sees a node FrameStep leaves behind: every node moves by far more.
        EXPECT_GT(smallestMove, 10.0 * tolerance) << what;
        EXPECT_GT(grounded, 0) << what << ": the ground must act in the frame";
    }
}

TEST(EngineGl, ImplicitEulerWarnsWhenPenaltyContactsNeedMoreSubsteps) {
    // Penalty contacts enter the implicit step explicitly (docs/integration.md): at 10⁶ N/m on
    // nodes of ~6 g one substep per frame is beyond their explicit limit; Bridson's are not limited.
    const std::string implicit = R"("time": {"integrator": "implicit_euler"},)";
    Engine penalty(sceneWith(R"(["springs", "collisions"])",
                             implicit + R"("collision": {"stiffness": 1e6, "response": "penalty"},)"));
    ASSERT_EQ(penalty.warnings().size(), 1u);
    EXPECT_NE(penalty.warnings()[0].find("penalty contact"), std::string::npos) << penalty.warnings()[0];
    Engine bridson(sceneWith(R"(["springs", "collisions"])",
                             implicit + R"("collision": {"stiffness": 1e6, "response": "bridson"},)"));
    EXPECT_TRUE(bridson.warnings().empty());
}

TEST(EngineGl, EveryShippedSceneComposesAndSteps) {
    const std::filesystem::path dir = std::filesystem::path(GLCOLLIDE_SOURCE_DIR) / "scenes";
    int scenes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        Scene scene = loadScene(entry.path());
        // One substep, not a frame: the large scenes take seconds per frame on llvmpipe, and
        // what this test checks (composition, upload, every pass runs and stays finite) needs one.
        scene.time.dt /= 1000.0;
        scene.time.substeps = 1;
        Engine engine(scene);
        engine.step();
        for (const glm::dvec3& x : engine.readPositions())
            ASSERT_TRUE(std::isfinite(x.x + x.y + x.z)) << entry.path();
        ++scenes;
    }
    EXPECT_GE(scenes, 3);
}

TEST(EngineGl, CollisionEffectsAddTheirPassesAndBuffers) {
    // Robust precision (the default) adds the undecided list of the exact pass.
    const Names collisionBuffers = {"faceInfo",      "objects",         "boxes",         "boxFaceOffsets",
                                    "boxFaceList",   "boxPairs",        "candidates",    "undecided",
                                    "intersections", "vertexFacePairs", "edgeEdgePairs", "collisionCounters",
                                    "dispatchArgs"};
    Engine engine(sceneWith(R"(["collisions", "springs"])", R"("collision": {"response": "penalty"},)"));
    EXPECT_EQ(engine.pipeline(), (Names{"SpringUpdate", "BBUpdate", "BBCollision", "TriTri", "FeaturePairs",
                                        "ContactResponse", "NodeUpdate"}));
    Names buffers = {"positions",         "velocities",     "faces",      "forces",        "springs",
                     "nodeSpringOffsets", "nodeSpringList", "heavyNodes", "contactForces", "health"};
    buffers.insert(buffers.end(), collisionBuffers.begin(), collisionBuffers.end());
    EXPECT_EQ(engine.allocatedBuffers(), buffers);
    engine.step();
    EXPECT_TRUE(engine.lastStep().collisions);
    EXPECT_EQ(engine.lastStep().passes.size(), 7u);
    // A scene that names no response gets the intersection-free one (decision 0024, "The
    // default"): continuous detection (the CCD) and the checked, cut and guarded step.
    Engine defaults(sceneWith(R"(["collisions", "springs", "gravity"])"));
    const Names pipeline = defaults.pipeline();
    for (const char* pass : {"NodePredict", "Ccd", "SafeStep", "EnergyGuard"})
        EXPECT_NE(std::find(pipeline.begin(), pipeline.end(), pass), pipeline.end()) << pass;
    EXPECT_EQ(std::find(pipeline.begin(), pipeline.end(), "NodeUpdate"), pipeline.end())
        << "the checked step is committed, not integrated again";
    // All pairs needs no leaf boxes (no BBUpdate); its face-pair stage is timed as BBCollision.
    Engine allPairs(sceneWith(R"(["self_collisions"])",
                              R"("collision": {"broad_phase": "all_pairs", "response": "penalty"},)"));
    EXPECT_EQ(allPairs.pipeline(),
              (Names{"BBCollision", "TriTri", "FeaturePairs", "ContactResponse", "NodeUpdate"}));
    allPairs.step();
}

TEST(EngineGl, ExplicitSubstepsBelowTheLimitWarn) {
    Scene scene = sceneWith(R"(["springs"])");
    scene.bodies[0].springs[0].stiffness = 1e7;
    scene.time.substeps = 1;
    Engine engine(scene);
    EXPECT_GT(engine.substepInfo().stableSubsteps, 1);
    ASSERT_EQ(engine.warnings().size(), 1u);
    EXPECT_NE(engine.warnings()[0].find("stability limit"), std::string::npos);
}

TEST(EngineGl, TimingsArePerPass) {
    Engine engine(sceneWith(R"(["gravity", "springs"])"), {.frameStep = false});
    engine.step();
    const StepStats& s = engine.lastStep();
    ASSERT_EQ(s.passes.size(), 2u); // SpringUpdate (gravity included), NodeUpdate
    for (const PassTiming& p : s.passes) EXPECT_GE(p.gpuMilliseconds, 0.0) << p.name;
    EXPECT_GT(s.passes[0].gpuMilliseconds, 0.0) << "timestamp pairs measure SpringUpdate";
    EXPECT_EQ(s.frame, 1u);
}

} // namespace
} // namespace glcollide

namespace glcollide {
namespace {

TEST(EngineGl, TwoEnginesOnOneContextDoNotInterfere) {
    // Stepping a second engine in between must not change the first one's results: no global
    // state, every dispatch rebinds its own buffers.
    const Scene cloth = sceneWith(R"(["gravity", "springs"])");
    Scene other = sceneWith(R"(["gravity"])");
    other.gravity = {5.0, 3.0, 0.0};
    Engine alone(cloth);
    for (int i = 0; i < 10; ++i) alone.step();
    Engine first(cloth);
    Engine second(other);
    for (int i = 0; i < 10; ++i) {
        first.step();
        second.step();
    }
    EXPECT_EQ(first.readPositions(), alone.readPositions()) << "bit-identical: same device, same order";
    EXPECT_NE(second.readPositions(), alone.readPositions());
}

} // namespace
} // namespace glcollide
