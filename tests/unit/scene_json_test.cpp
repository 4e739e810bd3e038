// JSON scene reader: parameters, transforms, masses, springs, errors with file and pointer.
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <filesystem>
#include <numbers>
#include <string>

using namespace glcollide;
using ::testing::HasSubstr;

namespace {

const std::string kSource = GLCOLLIDE_SOURCE_DIR;
const std::string kData = GLCOLLIDE_TEST_DATA_DIR;

Scene parse(const std::string& text) {
    return parseScene(text, kData + "/mesh", "test.json");
}

std::string errorOf(const std::string& text) {
    try {
        parse(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

/// A one-object scene; `object` is spliced into the objects array, `extra` into the root.
std::string scene(const std::string& object, const std::string& extra = "",
                  const std::string& effects = R"(["gravity", "springs"])") {
    return R"({"format_version": 1, "effects": )" + effects + (extra.empty() ? "" : ", " + extra) +
           R"(, "objects": [)" + object + "]}";
}

const std::string kCloth = R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
                              "mass": 0.6, "springs": {"stiffness": 100}})";

double totalMass(const Body& b) {
    double m = 0.0;
    for (double x : b.masses) m += x;
    return m;
}

} // namespace

TEST(SceneJson, DefaultSceneEqualsHangingClothJson) {
    const Scene def = defaultScene();
    const Scene file = loadScene(kSource + "/scenes/hanging_cloth.json");
    EXPECT_EQ(def.name, file.name);
    EXPECT_EQ(def.effects, file.effects);
    EXPECT_EQ(def.effects, (EffectSet{Effect::Gravity, Effect::Springs, Effect::Damping}));
    EXPECT_EQ(def.time.dt, file.time.dt);
    EXPECT_EQ(def.time.substeps, 0);
    EXPECT_EQ(def.time.frames, 240);
    EXPECT_EQ(def.gravity, file.gravity);
    EXPECT_EQ(def.damping, file.damping);
    ASSERT_EQ(def.bodies.size(), 1u);
    ASSERT_EQ(file.bodies.size(), 1u);
    const Body& a = def.bodies[0];
    const Body& b = file.bodies[0];
    EXPECT_EQ(a.positions.size(), 32u * 32u);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.masses, b.masses);
    EXPECT_EQ(a.pinned, b.pinned);
    EXPECT_EQ(a.springs.size(), b.springs.size());
    EXPECT_EQ(a.faces, b.faces);
    // Pinned at the two corners of one edge; horizontal at y = 1.5 (the XY plane turned 90°
    // about X), so it swings down. Tolerance: the rotation's cos(90°) rounding, ~1e-16 m.
    EXPECT_EQ(a.pinned[0], 1);
    EXPECT_EQ(a.pinned[31], 1);
    EXPECT_NEAR(a.positions[0].y, 1.5, 1e-12);
    EXPECT_NEAR(a.positions.back().y, 1.5, 1e-12);
    EXPECT_NEAR(a.positions[0].z, 0.5, 1e-12);
    EXPECT_NEAR(a.positions.back().z, -0.5, 1e-12);
    EXPECT_TRUE(def.sourcePath.empty());
    EXPECT_EQ(file.sourcePath, std::filesystem::path(kSource + "/scenes/hanging_cloth.json"));
}

TEST(SceneJson, EveryShippedSceneLoads) {
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(kSource + "/scenes")) {
        if (entry.path().extension() != ".json") continue;
        ++count;
        EXPECT_NO_THROW({
            const Scene s = loadScene(entry.path());
            EXPECT_FALSE(s.bodies.empty());
        }) << entry.path();
    }
    EXPECT_GE(count, 5);
}

TEST(SceneJson, ShippedScenesHaveWhatTheyPromise) {
    const Scene ball = loadScene(kSource + "/scenes/falling_tet_body.json");
    EXPECT_EQ(ball.bodies[0].positions.size(), 1760u);
    EXPECT_EQ(ball.bodies[0].faces.size(), 2474u);
    EXPECT_TRUE(ball.effects.has(Effect::Ground));
    const Scene button = loadScene(kSource + "/scenes/button_cloth.json");
    const Body& cloth = button.bodies[0];
    EXPECT_EQ(cloth.positions.size(), 392u);
    std::size_t pinned = 0;
    for (auto p : cloth.pinned) pinned += p;
    EXPECT_EQ(pinned, 20u); // the OBJ has 20 vertices at y = 0 (its top edge)
    const Scene flag = loadScene(kSource + "/scenes/windy_flag.json");
    pinned = 0;
    for (auto p : flag.bodies[0].pinned) pinned += p;
    EXPECT_EQ(pinned, 20u); // the left column of a 30 x 20 grid
    EXPECT_EQ(flag.wind.velocity, glm::dvec3(6, 0, 1.5));
}

TEST(SceneJson, ClothMassSpringsAndDefaults) {
    const Scene s = parse(scene(kCloth));
    const Body& b = s.bodies[0];
    EXPECT_EQ(b.name, "object 0");
    EXPECT_EQ(s.name, "test");
    EXPECT_EQ(b.positions.size(), 20u);
    // Sum of 20 lumps rescaled to the total: a few ulp.
    EXPECT_NEAR(totalMass(b), 0.6, 1e-14);
    // Interior nodes carry 6 triangles' thirds, corners fewer: lumping, not equal shares.
    EXPECT_GT(b.masses[5], b.masses[0]);
    std::size_t structural = 0, shear = 0, bend = 0;
    for (const Spring& sp : b.springs) {
        EXPECT_DOUBLE_EQ(sp.restLength, glm::length(b.positions[sp.a] - b.positions[sp.b]));
        switch (sp.kind) {
        case SpringKind::Structural:
            ++structural;
            EXPECT_EQ(sp.stiffness, 100.0);
            break;
        case SpringKind::Shear:
            ++shear;
            EXPECT_EQ(sp.stiffness, 100.0);
            break;
        case SpringKind::Bend:
            ++bend;
            EXPECT_EQ(sp.stiffness, 10.0);
            break;
        default:
            ADD_FAILURE();
        }
        EXPECT_EQ(sp.damping, 0.0);
    }
    EXPECT_EQ(structural, 3u * 5u + 4u * 4u);
    EXPECT_EQ(shear, 2u * 3u * 4u);
    EXPECT_EQ(bend, 2u * 5u + 4u * 3u);
    EXPECT_EQ(s.time.dt, 1.0 / 60.0);
    EXPECT_EQ(s.gravity, glm::dvec3(0, -9.81, 0));

    const Scene noBend = parse(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "density": 0.2, "springs": {"stiffness": 100, "damping": 2, "shear_stiffness": 0, "bend_stiffness": 0}})"));
    EXPECT_EQ(noBend.bodies[0].springs.size(), structural);
    EXPECT_EQ(noBend.bodies[0].springs[0].damping, 2.0);
    // density 0.2 kg/m² on 1 × 2 m.
    EXPECT_NEAR(totalMass(noBend.bodies[0]), 0.4, 1e-14);
}

