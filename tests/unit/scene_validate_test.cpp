// validateScene on scenes assembled in code.
#include <glcollide/error.hpp>
#include <glcollide/scene.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <limits>

using namespace glcollide;
using ::testing::HasSubstr;

namespace {

Scene twoNodes() {
    Scene s;
    s.name = "code";
    Body b;
    b.name = "pair";
    b.positions = {{0, 0, 0}, {1, 0, 0}};
    b.velocities = {glm::dvec3(0), glm::dvec3(0)};
    b.masses = {1, 1};
    b.pinned = {0, 0};
    Spring sp;
    sp.a = 0;
    sp.b = 1;
    sp.restLength = 1;
    sp.stiffness = 10;
    b.springs = {sp};
    s.bodies = {b};
    return s;
}

std::string errorAfter(const std::function<void(Scene&)>& change) {
    Scene s = twoNodes();
    change(s);
    try {
        validateScene(s);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST(SceneValidate, AcceptsAValidScene) {
    EXPECT_NO_THROW(validateScene(twoNodes()));
}

TEST(SceneValidate, RejectsBrokenInvariants) {
    EXPECT_THAT(errorAfter([](Scene& s) { s.collision.detection = Detection::Discrete; }),
                HasSubstr("intersection_free needs collision.detection continuous"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.collision.responseIterations = -1; }),
                HasSubstr("collision.response_iterations must be 1 … 64 (or 0: automatic), got -1"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].masses.pop_back(); }),
                HasSubstr("body 0 'pair': per-node vectors differ in length"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].masses[1] = 0; }),
                HasSubstr("body 0 'pair': node 1: mass"));
    EXPECT_THAT(
        errorAfter([](Scene& s) { s.bodies[0].positions[0].x = std::numeric_limits<double>::quiet_NaN(); }),
        HasSubstr("node 0: position is not finite"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].springs[0].b = 0; }),
                HasSubstr("spring 0: both ends are node 0"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].springs[0].b = 2; }),
                HasSubstr("spring 0: end index out of range"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].springs[0].restLength = 0; }),
                HasSubstr("spring 0: rest length"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].springs[0].stiffness = -1; }),
                HasSubstr("spring 0: stiffness"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].springs[0].damping = -1; }),
                HasSubstr("spring 0: damping"));
    EXPECT_THAT(errorAfter([](Scene& s) {
                    s.bodies[0].faces = {{0, 1, 2}};
                }),
                HasSubstr("face 0: index 2 out of range"));
    EXPECT_THAT(errorAfter([](Scene& s) {
                    s.bodies[0].tets = {{0, 1, 0, 5}};
                }),
                HasSubstr("tet 0: index 5 out of range"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.time.dt = 0; }), HasSubstr("scene 'code': time.dt"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.time.frames = 0; }), HasSubstr("time.frames"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.time.substeps = -1; }), HasSubstr("time.substeps"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.ground.restitution = 2; }), HasSubstr("ground.restitution"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.ground.friction = -1; }), HasSubstr("ground.friction"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.wind.drag = -1; }), HasSubstr("wind.drag"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.collision.friction = -1; }), HasSubstr("collision.friction"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.collision.friction = std::numeric_limits<double>::quiet_NaN(); }),
                HasSubstr("collision.friction"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.damping = -1; }), HasSubstr("damping"));
    EXPECT_THAT(errorAfter([](Scene& s) { s.bodies[0].positions.clear(); }), HasSubstr("has no nodes"));
}
