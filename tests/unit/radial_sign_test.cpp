// Radial view-based culling's classification (shaders/common/radial_sign.glsl, compiled as C++ by
// cpu/radial_library.hpp) against exact rational arithmetic (GMP): the Bernstein coefficients
// reproduce the cubic phi(t) = n(t) . (p0(t) - q(t)) exactly; a triangle proven positive has four
// exactly positive coefficients (so phi > 0 on the whole substep) on random, near-coplanar,
// crossing, degenerate, scaled and far-from-the-origin cases; and a well-separated case is proven
// (the filter is not vacuous). The same tests run in glcollide_relaxed_float_tests (fast-math, FMA
// contraction, FTZ/DAZ), where the proof must hold too.

#include "cpu/oracle/exact_radial.hpp"
#include "cpu/radial_library.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <random>

namespace glcollide {
namespace {

/// A triangle and an observer at both ends of the substep.
struct Case {
    std::array<glm::vec3, 4> start, end; // p0, p1, p2, q
};

/// The four exact Bernstein coefficients (times 1, 3, 3, 1).
std::array<mpq_class, 4> exactCoefficients(const Case& c) {
    return cpu::exactRadialCoefficients(c.start, c.end);
}

/// True when every exact coefficient exceeds `ratio` times its products' magnitude sum.
bool wellSeparated(const Case& c, double ratio) {
    const std::array<mpq_class, 4> m = cpu::exactRadialMagnitudes(c.start, c.end);
    const std::array<mpq_class, 4> b = exactCoefficients(c);
    for (int i = 0; i < 4; ++i)
        if (!(b[i] > mpq_class(ratio) * m[i])) return false;
    return true;
}

/// k / n, canonical (GMP's arithmetic needs it).
mpq_class fraction(int k, int n) {
    mpq_class q(k, n);
    q.canonicalize();
    return q;
}

/// phi(t) evaluated exactly from the interpolated points.
mpq_class exactPhi(const Case& c, const mpq_class& t) {
    return cpu::exactRadialPhi(c.start, c.end, t);
}

bool proven(const Case& c) {
    return shader::glcRadialPositive(c.start[0], c.start[1], c.start[2], c.start[3], c.end[0], c.end[1],
                                     c.end[2], c.end[3]);
}

bool exactlyPositive(const Case& c) {
    return cpu::exactlyRadialPositive(c.start, c.end);
}

/// A triangle of size ~`size` around `centre`, the observer `distance` below its plane's normal
/// side at t = 0, everything moved by up to `motion` (random) over the substep.
Case randomCase(std::mt19937& rng, glm::vec3 centre, float size, float distance, float motion) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const auto jitter = [&](float r) { return glm::vec3(u(rng), u(rng), u(rng)) * r; };
    Case c;
    c.start[0] = centre + glm::vec3(-size, -size, 0.0f) + jitter(0.2f * size);
    c.start[1] = centre + glm::vec3(size, -size, 0.0f) + jitter(0.2f * size);
    c.start[2] = centre + glm::vec3(0.0f, size, 0.0f) + jitter(0.2f * size);
    // n = (p1 - p0) x (p2 - p0) points along +z: a positive triangle has the observer below.
    c.start[3] = centre + glm::vec3(0.0f, 0.0f, -distance) + jitter(0.5f * size);
    for (int i = 0; i < 4; ++i) c.end[i] = c.start[i] + jitter(motion);
    return c;
}

TEST(RadialSign, BernsteinCoefficientsReproduceTheCubicExactly) {
    std::mt19937 rng(11);
    for (int n = 0; n < 50; ++n) {
        const Case c = randomCase(rng, glm::vec3(0.3f, -0.2f, 0.1f), 0.05f, 0.02f, 0.08f);
        const std::array<mpq_class, 4> b = exactCoefficients(c); // B0, 3 B1, 3 B2, B3
        for (int k = 0; k <= 7; ++k) {
            const mpq_class t = fraction(k, 7), s = 1 - t;
            const mpq_class bernstein =
                b[0] * s * s * s + b[1] * t * s * s + b[2] * t * t * s + b[3] * t * t * t;
            EXPECT_EQ(bernstein, exactPhi(c, t)) << "case " << n << ", t = " << k << "/7";
        }
    }
}

/// Runs `c` (and every power-of-two scaling 2^k of it in `scales`): proven implies exactly
/// positive. Returns how many were proven.
int expectSound(const Case& c, const char* family, int index) {
    const bool p = proven(c);
    if (p) {
        EXPECT_TRUE(exactlyPositive(c))
            << family << " " << index << ": proven positive but a coefficient is <= 0";
        for (int k = 0; k <= 8; ++k) EXPECT_GT(sgn(exactPhi(c, fraction(k, 8))), 0) << family << " " << index;
    }
    return p ? 1 : 0;
}

TEST(RadialSign, ProvenPositiveIsExactlyPositiveOnHardFamilies) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    int provenCount = 0, cases = 0;
    // Near-coplanar: the observer in the triangle's plane at t = 0 (an affine combination of the
    // vertices, rounded to float), nudged by a few ulps; small or no motion.
    for (int n = 0; n < 4000; ++n, ++cases) {
        Case c = randomCase(rng, glm::vec3(u(rng), u(rng), u(rng)), 0.1f, 0.0f, n % 2 == 0 ? 0.0f : 1e-6f);
        const float wa = 0.25f + 0.1f * u(rng), wb = 0.25f + 0.1f * u(rng);
        glm::vec3 q = c.start[0] + wa * (c.start[1] - c.start[0]) + wb * (c.start[2] - c.start[0]);
        for (int k = 0; k < n % 5; ++k) q.z = std::nextafter(q.z, n % 3 == 0 ? 1.0f : -1.0f);
        c.start[3] = q;
        if (n % 2 == 0) c.end = c.start;
        provenCount += expectSound(c, "near-coplanar", n);
    }
    // Crossing: the observer passes from below the triangle's centre to above it during the
    // substep (phi changes sign), the triangle still or drifting by less than the crossing.
    for (int n = 0; n < 2000; ++n, ++cases) {
        Case c = randomCase(rng, glm::vec3(u(rng), u(rng), u(rng)), 0.05f, 0.01f, n % 2 == 0 ? 0.0f : 1e-3f);
        const glm::vec3 centre = (c.start[0] + c.start[1] + c.start[2]) / 3.0f;
        c.start[3] = centre - glm::vec3(0.0f, 0.0f, 0.01f);
        c.end[3] = centre + glm::vec3(0.0f, 0.0f, 0.01f + 0.01f * std::abs(u(rng)));
        EXPECT_FALSE(proven(c)) << "crossing " << n;
        provenCount += expectSound(c, "crossing", n);
    }
    // Degenerate triangles (a repeated or collinear vertex): phi is 0, never proven.
    for (int n = 0; n < 1000; ++n, ++cases) {
        Case c = randomCase(rng, glm::vec3(u(rng), u(rng), u(rng)), 0.05f, 0.01f, 0.01f);
        c.start[2] = n % 2 == 0 ? c.start[1] : c.start[0] + 2.0f * (c.start[1] - c.start[0]);
        c.end[2] = n % 2 == 0 ? c.end[1] : c.end[0] + 2.0f * (c.end[1] - c.end[0]);
        provenCount += expectSound(c, "degenerate", n);
        if (n % 2 == 0) {
            EXPECT_FALSE(proven(c)) << "repeated vertex " << n;
        }
    }
    // Every magnitude float allows, subnormal and overflowing ones included: 2^k for k = -140 ... 120.
    for (int k = -140; k <= 120; k += 4) {
        for (int n = 0; n < 40; ++n, ++cases) {
            Case c = randomCase(rng, glm::vec3(u(rng), u(rng), u(rng)), 0.05f,
                                0.01f * static_cast<float>(1 + n % 3), 0.02f);
            for (int i = 0; i < 4; ++i)
                c.start[i] = std::ldexp(1.0f, k) * c.start[i], c.end[i] = std::ldexp(1.0f, k) * c.end[i];
            provenCount += expectSound(c, "scaled", k * 100 + n);
        }
    }
    // Random motion, anything goes.
    for (int n = 0; n < 4000; ++n, ++cases) {
        Case c = randomCase(rng, glm::vec3(u(rng), u(rng), u(rng)), 0.05f, 0.02f * u(rng), 0.05f);
        provenCount += expectSound(c, "random", n);
    }
    RecordProperty("proven", provenCount);
    RecordProperty("cases", cases);
    EXPECT_GT(provenCount, 0);
}