TEST(SceneJson, TransformScaleRotateTranslate) {
    const Scene s = parse(scene(R"({"generator": {"type": "cloth", "size": [2, 2], "resolution": [2, 2]},
        "transform": {"translate": [1, 2, 3], "rotate_deg": [90, 0, 0], "scale": 2},
        "mass": 1, "springs": {"stiffness": 1}})"));
    const Body& b = s.bodies[0];
    // Node 0 is local (-1, 1, 0): scaled (-2, 2, 0), rotated 90° about X to (-2, 0, 2), moved.
    // cos(pi/2) is 6e-17 in double, so the rotated zero is off by ~1e-16.
    EXPECT_NEAR(b.positions[0].x, -1.0, 1e-12);
    EXPECT_NEAR(b.positions[0].y, 2.0, 1e-12);
    EXPECT_NEAR(b.positions[0].z, 5.0, 1e-12);
    // Rest lengths are measured after scaling: the structural edges are 4 m long.
    EXPECT_NEAR(b.springs[0].restLength, 4.0, 1e-12);

    const Scene z = parse(scene(R"({"generator": {"type": "cloth", "size": [2, 2], "resolution": [2, 2]},
        "transform": {"rotate_deg": [0, 0, 90], "scale": [1, 3, 1]}, "mass": 1, "springs": {"stiffness": 1}})"));
    // (-1, 1, 0) → scale (-1, 3, 0) → 90° about Z: (-3, -1, 0).
    EXPECT_NEAR(z.bodies[0].positions[0].x, -3.0, 1e-12);
    EXPECT_NEAR(z.bodies[0].positions[0].y, -1.0, 1e-12);
}

TEST(SceneJson, VelocityAndAngularVelocity) {
    const Scene s =
        parse(scene(R"({"generator": {"type": "tet_box", "size": [1, 1, 1], "resolution": [2, 2, 2]},
        "transform": {"translate": [5, 0, 0]}, "velocity": [1, 0, 0], "angular_velocity": [0, 0, 2],
        "mass": 1, "springs": {"stiffness": 1}})"));
    const Body& b = s.bodies[0];
    for (std::size_t v = 0; v < b.positions.size(); ++v) {
        const glm::dvec3 r =
            b.positions[v] - glm::dvec3(5, 0, 0); // the box is symmetric: centre of mass at the translation
        const glm::dvec3 want = glm::dvec3(1, 0, 0) + glm::cross(glm::dvec3(0, 0, 2), r);
        EXPECT_NEAR(glm::length(b.velocities[v] - want), 0.0, 1e-12);
    }
}

TEST(SceneJson, TetMeshSceneFromFile) {
    const Scene s = loadScene(kData + "/scene/two_tets.json");
    const Body& b = s.bodies[0];
    EXPECT_EQ(b.name, "two tets");
    EXPECT_EQ(b.positions.size(), 5u);
    EXPECT_EQ(b.tets.size(), 2u);
    EXPECT_EQ(b.faces.size(), 6u);
    EXPECT_EQ(b.springs.size(), 9u); // 6 + 6 tet edges, 3 shared
    // Volume 0.5 m³ at 1000 kg/m³; volumes of integer-coordinate tets are exact to an ulp.
    EXPECT_NEAR(totalMass(b), 500.0, 1e-10);
    EXPECT_EQ(b.pinned, (std::vector<std::uint8_t>{0, 0, 0, 0, 1}));
    for (const Spring& sp : b.springs) {
        EXPECT_EQ(sp.kind, SpringKind::Edge);
        EXPECT_EQ(sp.stiffness, 100.0);
        EXPECT_EQ(sp.damping, 0.1);
    }
}

TEST(SceneJson, SurfaceMeshEdgeAndBendSprings) {
    const Scene s = parse(scene(R"({"mesh": "seam_square.obj", "mass": 2,
        "springs": {"stiffness": 10, "bend_stiffness": 1}})"));
    const Body& b = s.bodies[0];
    EXPECT_EQ(b.positions.size(), 4u);
    ASSERT_EQ(b.springs.size(), 6u); // 5 edges + 1 bend across the diagonal
    EXPECT_EQ(b.springs.back().kind, SpringKind::Bend);
    EXPECT_EQ(b.springs.back().stiffness, 1.0);
    EXPECT_NEAR(b.springs.back().restLength, std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(totalMass(b), 2.0, 1e-14);
    const Scene noBend =
        parse(scene(R"({"mesh": "seam_square.obj", "mass": 2, "springs": {"stiffness": 10}})"));
    EXPECT_EQ(noBend.bodies[0].springs.size(), 5u);
}

TEST(SceneJson, PinnedBox) {
    const Scene s = parse(scene(R"({"generator": {"type": "cloth", "size": [1, 1], "resolution": [3, 3]},
        "mass": 1, "springs": {"stiffness": 1}, "pinned": {"inside": {"min": [-1, 0.4, -1], "max": [1, 1, 1]}}})"));
    EXPECT_EQ(s.bodies[0].pinned, (std::vector<std::uint8_t>{1, 1, 1, 0, 0, 0, 0, 0, 0}));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 1], "resolution": [3, 3]},
        "mass": 1, "springs": {"stiffness": 1}, "pinned": {"inside": {"min": [5, 5, 5], "max": [6, 6, 6]}}})")),
                HasSubstr("test.json: /objects/0/pinned/inside: the box contains no node"));
}

