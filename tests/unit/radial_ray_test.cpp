// Radial culling's observer check (glcRadialRayCrossing in shaders/common/radial_sign.glsl, compiled
// as C++; decision 0025, "The winding number") against exact rational arithmetic (GMP): whenever
// the predicate answers (+1, -1 or 0) its answer is the exact one, computed here from the same
// float inputs — on random triangles and rays, on triangles the ray passes close to an edge or a
// vertex, with the observer on or near the triangle's plane, at scales 2^k and far from the origin;
// it decides nearly all well-separated cases (it is not vacuous). And the winding numbers it sums
// (cpu::radialWindingNumbers, the GPU pass's twin) on the sphere generator's closed surface: 1 from
// inside, 0 from outside, -1 for the surface turned inward. These tests also run in
// glcollide_relaxed_float_tests (fast-math, FMA contraction, FTZ/DAZ).

#include "cpu/radial_library.hpp"
#include "cpu/radial_twin.hpp"
#ifndef GLCOLLIDE_RELAXED_FLOAT
#include "scene/scene_detail.hpp"
#endif

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

namespace glcollide {
namespace {

using Vq = std::array<mpq_class, 3>;

Vq exact(const glm::vec3& v) {
    return {mpq_class(static_cast<double>(v.x)), mpq_class(static_cast<double>(v.y)),
            mpq_class(static_cast<double>(v.z))};
}

Vq minus(const Vq& a, const Vq& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

int sign(const mpq_class& v) {
    return sgn(v);
}

/// (a x b) . c, exactly.
mpq_class triple(const Vq& a, const Vq& b, const Vq& c) {
    return (a[1] * b[2] - a[2] * b[1]) * c[0] + (a[2] * b[0] - a[0] * b[2]) * c[1] +
           (a[0] * b[1] - a[1] * b[0]) * c[2];
}

/// The exact crossing of the ray from q along d with (p0, p1, p2): +1, -1, 0, or 2 when the ray
/// touches the triangle's boundary or q lies on its plane (where the predicate must not answer).
int exactCrossing(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& q,
                  const glm::vec3& d) {
    const Vq e0 = minus(exact(p0), exact(q)), e1 = minus(exact(p1), exact(q)),
             e2 = minus(exact(p2), exact(q));
    const Vq dq = exact(d);
    const int s0 = sign(triple(e0, e1, dq)), s1 = sign(triple(e1, e2, dq)), s2 = sign(triple(e2, e0, dq));
    if (s0 * s1 < 0 || s1 * s2 < 0 || s2 * s0 < 0) return 0;
    if (s0 == 0 || s1 == 0 || s2 == 0) return 2;
    const int side = sign(triple(e0, e1, e2));
    if (side == 0) return 2;
    return side == s0 ? s0 : 0;
}

const glm::vec3 kRay = shader::GLC_RADIAL_RAY;

struct Tally {
    int decided = 0, undecided = 0;
};

/// The predicate's answer is the exact one whenever it answers.
void expectAgrees(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& q,
                  Tally& t) {
    const int got = shader::glcRadialRayCrossing(p0, p1, p2, q, kRay);
    if (got == shader::GLC_RADIAL_RAY_UNDECIDED) {
        ++t.undecided;
        return;
    }
    ++t.decided;
    const int want = exactCrossing(p0, p1, p2, q, kRay);
    EXPECT_EQ(got, want) << "triangle (" << p0.x << ", " << p0.y << ", " << p0.z << ") (" << p1.x << ", "
                         << p1.y << ", " << p1.z << ") (" << p2.x << ", " << p2.y << ", " << p2.z << "), q ("
                         << q.x << ", " << q.y << ", " << q.z << ")";
}

TEST(RadialRay, AnswersAreExactOnRandomAndNearDegenerateCases) {
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const auto random = [&](float r) { return glm::vec3(u(rng), u(rng), u(rng)) * r; };
    Tally separated, hard;
    for (int k = -20; k <= 20; k += 4) {
        const float scale = std::ldexp(1.0f, k);
        for (const glm::vec3 origin : {glm::vec3(0.0f), glm::vec3(1.0e5f, -3.0e4f, 2.0e4f) * scale}) {
            for (int i = 0; i < 400; ++i) {
                // Random triangles around the ray's line, q at random.
                const glm::vec3 q = origin + random(scale);
                const glm::vec3 hit = q + kRay * (scale * (0.5f + u(rng)));
                expectAgrees(hit + random(scale), hit + random(scale), hit + random(scale), q, separated);
                // The ray through (or within rounding of) a vertex, an edge's midpoint, and q on the
                // triangle's plane.
                const glm::vec3 a = hit + random(scale), b = hit + random(scale);
                expectAgrees(hit, a, b, q, hard);
                expectAgrees(a, b, hit + (hit - a), q, hard); // the edge (a, 2 hit - a) through about hit
                expectAgrees(a, b, hit, a + 0.5f * (b - a), hard);
                expectAgrees(q, a, b, q, hard); // q a vertex
            }
        }
    }
    std::printf("separated: %d decided, %d undecided; hard: %d decided, %d undecided\n", separated.decided,
                separated.undecided, hard.decided, hard.undecided);
    EXPECT_LT(separated.undecided * 100, separated.decided)
        << "the predicate must decide well-separated cases";
    EXPECT_GT(hard.undecided, 0) << "the hard cases must reach the undecided answer";
}

#ifndef GLCOLLIDE_RELAXED_FLOAT // the scene generators are not linked into the relaxed-float tests
TEST(RadialRay, TheSphereWindsOnceAroundAPointInside) {
    const Body sphere = detail::generateSphere(1.0, 3);
    std::vector<std::uint32_t> faces;
    for (const auto& f : sphere.faces) faces.insert(faces.end(), f.begin(), f.end());
    std::vector<glm::vec3> x(sphere.positions.begin(), sphere.positions.end());
    const std::vector<std::uint32_t> observer(sphere.faces.size(), 0u);
    for (const glm::vec3 q : {glm::vec3(0.0f), glm::vec3(0.3f, -0.2f, 0.5f), glm::vec3(0.0f, 0.0f, 0.95f)}) {
        const auto inside = cpu::radialWindingNumbers(faces, x, observer, {q}, {false});
        EXPECT_EQ(inside.at(0).number, 1);
        EXPECT_FALSE(inside[0].undecided);
        const auto turned = cpu::radialWindingNumbers(faces, x, observer, {q}, {true});
        EXPECT_EQ(turned.at(0).number, -1);
    }
    const auto outside =
        cpu::radialWindingNumbers(faces, x, observer, {glm::vec3(1.5f, 0.2f, -0.1f)}, {false});
    EXPECT_EQ(outside.at(0).number, 0);
    EXPECT_FALSE(outside[0].undecided);
}
#endif

} // namespace
} // namespace glcollide
