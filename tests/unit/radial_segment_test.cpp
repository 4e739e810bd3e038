// Segment observers of radial culling (decision 0025, "Segment observers";
// shaders/common/radial_sign.glsl and radial_footprint.glsl compiled as C++ by cpu/radial_library.hpp)
// against sampled motions in double precision, which share no code with them: every point of a
// moving triangle has its foot (the segment's nearest point) within the triangle's feet interval;
// a triangle proven positive has n(t) . (x - foot(x)) > 0 at every sampled point and time; every
// fiber direction x - foot(x) is inside the footprint cone. Also in the relaxed-float build
// (fast-math, FMA, FTZ/DAZ).

#include "cpu/radial_library.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace glcollide {
namespace {

/// A triangle and a segment observer, each point at t = 0 and t = 1.
struct SegmentMotion {
    std::array<glm::vec3, 5> start, end; // p0, p1, p2, a, b
};

glm::vec2 feet(const SegmentMotion& m) {
    return shader::glcRadialFeet(m.start[0], m.start[1], m.start[2], m.start[3], m.start[4], m.end[0],
                                 m.end[1], m.end[2], m.end[3], m.end[4]);
}

bool positive(const SegmentMotion& m, glm::vec2 f) {
    return shader::glcRadialSegmentPositive(m.start[0], m.start[1], m.start[2], m.start[3], m.start[4],
                                            m.end[0], m.end[1], m.end[2], m.end[3], m.end[4], f.x, f.y);
}

glm::vec4 cone(const SegmentMotion& m, glm::vec2 f) {
    return shader::glcRadialSegmentFootprint(m.start[0], m.start[1], m.start[2], m.start[3], m.start[4],
                                             m.end[0], m.end[1], m.end[2], m.end[3], m.end[4], f);
}

/// A segment of length `length` about a random point, a triangle of size `size` at `distance` from
/// the point at u0 in [-0.3, 1.3] of it (beyond its ends too), facing away from it (so that many
/// are positive), and every point moved by up to `motion`; `offset` moves it all far from the origin.
SegmentMotion randomSegmentMotion(std::mt19937& rng, float length, float distance, float size, float motion,
                                  float offset = 0.0f) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const auto v = [&](float r) { return glm::vec3(u(rng), u(rng), u(rng)) * r; };
    glm::vec3 axis = v(1.0f);
    if (glm::length(axis) < 1e-3f) axis = glm::vec3(1.0f, 0.0f, 0.0f);
    axis = glm::normalize(axis);
    const glm::vec3 origin = v(1.0f) + glm::vec3(offset);
    const glm::vec3 a = origin, b = origin + length * axis;
    const float u0 = 0.8f * u(rng) + 0.5f;
    const glm::vec3 foot = a + std::clamp(u0, 0.0f, 1.0f) * (b - a);
    glm::vec3 out = v(1.0f);
    if (u0 > 0.0f && u0 < 1.0f) out -= glm::dot(out, axis) * axis; // a side fiber: perpendicular
    if (glm::length(out) < 1e-3f) out = glm::cross(axis, glm::vec3(0.3f, 0.5f, 0.8f));
    out = glm::normalize(out);
    const glm::vec3 centre = foot + distance * out;
    // Two directions in the plane facing `out` (tilted a little), corners around the centre wound
    // so that (p1 - p0) x (p2 - p0) points along `out`.
    const glm::vec3 normal = glm::normalize(out + v(0.3f));
    const glm::vec3 e1 = glm::normalize(
        glm::cross(normal, glm::abs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    const glm::vec3 e2 = glm::cross(normal, e1);
    SegmentMotion m;
    m.start = {centre + size * e1, centre + size * (-0.5f * e1 + 0.866f * e2),
               centre + size * (-0.5f * e1 - 0.866f * e2), a, b};
    for (std::size_t i = 0; i < 5; ++i) m.end[i] = m.start[i] + v(motion);
    return m;
}

struct Sample {
    glm::dvec3 x, a, b; // a point of the triangle, and the segment's ends, at one time
    glm::dvec3 normal;  // (p1 - p0) x (p2 - p0) at that time
};

Sample sampleAt(const SegmentMotion& m, int k, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double t = k < 8 ? (k % 2) : u(rng);
    double wa = u(rng), wb = u(rng);
    if (k % 5 == 0) wb = 0.0;
    if (k % 7 == 0) wa = 0.0, wb = 0.0; // a corner
    if (wa + wb > 1.0) wa = 1.0 - wa, wb = 1.0 - wb;
    const auto at = [&](std::size_t i) { return glm::mix(glm::dvec3(m.start[i]), glm::dvec3(m.end[i]), t); };
    Sample s;
    s.x = at(0) + wa * (at(1) - at(0)) + wb * (at(2) - at(0));
    s.a = at(3);
    s.b = at(4);
    s.normal = glm::cross(at(1) - at(0), at(2) - at(0));
    return s;
}

/// The foot's u of x on the segment (a, b), clamped, in double.
double footParameter(const Sample& s) {
    const glm::dvec3 d = s.b - s.a;
    return std::clamp(glm::dot(s.x - s.a, d) / glm::dot(d, d), 0.0, 1.0);
}

struct Scale {
    float length, distance, size, motion, offset;
};

// Lengths 5 cm - 2 m, distances from touching to far, triangles 1 mm - 30 cm, motions 0 - 20 cm,
// near the origin and 1 km from it.
const std::array<Scale, 9> kScales = {{{0.3f, 0.1f, 0.02f, 0.0f, 0.0f},
                                       {0.3f, 0.1f, 0.02f, 0.02f, 0.0f},
                                       {1.0f, 0.05f, 0.01f, 0.005f, 0.0f},
                                       {2.0f, 0.5f, 0.3f, 0.2f, 0.0f},
                                       {0.05f, 0.2f, 0.05f, 0.05f, 0.0f},
                                       {0.5f, 0.005f, 0.001f, 0.001f, 0.0f},
                                       {0.3f, 0.02f, 0.03f, 0.05f, 0.0f},
                                       {0.3f, 0.1f, 0.02f, 0.01f, 1000.0f},
                                       {0.5f, 1.0f, 0.2f, 0.1f, 0.0f}}};

TEST(RadialSegment, EveryPointsFootLiesWithinTheTrianglesFeet) {
    std::mt19937 rng(11);
    int checked = 0, narrow = 0;
    for (const Scale& sc : kScales)
        for (int n = 0; n < 300; ++n) {
            const SegmentMotion m =
                randomSegmentMotion(rng, sc.length, sc.distance, sc.size, sc.motion, sc.offset);
            const glm::vec2 f = feet(m);
            ASSERT_LE(0.0f, f.x);
            ASSERT_LE(f.x, f.y);
            ASSERT_LE(f.y, 1.0f);
            narrow += f.y - f.x < 0.5f ? 1 : 0;
            for (int k = 0; k < 200; ++k) {
                const double footU = footParameter(sampleAt(m, k, rng));
                ASSERT_LE(double{f.x}, footU)
                    << "scale " << sc.length << ", motion " << n << ", sample " << k;
                ASSERT_GE(double{f.y}, footU)
                    << "scale " << sc.length << ", motion " << n << ", sample " << k;
                ++checked;
            }
        }
    EXPECT_EQ(checked, 9 * 300 * 200);
    EXPECT_GT(narrow, 9 * 300 / 2) << "the feet must say more than 'the whole segment' for most motions";
}

TEST(RadialSegment, AStillTriangleBesideTheSegmentHasNarrowFeet) {
    // A 2 cm triangle 10 cm from the middle of a 1 m segment along x: its feet span its own
    // extent along x (about 2 cm of 1 m), widened by the slack only.
    const glm::vec3 a(0.0f), b(1.0f, 0.0f, 0.0f);
    const glm::vec3 p0(0.49f, 0.1f, 0.0f), p1(0.51f, 0.1f, 0.0f), p2(0.5f, 0.1f, 0.02f);
    const glm::vec2 f = shader::glcRadialFeet(p0, p1, p2, a, b, p0, p1, p2, a, b);
    EXPECT_LE(f.x, 0.49f);
    EXPECT_GE(f.y, 0.51f);
    EXPECT_GT(f.x, 0.489f);
    EXPECT_LT(f.y, 0.511f);
    // A segment that turns by 90 degrees within the substep: no bound but the whole segment.
    const glm::vec2 turned = shader::glcRadialFeet(p0, p1, p2, a, b, p0, p1, p2, a, glm::vec3(0, 1, 0));
    EXPECT_EQ(turned.x, 0.0f);
    EXPECT_EQ(turned.y, 1.0f);
}

TEST(RadialSegment, APositiveTriangleFacesAwayFromEveryFootAtEverySampledTime) {
    std::mt19937 rng(12);
    int proven = 0, motions = 0;
    for (const Scale& sc : kScales)
        for (int n = 0; n < 300; ++n, ++motions) {
            const SegmentMotion m =
                randomSegmentMotion(rng, sc.length, sc.distance, sc.size, sc.motion, sc.offset);
            if (!positive(m, feet(m))) continue;
            ++proven;
            for (int k = 0; k < 200; ++k) {
                const Sample s = sampleAt(m, k, rng);
                const double footU = footParameter(s);
                const glm::dvec3 foot = s.a + footU * (s.b - s.a);
                ASSERT_GT(glm::dot(s.normal, s.x - foot), 0.0)
                    << "scale " << sc.length << "/" << sc.distance << ", motion " << n << ", sample " << k;
            }
        }
    RecordProperty("proven_positive", proven);
    EXPECT_GT(proven, motions / 3) << "triangles facing away from the segment are mostly proven positive";
}

TEST(RadialSegment, TheConeHoldsEveryFiberDirection) {
    std::mt19937 rng(13);
    int bounded = 0, motions = 0;
    for (const Scale& sc : kScales)
        for (int n = 0; n < 300; ++n, ++motions) {
            const SegmentMotion m =
                randomSegmentMotion(rng, sc.length, sc.distance, sc.size, sc.motion, sc.offset);
            const glm::vec2 f = feet(m);
            const glm::vec4 c = cone(m, f);
            if (c.w <= -1.0f) continue; // every direction
            ++bounded;
            const glm::dvec3 axis(c.x, c.y, c.z);
            for (int k = 0; k < 200; ++k) {
                const Sample s = sampleAt(m, k, rng);
                const glm::dvec3 d = s.x - (s.a + footParameter(s) * (s.b - s.a));
                const double cosine = glm::dot(axis, d) / (glm::length(axis) * glm::length(d));
                // 1e-12: the double evaluation of this check itself.
                ASSERT_GE(cosine, double{c.w} - 1e-12)
                    << "scale " << sc.length << "/" << sc.distance << ", motion " << n << ", sample " << k;
            }
        }
    RecordProperty("bounded_cones", bounded);
    EXPECT_GT(bounded, motions / 2);
}

TEST(RadialSegment, APointLikeSegmentProvesNoMoreThanItsPoint) {
    // A segment of no length is the point observer; its test (coefficients minus twice their error)
    // is the point test's with more margin, never less.
    std::mt19937 rng(14);
    int both = 0;
    for (const Scale& sc : kScales)
        for (int n = 0; n < 200; ++n) {
            SegmentMotion m = randomSegmentMotion(rng, sc.length, sc.distance, sc.size, sc.motion, sc.offset);
            m.start[4] = m.start[3];
            m.end[4] = m.end[3];
            const glm::vec2 f = feet(m);
            EXPECT_EQ(f.x, 0.0f);
            EXPECT_EQ(f.y, 1.0f);
            const bool segment = positive(m, f);
            const bool point = shader::glcRadialPositive(m.start[0], m.start[1], m.start[2], m.start[3],
                                                         m.end[0], m.end[1], m.end[2], m.end[3]);
            if (segment) {
                EXPECT_TRUE(point) << "scale " << sc.length << ", motion " << n;
            }
            both += segment && point ? 1 : 0;
        }
    EXPECT_GT(both, 0);
}

TEST(RadialSegment, ATriangleTheSegmentPiercesIsNeitherPositiveNorBounded) {
    // The segment passes through the triangle's middle: no foot direction bound, not positive.
    const glm::vec3 a(0.0f, -0.5f, 0.0f), b(0.0f, 0.5f, 0.0f);
    const glm::vec3 p0(0.1f, 0.0f, 0.0f), p1(-0.05f, 0.0f, 0.08f), p2(-0.05f, 0.0f, -0.08f);
    for (int flip = 0; flip < 2; ++flip) {
        const glm::vec3 q1 = flip ? p2 : p1, q2 = flip ? p1 : p2;
        const glm::vec2 f = shader::glcRadialFeet(p0, q1, q2, a, b, p0, q1, q2, a, b);
        EXPECT_FALSE(shader::glcRadialSegmentPositive(p0, q1, q2, a, b, p0, q1, q2, a, b, f.x, f.y));
        EXPECT_EQ(shader::glcRadialSegmentFootprint(p0, q1, q2, a, b, p0, q1, q2, a, b, f).w, -1.0f);
    }
}

} // namespace
} // namespace glcollide