TEST(SceneJson, SettingsAndEffects) {
    const Scene s = parse(
        scene(kCloth,
              R"("name": "x", "time": {"dt": 0.01, "substeps": 7, "frames": 3},
        "gravity": [0, -1, 0], "damping": 0.5, "wind": {"velocity": [1, 2, 3], "drag": 0.5},
        "ground": {"height": -1, "restitution": 0.5, "friction": 0.25})",
              R"(["gravity", "springs", "damping", "wind", "ground", "collisions", "self_collisions"])"));
    EXPECT_EQ(s.name, "x");
    EXPECT_EQ(s.time.dt, 0.01);
    EXPECT_EQ(s.time.substeps, 7);
    EXPECT_EQ(s.time.frames, 3);
    EXPECT_EQ(s.gravity, glm::dvec3(0, -1, 0));
    EXPECT_EQ(s.damping, 0.5);
    EXPECT_EQ(s.wind.velocity, glm::dvec3(1, 2, 3));
    EXPECT_EQ(s.wind.drag, 0.5);
    EXPECT_EQ(s.ground.height, -1.0);
    EXPECT_EQ(s.ground.restitution, 0.5);
    EXPECT_EQ(s.ground.friction, 0.25);
    EXPECT_TRUE(s.effects.has(Effect::Collisions));
    EXPECT_TRUE(s.effects.has(Effect::SelfCollisions));
    EXPECT_EQ(s.collision.broadPhase, BroadPhase::Octree) << "documented default";
    EXPECT_EQ(s.collision.octreeDepth, 2);
    EXPECT_EQ(s.collision.precision, TriTriPrecision::Robust);
    // The default response is intersection_free, with continuous detection (decision 0024, "The
    // default"); penalty and bridson bring discrete detection unless a scene names one.
    EXPECT_EQ(s.collision.response, ContactResponse::IntersectionFree) << "documented default";
    EXPECT_EQ(s.collision.detection, Detection::Continuous) << "documented default";
    const Scene noCollisionObject = parse(scene(kCloth, "", R"(["springs", "self_collisions"])"));
    EXPECT_EQ(noCollisionObject.collision.response, ContactResponse::IntersectionFree);
    EXPECT_EQ(noCollisionObject.collision.detection, Detection::Continuous);
    EXPECT_EQ(
        parse(scene(kCloth, R"("collision": {"response": "penalty"})", R"(["springs", "self_collisions"])"))
            .collision.detection,
        Detection::Discrete);
    EXPECT_EQ(parse(scene(kCloth, R"("collision": {"response": "penalty", "detection": "continuous"})",
                          R"(["springs", "self_collisions"])"))
                  .collision.detection,
              Detection::Continuous);
    EXPECT_THAT(
        errorOf(
            scene(kCloth, R"("collision": {"detection": "discrete"})", R"(["springs", "self_collisions"])")),
        HasSubstr("/collision/detection: the default response, intersection_free, needs \"detection\": "
                  "\"continuous\"; name \"response\": \"penalty\" or \"bridson\" to detect discretely"));
    const Scene c = parse(scene(kCloth, R"("collision": {"broad_phase": "masked", "octree_depth": 3,
        "precision": "fast", "response": "bridson", "thickness": 0.002, "stiffness": 500, "damping": 0.1, "friction": 0.4, "relaxation_time": 0.02, "initial_capacity": 1})",
                                R"(["springs", "self_collisions"])"));
    EXPECT_EQ(c.collision.broadPhase, BroadPhase::Masked);
    EXPECT_EQ(c.collision.octreeDepth, 3);
    EXPECT_EQ(c.collision.precision, TriTriPrecision::Fast);
    EXPECT_EQ(c.collision.response, ContactResponse::Bridson);
    EXPECT_THAT(
        errorOf(
            scene(kCloth, R"("collision": {"response": "impulse"})", R"(["springs", "self_collisions"])")),
        HasSubstr("/collision/response: unknown response \"impulse\"; expected \"penalty\", \"bridson\" or "
                  "\"intersection_free\""));
    // The intersection-free response reads the CCD: continuous detection is its default, and
    // discrete detection is an error.
    const Scene safe = parse(scene(kCloth, R"("collision": {"response": "intersection_free"})",
                                   R"(["springs", "self_collisions"])"));
    EXPECT_EQ(safe.collision.response, ContactResponse::IntersectionFree);
    EXPECT_EQ(safe.collision.detection, Detection::Continuous);
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {"response": "intersection_free", "detection": "discrete"})",
                      R"(["springs", "self_collisions"])")),
        HasSubstr(
            "/collision/detection: the intersection_free response needs \"detection\": \"continuous\""));
    // Its energy guard: on by default, a boolean, its own response's only, and refused where the
    // scene asks for it with wind (which does work on the scene); by default the engine leaves it
    // out there.
    EXPECT_TRUE(safe.collision.energyGuard) << "documented default";
    EXPECT_FALSE(
        parse(scene(kCloth, R"("collision": {"response": "intersection_free", "energy_guard": false})",
                    R"(["springs", "self_collisions"])"))
            .collision.energyGuard);
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"response": "intersection_free", "energy_guard": 1})",
                              R"(["springs", "self_collisions"])")),
                HasSubstr("/collision/energy_guard: expected true or false, got 1"));
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {"response": "bridson", "energy_guard": true})",
                      R"(["springs", "self_collisions"])")),
        HasSubstr("/collision/energy_guard: only the \"intersection_free\" response has an energy guard"));
    // Its velocity-response iterations: automatic (0) unless set, 1 ... 64, its own response's only.
    EXPECT_EQ(safe.collision.responseIterations, 0) << "documented default: automatic";
    EXPECT_EQ(parse(scene(kCloth, R"("collision": {"response_iterations": 12})",
                          R"(["springs", "self_collisions"])"))
                  .collision.responseIterations,
              12);
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"response_iterations": 65})",
                              R"(["springs", "self_collisions"])")),
                HasSubstr("/collision/response_iterations: expected an integer in [1, 64], got 65"));
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {"response": "penalty", "response_iterations": 8})",
                      R"(["springs", "self_collisions"])")),
        HasSubstr("/collision/response_iterations: only the \"intersection_free\" response iterates its "
                  "velocity response"));
    EXPECT_THAT(
        errorOf(scene(
            kCloth,
            R"("wind": {"velocity": [1, 0, 0]}, "collision": {"response": "intersection_free", "energy_guard": true})",
            R"(["springs", "wind", "self_collisions"])")),
        HasSubstr("/collision/energy_guard: the energy guard needs a closed scene"));
    EXPECT_NO_THROW(parse(
        scene(kCloth, R"("wind": {"velocity": [1, 0, 0]})", R"(["springs", "wind", "self_collisions"])")));
    EXPECT_NO_THROW(
        parse(scene(kCloth, R"("wind": {"velocity": [1, 0, 0]}, "collision": {"thickness": 0.01})",
                    R"(["springs", "wind", "self_collisions"])")));
    EXPECT_NO_THROW(parse(scene(
        kCloth,
        R"("wind": {"velocity": [1, 0, 0]}, "collision": {"response": "intersection_free", "energy_guard": false})",
        R"(["springs", "wind", "self_collisions"])")));
    // Newton steps (time.solver.newton_steps): 1 by default, 1 … 4, above 1 only where the contacts
    // are in the solve (the intersection_free response).
    const std::string implicitTime =
        R"("time": {"integrator": "implicit_euler", "solver": {"newton_steps": )";
    EXPECT_EQ(safe.time.solver.newtonSteps, 0) << "documented default: automatic";
    EXPECT_EQ(parse(scene(kCloth, implicitTime + R"(2}}, "collision": {"response": "intersection_free"})",
                          R"(["springs", "self_collisions"])"))
                  .time.solver.newtonSteps,
              2);
    EXPECT_THAT(errorOf(scene(kCloth, implicitTime + R"(5}}, "collision": {"response": "intersection_free"})",
                              R"(["springs", "self_collisions"])")),
                HasSubstr("/time/solver/newton_steps: expected an integer in [1, 4], got 5"));
    EXPECT_THAT(
        errorOf(scene(kCloth, implicitTime + R"(2}}, "collision": {"response": "bridson"})",
                      R"(["springs", "self_collisions"])")),
        HasSubstr("/time/solver/newton_steps: more than 1 Newton step needs the contacts in the solve"));
    EXPECT_THAT(
        errorOf(scene(kCloth, implicitTime + R"(2}})")),
        HasSubstr("/time/solver/newton_steps: more than 1 Newton step needs the contacts in the solve"));
    // The Newton steps' line search (time.solver.line_search): on by default, a boolean.
    EXPECT_TRUE(safe.time.solver.lineSearch) << "documented default: on";
    EXPECT_FALSE(parse(scene(kCloth,
                             R"("time": {"integrator": "implicit_euler", "solver": {"line_search": false}},)"
                             R"( "collision": {"response": "intersection_free"})",
                             R"(["springs", "self_collisions"])"))
                     .time.solver.lineSearch);
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("time": {"integrator": "implicit_euler", "solver": {"line_search": 1}})")),
        HasSubstr("/time/solver/line_search: expected true or false, got 1"));
    // The solver's numbers of the intersection-free response: `key` set to `value`.
    const auto withSolverNumber = [&](const std::string& key, const std::string& value) {
        return scene(kCloth,
                     R"("time": {"integrator": "implicit_euler", "solver": {")" + key + R"(": )" + value +
                         R"(}}, "collision": {"response": "intersection_free"})",
                     R"(["springs", "self_collisions"])");
    };
    // The Newton steps' tolerance (time.solver.newton_tolerance): a fraction of the thickness.
    EXPECT_EQ(safe.time.solver.newtonTolerance, 0.25) << "documented default";
    EXPECT_EQ(parse(withSolverNumber("newton_tolerance", "0")).time.solver.newtonTolerance, 0.0);
    EXPECT_THAT(
        errorOf(withSolverNumber("newton_tolerance", "1.5")),
        HasSubstr("/time/solver/newton_tolerance: expected a fraction of the thickness in [0, 1], got 1.5"));
    EXPECT_THAT(errorOf(withSolverNumber("newton_tolerance", R"("a")")),
                HasSubstr("/time/solver/newton_tolerance: expected a number, got \"a\""));
    // Approaching pairs within a margin in the solve (time.solver.contact_margin): a multiple of the
    // thickness in [0, 4].
    EXPECT_EQ(safe.time.solver.contactMargin, 0.0) << "documented default";
    EXPECT_EQ(parse(withSolverNumber("contact_margin", "1.5")).time.solver.contactMargin, 1.5);
    for (const char* bad : {"4.5", "-1"})
        EXPECT_THAT(
            errorOf(withSolverNumber("contact_margin", bad)),
            HasSubstr(std::string("/time/solver/contact_margin: expected a multiple of the thickness in "
                                  "[0, 4], got ") +
                      bad));
    EXPECT_EQ(c.collision.thickness, 0.002);
    EXPECT_EQ(c.collision.stiffness, 500.0);
    EXPECT_EQ(c.collision.damping, 0.1);
    EXPECT_EQ(c.collision.friction, 0.4);
    EXPECT_EQ(s.collision.friction, 0.0) << "documented default: frictionless";
    EXPECT_EQ(c.collision.relaxationTime, 0.02);
    EXPECT_EQ(s.collision.relaxationTime, 0.01) << "documented default";
    EXPECT_EQ(c.collision.initialCapacity, 1u);
    EXPECT_EQ(c.collision.detection, Detection::Discrete) << "documented default";
    EXPECT_EQ(c.collision.ccd.budget, 4096u) << "documented default";
    EXPECT_EQ(c.collision.ccd.minSeparation, 0.0) << "documented default";
    const Scene cc = parse(scene(
        kCloth,
        R"("collision": {"detection": "continuous", "ccd": {"budget": 21844, "min_separation": 0.001}})",
        R"(["springs", "self_collisions"])"));
    EXPECT_EQ(cc.collision.detection, Detection::Continuous);
    EXPECT_EQ(cc.collision.ccd.budget, 21844u);
    EXPECT_EQ(cc.collision.ccd.minSeparation, 0.001);
    // Effects listed without their key use the documented defaults.
    const Scene d = parse(scene(kCloth, "", R"(["springs", "wind", "ground"])"));
    EXPECT_EQ(d.wind.velocity, glm::dvec3(0));
    EXPECT_EQ(d.wind.drag, 1.0);
    EXPECT_EQ(d.ground.height, 0.0);
}