// Not vacuous: where every exact coefficient exceeds 10^-4 of its products' magnitude sum (the
// filter's bound is about 2 * 10^-6 of it), the triangle is proven positive, also when the
// triangle is small and far from the origin (the differences keep the bound relative to the
// triangle, not to its coordinates).
TEST(RadialSign, WellSeparatedCasesAreProvenAnywhere) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    struct Placement {
        float offset, size, distance; // m
    };
    for (const Placement& at : {Placement{0.0f, 0.01f, 0.05f}, Placement{1.0f, 0.01f, 0.05f},
                                Placement{1000.0f, 0.01f, 0.05f}, Placement{1.0e5f, 1.0f, 5.0f}}) {
        int separated = 0, proven_ = 0;
        for (int n = 0; n < 500; ++n) {
            const glm::vec3 centre = at.offset * glm::vec3(u(rng), u(rng), u(rng));
            const Case c = randomCase(rng, centre, at.size, at.distance, 0.2f * at.size);
            if (!wellSeparated(c, 1e-4)) continue;
            ++separated;
            EXPECT_TRUE(proven(c)) << "offset " << at.offset << " case " << n;
            proven_ += proven(c) ? 1 : 0;
        }
        EXPECT_GT(separated, 400) << "offset " << at.offset << ": the family is meant to be well separated";
        EXPECT_EQ(proven_, separated) << "offset " << at.offset;
    }
}

} // namespace
} // namespace glcollide
