// Radial view-based culling's footprint cones (shaders/common/radial_footprint.glsl, compiled as
// C++ by cpu/radial_library.hpp) against sampled motions in double precision: every direction in
// which a point of the moving triangle lies from the moving observer is inside the cone, and two
// cones said not to meet are disjoint (the angle between their axes exceeds the sum of their
// half-angles, in double). Also in the relaxed-float build (fast-math, FMA, FTZ/DAZ).

#include "cpu/radial_library.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <random>

namespace glcollide {
namespace {

struct Motion {
    std::array<glm::vec3, 4> start, end; // p0, p1, p2, q
};

glm::vec4 footprint(const Motion& m) {
    return shader::glcRadialFootprint(m.start[0], m.start[1], m.start[2], m.start[3], m.end[0], m.end[1],
                                      m.end[2], m.end[3]);
}

Motion randomMotion(std::mt19937& rng, float distance, float size, float motion) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const auto v = [&](float r) { return glm::vec3(u(rng), u(rng), u(rng)) * r; };
    Motion m;
    const glm::vec3 q = v(1.0f);
    glm::vec3 centre = v(1.0f);
    if (glm::length(centre) == 0.0f) centre = glm::vec3(1.0f, 0.0f, 0.0f);
    centre = q + distance * glm::normalize(centre);
    for (int i = 0; i < 3; ++i) m.start[i] = centre + v(size);
    m.start[3] = q;
    for (int i = 0; i < 4; ++i) m.end[i] = m.start[i] + v(motion);
    return m;
}

/// Largest violation of "every sampled direction is in the cone" (<= 0: none), in cosine units.
double worstOutside(const Motion& m, const glm::vec4& cone, std::mt19937& rng) {
    if (cone.w <= -1.0f) return -1.0; // every direction
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::dvec3 axis(cone.x, cone.y, cone.z);
    double worst = -1.0;
    for (int k = 0; k < 400; ++k) {
        // t, then a point of the triangle at t (corners, edges and interior all sampled), and q(t).
        const double t = k < 8 ? (k % 2) : u(rng);
        double a = u(rng), b = u(rng);
        if (k % 5 == 0) b = 0.0;
        if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
        const auto at = [&](int i) { return glm::mix(glm::dvec3(m.start[i]), glm::dvec3(m.end[i]), t); };
        const glm::dvec3 x = at(0) + a * (at(1) - at(0)) + b * (at(2) - at(0));
        const glm::dvec3 d = x - at(3);
        const double cosine = glm::dot(axis, d) / (glm::length(axis) * glm::length(d));
        worst = std::max(worst, static_cast<double>(cone.w) - cosine);
    }
    return worst;
}

TEST(RadialFootprint, HoldsEveryDirectionOfTheMovingTriangle) {
    std::mt19937 rng(3);
    int everywhere = 0, cases = 0;
    for (const float distance : {0.05f, 0.5f, 5.0f})
        for (const float size : {0.001f, 0.05f, 0.3f})
            for (const float motion : {0.0f, 0.01f, 0.2f})
                for (int n = 0; n < 100; ++n, ++cases) {
                    const Motion m = randomMotion(rng, distance, size, motion);
                    const glm::vec4 cone = footprint(m);
                    everywhere += cone.w <= -1.0f ? 1 : 0;
                    EXPECT_LE(worstOutside(m, cone, rng), 0.0) << "distance " << distance << " size " << size
                                                               << " motion " << motion << " case " << n;
                }
    RecordProperty("everywhere", everywhere);
    // A small triangle far away has a narrow cone; only near or large ones span everything.
    EXPECT_LT(everywhere, cases / 4);
}

TEST(RadialFootprint, AnObserverInsideTheSweptTriangleSeesEverything) {
    Motion m;
    m.start = {glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -0.5f)};
    m.end = m.start;
    m.end[3] = glm::vec3(0, 0, 0.5f); // passes through the triangle
    EXPECT_EQ(footprint(m).w, -1.0f);
    m.end[3] = m.start[3]; // stays below: a cone, narrower than a half-space
    const glm::vec4 below = footprint(m);
    EXPECT_GT(below.w, 0.0f);
    EXPECT_GT(below.z, 0.9f); // looking up
    // A point observer exactly at a vertex: no direction for it, everything.
    m.start[3] = m.end[3] = m.start[0];
    EXPECT_EQ(footprint(m).w, -1.0f);
}

TEST(RadialFootprint, ConesSaidNotToMeetAreDisjoint) {
    std::mt19937 rng(9);
    int apart = 0, together = 0;
    for (int n = 0; n < 20000; ++n) {
        const glm::vec4 a = footprint(randomMotion(rng, 1.0f, 0.2f, 0.05f));
        const glm::vec4 b = footprint(randomMotion(rng, 1.0f, 0.2f, 0.05f));
        if (shader::glcRadialFootprintsMeet(a, b)) {
            ++together;
            continue;
        }
        ++apart;
        ASSERT_GT(a.w, -1.0f);
        ASSERT_GT(b.w, -1.0f);
        const glm::dvec3 axisA(a.x, a.y, a.z), axisB(b.x, b.y, b.z);
        const double axes = std::acos(
            std::clamp(glm::dot(axisA, axisB) / (glm::length(axisA) * glm::length(axisB)), -1.0, 1.0));
        EXPECT_GT(axes, std::acos(static_cast<double>(a.w)) + std::acos(static_cast<double>(b.w)))
            << "case " << n;
    }
    // Random cones of about 15 degrees all over the sphere: both answers occur (measured: 786 of
    // 20,000 pairs meet).
    EXPECT_GT(apart, 10000);
    EXPECT_GT(together, 200);
    // Two triangles sharing a vertex, seen by one observer, share that direction: they meet.
    for (int n = 0; n < 1000; ++n) {
        const Motion m = randomMotion(rng, 1.0f, 0.2f, 0.05f);
        Motion other = randomMotion(rng, 1.0f, 0.2f, 0.05f);
        other.start[0] = m.start[1], other.end[0] = m.end[1];
        other.start[3] = m.start[3], other.end[3] = m.end[3];
        EXPECT_TRUE(shader::glcRadialFootprintsMeet(footprint(m), footprint(other))) << "case " << n;
    }
    // Everything meets everything; a cone meets itself.
    const glm::vec4 cone = footprint(randomMotion(rng, 1.0f, 0.1f, 0.0f));
    EXPECT_TRUE(shader::glcRadialFootprintsMeet(cone, cone));
    EXPECT_TRUE(shader::glcRadialFootprintsMeet(cone, shader::glcRadialEverywhere()));
}

} // namespace
} // namespace glcollide