TEST(SceneJson, UnknownKeysAreErrors) {
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("gravty": [0, 0, 0])")),
        HasSubstr(
            "test.json: /gravty: unknown key 'gravty'; allowed keys here: format_version, name, effects"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "masss": 0.6, "springs": {"stiffness": 100}})")),
                HasSubstr("test.json: /objects/0/masss: unknown key 'masss'"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "mass": 0.6, "springs": {"stifness": 100}})")),
                HasSubstr("test.json: /objects/0/springs/stifness: unknown key 'stifness'"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolutoin": [4, 5]},
        "mass": 0.6, "springs": {"stiffness": 100}})")),
                HasSubstr("/objects/0/generator/resolutoin: unknown key"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "transform": {"rotate": [0, 0, 0]}, "mass": 0.6, "springs": {"stiffness": 100}})")),
                HasSubstr("/objects/0/transform/rotate: unknown key 'rotate'; allowed keys here: translate, "
                          "rotate_deg, scale"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("time": {"dt": 0.01, "step": 2})")),
                HasSubstr("/time/step: unknown key"));
    // Keys that belong to other body kinds are unknown too.
    EXPECT_THAT(
        errorOf(scene(R"({"generator": {"type": "tet_box", "size": [1, 1, 1], "resolution": [1, 1, 1]},
        "mass": 1, "springs": {"stiffness": 1, "bend_stiffness": 1}})")),
        HasSubstr("/objects/0/springs/bend_stiffness: unknown key"));
}

TEST(SceneJson, ValueErrorsNameFileAndPointer) {
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "mass": 0.6, "springs": {"stiffness": -3}})")),
                HasSubstr("test.json: /objects/0/springs/stiffness: expected a positive number, got -3"));
    EXPECT_THAT(errorOf(R"({"format_version": 2, "effects": [], "objects": []})"),
                HasSubstr("test.json: /format_version: unsupported format version 2; supported versions: 1"));
    EXPECT_THAT(errorOf(R"({"effects": [], "objects": []})"),
                HasSubstr("/format_version: required key is missing"));
    EXPECT_THAT(
        errorOf(scene(kCloth, "", R"(["gravity", "sprigs"])")),
        HasSubstr(
            "/effects/1: unknown effect 'sprigs'; known effects: gravity, springs, damping, wind, ground, "
            "collisions, self_collisions"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("wind": {"velocity": [1, 0, 0]})")),
                HasSubstr("test.json: /wind: given but 'wind' is not in /effects"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("damping": 0.1)")), HasSubstr("/damping: given but 'damping'"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {})")),
                HasSubstr("/collision: given but neither 'collisions' nor 'self_collisions' is in /effects"));
    const char* collide = R"(["springs", "collisions"])";
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"broad_phase": "kd_tree"})", collide)),
                HasSubstr("/collision/broad_phase: unknown broad phase \"kd_tree\"; expected \"octree\", "
                          "\"masked\", \"all_pairs\" or \"bvh\""));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"bvh": {"rebuild": 0}})", collide)),
                HasSubstr("/collision/bvh/rebuild: expected \"substep\", \"frame\", \"never\" or a number of "
                          "frames 1 ... 1000000, got 0"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"bvh": {"visits_per_round": 65535}})", collide)),
                HasSubstr("/collision/bvh/visits_per_round: expected an integer in 1 ... 65534, got 65535"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"bvh": {"depth": 3}})", collide)),
                HasSubstr("/collision/bvh"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"friction": -0.1})", collide)),
                HasSubstr("/collision/friction: expected a number >= 0, got -0.1"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"friction": "high"})", collide)),
                HasSubstr("/collision/friction: expected a number >= 0"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"restitution": 1.5})", collide)),
                HasSubstr("/collision/restitution: expected a number in [0, 1], got 1.5"));
    EXPECT_THAT(
        errorOf(scene(kCloth,
                      R"("collision": {"response": "bridson", "detection": "discrete", "restitution": 0.5})",
                      collide)),
        HasSubstr("/collision/restitution: only the \"intersection_free\" response has a restitution between "
                  "bodies"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"restitution_iterations": 8})", collide)),
                HasSubstr("/collision/restitution_iterations: only a restitution above 0 has iterations"));
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {"restitution": 0.5, "restitution_iterations": 65})", collide)),
        HasSubstr("/collision/restitution_iterations: expected an integer in [1, 64], got 65"));
    {
        const Scene s = parse(
            scene(kCloth, R"("collision": {"restitution": 0.5, "restitution_iterations": 8})", collide));
        EXPECT_EQ(s.collision.restitution, 0.5);
        EXPECT_EQ(s.collision.restitutionIterations, 8);
        EXPECT_EQ(parse(scene(kCloth, "", collide)).collision.restitution, 0.0);
    }
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"relaxation_time": 0})", collide)),
                HasSubstr("/collision/relaxation_time: expected a positive number of seconds, got 0"));
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {"response": "penalty", "relaxation_time": 0.02})", collide)),
        HasSubstr("/collision/relaxation_time: the penalty response does not relax"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"detection": "swept"})", collide)),
                HasSubstr("/collision/detection: unknown detection \"swept\"; expected \"discrete\" or "
                          "\"continuous\""));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"ccd": {"budget": 21845}})", collide)),
                HasSubstr("/collision/ccd/budget: expected an integer in 1 ... 21844, got 21845"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"ccd": {"min_separation": -1}})", collide)),
                HasSubstr("/collision/ccd/min_separation"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"ccd": {"tolerance": 1}})", collide)),
                HasSubstr("/collision/ccd/tolerance: unknown key"));
    const char* self = R"(["springs", "self_collisions"])";
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {"ghost_max_perimeter": 1})", self)),
        HasSubstr("/collision/ghost_max_perimeter: ghost triangles close holes for radial culling only"));
    EXPECT_THAT(errorOf(scene(kCloth,
                              R"("collision": {"response": "intersection_free", "culling": "radial",
                                               "ghost_max_perimeter": -1})",
                              self)),
                HasSubstr("/collision/ghost_max_perimeter: expected a number >= 0, got -1"));
    const std::string radial = R"("response": "intersection_free", "culling": "radial", )";
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"observers": "clusters"})", self)),
                HasSubstr("/collision/observers: observers serve radial culling only"));
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {)" + radial + R"("observers": "bones"})", self)),
        HasSubstr("/collision/observers: unknown observers \"bones\"; expected \"auto\", \"objects\" or "
                  "\"clusters\""));
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {)" + radial + R"("cluster_max_angle": 90})", self)),
        HasSubstr(
            "/collision/cluster_max_angle: expected an angle in degrees, above 0 and below 90, got 90"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"cluster_max_angle": 30})", self)),
                HasSubstr("/collision/cluster_max_angle: clusters serve radial culling only"));
    EXPECT_THAT(
        errorOf(scene(kCloth, R"("collision": {)" + radial + R"("cluster_max_faces": 1.5})", self)),
        HasSubstr(
            "/collision/cluster_max_faces: expected a whole number of faces >= 0 (0: no limit), got 1.5"));
    {
        const Scene ok = parseScene(
            scene(kCloth,
                  R"("collision": {)" + radial +
                      R"("observers": "clusters", "cluster_max_angle": 30, "cluster_max_faces": 64})",
                  self),
            ".", "ok");
        EXPECT_EQ(ok.collision.observers, RadialObservers::Clusters);
        EXPECT_NEAR(ok.collision.clusterMaxAngle, std::numbers::pi / 6.0, 1e-15);
        EXPECT_EQ(ok.collision.clusterMaxFaces, 64u);
    }
    {
        // A user observer: given in the object's coordinates, moved with its transform.
        const std::string ball = R"({"generator": {"type": "sphere", "radius": 0.1, "subdivisions": 1},
            "mass": 1, "springs": {"stiffness": 1}, "observer": [0.01, 0, 0],
            "transform": {"translate": [0, 1, 0], "scale": 2}})";
        const Scene ok = parseScene(
            scene(ball, R"("collision": {)" + radial + R"("observers": "auto"})", self), ".", "ok");
        ASSERT_TRUE(ok.bodies[0].observer.has_value());
        EXPECT_EQ(*ok.bodies[0].observer, glm::dvec3(0.02, 1.0, 0.0));
        EXPECT_THAT(errorOf(scene(ball, "", self)),
                    HasSubstr("/objects/0/observer: an observer serves radial culling only"));
        std::string bad = ball;
        bad.replace(bad.find("[0.01, 0, 0]"), 12, "[0.01, 0]");
        EXPECT_THAT(errorOf(scene(bad, R"("collision": {)" + radial + R"("observers": "auto"})", self)),
                    HasSubstr("/objects/0/observer"));
        // A segment observer: two points, both moved with the transform; its ends must differ.
        std::string segment = ball;
        segment.replace(segment.find("[0.01, 0, 0]"), 12, "[[0.01, 0, 0], [0, 0.02, 0]]");
        const Scene seg = parseScene(
            scene(segment, R"("collision": {)" + radial + R"("observers": "auto"})", self), ".", "segment");
        ASSERT_TRUE(seg.bodies[0].observer.has_value());
        ASSERT_TRUE(seg.bodies[0].observerEnd.has_value());
        EXPECT_EQ(*seg.bodies[0].observer, glm::dvec3(0.02, 1.0, 0.0));
        EXPECT_EQ(*seg.bodies[0].observerEnd, glm::dvec3(0.0, 0.02 * 2.0 + 1.0, 0.0));
        EXPECT_FALSE(ok.bodies[0].observerEnd.has_value());
        std::string same = ball;
        same.replace(same.find("[0.01, 0, 0]"), 12, "[[0.01, 0, 0], [0.01, 0, 0]]");
        EXPECT_THAT(errorOf(scene(same, R"("collision": {)" + radial + R"("observers": "auto"})", self)),
                    HasSubstr("/objects/0/observer: a segment observer's two ends must differ"));
        std::string short_ = ball;
        short_.replace(short_.find("[0.01, 0, 0]"), 12, "[[0.01, 0, 0], [0, 1]]");
        EXPECT_THAT(errorOf(scene(short_, R"("collision": {)" + radial + R"("observers": "auto"})", self)),
                    HasSubstr("/objects/0/observer/1: expected an array of 3 numbers"));
        // A skeleton: bones, each two points moved with the transform; not with an observer.
        const std::string radialAuto = R"("collision": {)" + radial + R"("observers": "auto"})";
        std::string bones = ball;
        bones.replace(bones.find(R"("observer": [0.01, 0, 0])"), 24,
                      R"("skeleton": [[[0, 0, 0], [0.01, 0, 0]], [[0.01, 0, 0], [0.01, 0.02, 0]]])");
        const Scene skel = parseScene(scene(bones, radialAuto, self), ".", "skeleton");
        ASSERT_EQ(skel.bodies[0].skeleton.size(), 2u);
        EXPECT_EQ(skel.bodies[0].skeleton[0][0], glm::dvec3(0.0, 1.0, 0.0));
        EXPECT_EQ(skel.bodies[0].skeleton[0][1], glm::dvec3(0.02, 1.0, 0.0));
        EXPECT_EQ(skel.bodies[0].skeleton[1][1], glm::dvec3(0.02, 1.04, 0.0));
        EXPECT_FALSE(skel.bodies[0].observer.has_value());
        EXPECT_TRUE(ok.bodies[0].skeleton.empty());
        EXPECT_THAT(errorOf(scene(bones, "", self)),
                    HasSubstr("/objects/0/skeleton: a skeleton serves radial culling only"));
        const auto skeletonError = [&](const std::string& value) {
            std::string b = ball;
            b.replace(b.find(R"("observer": [0.01, 0, 0])"), 24, R"("skeleton": )" + value);
            return errorOf(scene(b, radialAuto, self));
        };
        EXPECT_THAT(skeletonError("[]"), HasSubstr("/objects/0/skeleton: expected an array of bones"));
        EXPECT_THAT(skeletonError("[[[0, 0, 0]]]"), HasSubstr("/objects/0/skeleton/0: expected a bone"));
        EXPECT_THAT(skeletonError("[[[0, 0, 0], [0, 0, 0]]]"),
                    HasSubstr("/objects/0/skeleton/0: a bone's two ends must differ"));
        EXPECT_THAT(skeletonError("[[[0, 0, 0], [0, 1, 0]], [[0, 0, 0], [0, 1]]]"),
                    HasSubstr("/objects/0/skeleton/1/1: expected an array of 3 numbers"));
        std::string both = ball;
        both.replace(both.find(R"("observer": [0.01, 0, 0])"), 24,
                     R"("observer": [0.01, 0, 0], "skeleton": [[[0, 0, 0], [0.01, 0, 0]]])");
        EXPECT_THAT(errorOf(scene(both, radialAuto, self)),
                    HasSubstr("/objects/0/skeleton: give 'observer' or 'skeleton', not both"));
    }
    // The tube's bend: an angle in [0, 180), and an arc wider than the tube.
    const auto tubeError = [&](const std::string& bend, double radius) {
        return errorOf(scene(R"({"generator": {"type": "tube", "radius": )" + std::to_string(radius) +
                             R"(, "length": 0.6, "resolution": [8, 4], "bend_deg": )" + bend +
                             R"(}, "mass": 1, "springs": {"stiffness": 1}})"));
    };
    EXPECT_THAT(tubeError("180", 0.01),
                HasSubstr("/objects/0/generator/bend_deg: expected an angle in degrees in [0, 180)"));
    EXPECT_THAT(tubeError("-1", 0.01), HasSubstr("/objects/0/generator/bend_deg: expected an angle"));
    EXPECT_THAT(tubeError("90", 0.2),
                HasSubstr("/objects/0/generator/bend_deg: the bend's arc radius (0.127324 m"));
    EXPECT_EQ(
        parseScene(scene(R"({"generator": {"type": "tube", "radius": 0.1, "length": 0.6, "resolution": [8, 4],
        "bend_deg": 90}, "mass": 1, "springs": {"stiffness": 1}})"),
                   ".", "bent")
            .bodies[0]
            .positions.size(),
        32u);
    EXPECT_THAT(
        errorOf(scene(R"({"generator": {"type": "tube", "radius": 0.1, "length": 1, "resolution": [2, 4]},
        "mass": 1, "springs": {"stiffness": 1}})")),
        HasSubstr("/objects/0/generator/resolution/0"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "tube", "radius": 0.1, "resolution": [8, 4]},
        "mass": 1, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0/generator/length: required key is missing"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"octree_depth": 4})", collide)),
                HasSubstr("/collision/octree_depth: expected an integer 1, 2 or 3"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"precision": "exact"})", collide)),
                HasSubstr("/collision/precision: unknown precision \"exact\""));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"thickness": 0})", collide)),
                HasSubstr("/collision/thickness: expected a positive number of metres, got 0"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"initial_capacity": 0})", collide)),
                HasSubstr("/collision/initial_capacity: expected an integer in 1 ... 2^30, got 0"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("collision": {"thicknes": 1})", collide)),
                HasSubstr("/collision/thicknes: unknown key"));
    EXPECT_THAT(errorOf(scene(kCloth, "", R"(["gravity"])")),
                HasSubstr("/objects/0/springs: given but 'springs'"));
    EXPECT_THAT(errorOf(scene(
                    R"({"generator": {"type": "cloth", "size": [1, 1], "resolution": [2, 2]}, "mass": 1})")),
                HasSubstr("/objects/0/springs: required because 'springs' is in /effects"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("time": {"substeps": "fast"})")),
                HasSubstr("/time/substeps: expected \"auto\" or a positive integer, got \"fast\""));
    EXPECT_THAT(errorOf(scene(kCloth, R"("time": {"dt": 0})")),
                HasSubstr("/time/dt: expected a positive number, got 0"));
    EXPECT_THAT(errorOf(scene(kCloth, R"("ground": {"restitution": 1.5})", R"(["springs", "ground"])")),
                HasSubstr("/ground/restitution: expected a number in [0, 1], got 1.5"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 1], "resolution": [2, 2]},
        "mass": 1, "springs": {"stiffness": 1}, "pinned": [0, 4]})")),
                HasSubstr("/objects/0/pinned/1: expected an integer in [0, 3], got 4"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 1], "resolution": [2, 2]},
        "mass": 1, "density": 1, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0: give exactly one of 'mass'"));
    EXPECT_THAT(errorOf(scene(R"({"mass": 1, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0: give exactly one of 'mesh' and 'generator'"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 1], "resolution": [1, 2]},
        "mass": 1, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0/generator/resolution/0: expected an integer in [2, 4096], got 1"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "donut"}, "mass": 1, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0/generator/type: unknown generator 'donut'; known generators: cloth, "
                          "tube, tet_box, sphere"));
    EXPECT_THAT(errorOf(scene(R"({"mesh": "x.stl", "mass": 1, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0/mesh: unsupported mesh file 'x.stl'"));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "sphere", "radius": 1}, "mass": 1,
        "transform": {"scale": [1, -1, 1]}, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0/transform/scale/1: expected a positive number, got -1"));
    EXPECT_THAT(errorOf(R"({"format_version": 1, "effects": [], "objects": []})"),
                HasSubstr("/objects: expected a non-empty array"));
    EXPECT_THAT(errorOf("{\"format_version\": 1,\n \"effects\": [}"), HasSubstr("test.json: invalid JSON: "));
    EXPECT_THAT(errorOf("{\"format_version\": 1,\n \"effects\": [}"), HasSubstr("line 2"));
}

TEST(SceneJson, CameraIsOptionalWithDefaults) {
    EXPECT_FALSE(parse(scene(kCloth)).camera.has_value());
    const Scene full =
        parse(scene(kCloth, R"("camera": {"eye": [3, 2, 5], "target": [0, 0.5, 0], "up": [0, 0, 1],
                                                        "fov_deg": 30})"));
    ASSERT_TRUE(full.camera.has_value());
    EXPECT_EQ(full.camera->eye, glm::dvec3(3, 2, 5));
    EXPECT_EQ(full.camera->target, glm::dvec3(0, 0.5, 0));
    EXPECT_EQ(full.camera->up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(full.camera->fovDeg, 30.0);
    const Scene minimal = parse(scene(kCloth, R"("camera": {"eye": [0, 1, 4], "target": [0, 1, 0]})"));
    ASSERT_TRUE(minimal.camera.has_value());
    EXPECT_EQ(minimal.camera->up, glm::dvec3(0, 1, 0));
    EXPECT_EQ(minimal.camera->fovDeg, 45.0);
}

TEST(SceneJson, CameraErrorsNamePointer) {
    const auto camera = [](const std::string& body) {
        return errorOf(scene(kCloth, R"("camera": )" + body));
    };
    EXPECT_THAT(camera("[0, 1, 2]"), HasSubstr("test.json: /camera: expected an object"));
    EXPECT_THAT(camera(R"({"target": [0, 0, 0]})"),
                HasSubstr("test.json: /camera/eye: required key is missing"));
    EXPECT_THAT(camera(R"({"eye": [0, 0, 1]})"), HasSubstr("/camera/target: required key is missing"));
    EXPECT_THAT(camera(R"({"eye": [0, 0], "target": [0, 0, 0]})"),
                HasSubstr("/camera/eye: expected an array of 3 numbers, got [0,0]"));
    EXPECT_THAT(camera(R"({"eye": [0, 0, 1], "target": [0, "x", 0]})"),
                HasSubstr("/camera/target/1: expected a number"));
    EXPECT_THAT(camera(R"({"eye": [1, 2, 3], "target": [1, 2, 3]})"),
                HasSubstr("/camera/target: must differ from eye"));
    EXPECT_THAT(camera(R"({"eye": [0, 0, 1], "target": [0, 0, 0], "up": [0, 0, 0]})"),
                HasSubstr("/camera/up: expected a non-zero vector, got [0,0,0]"));
    EXPECT_THAT(camera(R"({"eye": [0, 5, 0], "target": [0, 0, 0], "up": [0, 1, 0]})"),
                HasSubstr("/camera/up: must not be parallel to the view direction"));
    EXPECT_THAT(camera(R"({"eye": [0, 0, 1], "target": [0, 0, 0], "fov_deg": 180})"),
                HasSubstr("/camera/fov_deg: expected a number of degrees in (0, 180), got 180"));
    EXPECT_THAT(camera(R"({"eye": [0, 0, 1], "target": [0, 0, 0], "fov_deg": 0})"),
                HasSubstr("/camera/fov_deg: expected a number of degrees in (0, 180), got 0"));
    EXPECT_THAT(camera(R"({"eye": [0, 0, 1], "target": [0, 0, 0], "fov_deg": "wide"})"),
                HasSubstr("/camera/fov_deg: expected a number of degrees in (0, 180), got \"wide\""));
    EXPECT_THAT(camera(R"({"eye": [0, 0, 1], "target": [0, 0, 0], "fov": 45})"),
                HasSubstr("/camera/fov: unknown key 'fov'; allowed keys here: eye, target, up, fov_deg"));
}

TEST(SceneJson, DuplicateKeysAreErrors) {
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "mass": 0.6, "mass": 0.7, "springs": {"stiffness": 100}})")),
                HasSubstr("test.json: /objects/0/mass: duplicate key 'mass'"));
    // The pointer counts array elements, nested arrays included.
    EXPECT_THAT(
        errorOf(scene(kCloth + R"(, {"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5],
        "size": [1, 2]}, "mass": 0.6, "springs": {"stiffness": 100}})")),
        HasSubstr("test.json: /objects/1/generator/size: duplicate key 'size'"));
    // The same key in two different objects is fine.
    EXPECT_NO_THROW(parse(scene(kCloth + ", " + kCloth)));
}

TEST(SceneJson, NumbersOutsideDoubleRangeAreErrors) {
    // JSON cannot spell infinity; 1e999 overflows the parser and must come out as a scene error.
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "mass": 1e999, "springs": {"stiffness": 100}})")),
                HasSubstr("test.json: invalid JSON: line "));
    EXPECT_THAT(errorOf(scene(R"({"generator": {"type": "cloth", "size": [1, 2], "resolution": [4, 5]},
        "mass": -1e999, "springs": {"stiffness": 100}})")),
                HasSubstr("number -1e999 is outside the range of a double"));
}

TEST(SceneJson, CommentsAreAllowed) {
    EXPECT_NO_THROW(parse("// leading comment\n" + scene(kCloth) + "\n/* trailing */"));
}

TEST(SceneJson, MeshErrorsNameSceneAndMesh) {
    try {
        loadScene(kData + "/scene/missing_mesh.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("missing_mesh.json: /objects/0/mesh: "));
        EXPECT_THAT(e.what(), HasSubstr("no_such_mesh.msh: cannot open file"));
    }
    EXPECT_THAT(errorOf(scene(R"({"mesh": "bad_tag_v41.msh", "mass": 1, "springs": {"stiffness": 1}})")),
                HasSubstr("/objects/0/mesh: " + kData + "/mesh/bad_tag_v41.msh:29: node tag 77"));
    EXPECT_THAT(
        errorOf(scene(R"({"mesh": "isolated_node_v22.msh", "mass": 1, "springs": {"stiffness": 1}})")),
        HasSubstr("/objects/0/mesh: isolated_node_v22.msh: vertex 5 belongs to no tetrahedron"));
    try {
        loadScene(kData + "/scene/nope.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("nope.json: cannot open scene file"));
    }
}
