#pragma once
// The worst float evaluation of the orient3d filter that the soundness argument admits
// (docs/narrow-phase.md, "Why the filter is sound on any conforming device"), and inputs whose
// exact determinant lies just above a chosen multiple of u * permanent or of 2^-126 * max(M, 1)^2.
// Used by tests/unit/shader_library_test.cpp, which feeds the adversary's (det, permanent, max(M, 1))
// to the library's own decision (glcOrient3dFilter, through the C++ view's estimate seam), in both
// C++ builds.
//
// The adversary is a conforming device that is as unlucky as GLSL allows: each + - * result is
// one of the two floats around the exact value (any rounding mode, so an error below one ulp, in
// the direction that pushes det where it should not go), a result or input below 2^-126 may read
// as 0 (flushing), and the sum may be evaluated as written or as the expanded sum of the six
// monomials, largest first so that it passes through the most additions (reassociation). The
// permanent is rounded down, which shrinks the bound. Every value is computed here in exact
// rationals (GMP) and rounded to float from integers: the relaxed build's fast-math cannot touch it.

#include <glm/vec3.hpp>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <optional>
#include <random>
#include <utility>
#include <vector>

namespace glcollide::test {

using glm::vec3;

/// The float's exact value, from its bits (the relaxed build runs with DAZ, which would read a
/// denormal as 0 in any float -> double conversion).
inline mpq_class exactFloat(float f) {
    const std::uint32_t b = std::bit_cast<std::uint32_t>(f);
    const std::uint32_t e = (b >> 23) & 0xffu, m = (b & 0x7fffffu) | (e != 0 ? 0x800000u : 0u);
    const int exponent = (e == 0 ? 1 : static_cast<int>(e)) - 150;
    mpq_class v = mpz_class(m);
    if (exponent >= 0)
        v *= mpq_class(mpz_class(1) << static_cast<unsigned>(exponent));
    else
        v /= mpq_class(mpz_class(1) << static_cast<unsigned>(-exponent));
    return (b >> 31) ? mpq_class(-v) : v;
}

inline mpq_class powerOfTwo(int e) {
    return e >= 0 ? mpq_class(mpz_class(1) << static_cast<unsigned>(e))
                  : mpq_class(mpz_class(1), mpz_class(1) << static_cast<unsigned>(-e));
}

/// The float next to `v` in `direction` (+1: the least float >= v; -1: the greatest float <= v),
/// built from integers. |v| must stay below 2^128.
inline float floatToward(const mpq_class& v, int direction) {
    if (sgn(v) == 0) return 0.0f;
    const bool negative = sgn(v) < 0;
    const mpq_class magnitude = abs(v);
    // e = floor(log2 |v|): start from the bit lengths, then correct by comparison.
    int e = static_cast<int>(mpz_sizeinbase(magnitude.get_num_mpz_t(), 2)) -
            static_cast<int>(mpz_sizeinbase(magnitude.get_den_mpz_t(), 2));
    while (magnitude < powerOfTwo(e)) --e;
    while (magnitude >= powerOfTwo(e + 1)) ++e;
    int quantum = std::max(e - 23, -149); // the spacing of floats at |v| (denormals: 2^-149)
    const mpq_class scaled = magnitude / powerOfTwo(quantum);
    mpz_class m = scaled.get_num() / scaled.get_den(); // floor
    const bool inexact = mpq_class(m) != scaled;
    // Rounding the magnitude up moves v away from 0: up for positive v, down for negative v.
    if (inexact && (direction > 0) != negative) m += 1;
    if (m == (mpz_class(1) << 24)) {
        m = mpz_class(1) << 23;
        ++quantum;
    }
    const auto mantissa = static_cast<std::uint32_t>(m.get_ui());
    const std::uint32_t bits =
        mantissa < (1u << 23) ? mantissa // a denormal (quantum is -149)
                              : (static_cast<std::uint32_t>(quantum + 150) << 23) | (mantissa - (1u << 23));
    return std::bit_cast<float>(bits | (negative ? 0x80000000u : 0u));
}

/// The float nearest to `v` (ties either way: the generator only needs a close float).
inline float floatNearest(const mpq_class& v) {
    const float down = floatToward(v, -1), up = floatToward(v, 1);
    return abs(v - exactFloat(down)) <= abs(exactFloat(up) - v) ? down : up;
}

/// Nonzero and below 2^-126 in magnitude: a denormal, which a conforming device may flush.
inline bool flushable(float f) {
    const std::uint32_t b = std::bit_cast<std::uint32_t>(f) & 0x7fffffffu;
    return b != 0 && b < 0x00800000u;
}

struct ExactOrient {
    mpq_class det, permanent;
};

/// det[b-a, c-a, d-a] and its permanent, exactly.
inline ExactOrient exactOrient3d(vec3 a, vec3 b, vec3 c, vec3 d) {
    std::array<mpq_class, 9> r;
    for (int k = 0; k < 3; ++k) {
        r[k] = exactFloat(b[k]) - exactFloat(a[k]);
        r[3 + k] = exactFloat(c[k]) - exactFloat(a[k]);
        r[6 + k] = exactFloat(d[k]) - exactFloat(a[k]);
    }
    ExactOrient o;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        o.det += r[i] * (r[3 + j] * r[6 + k] - r[3 + k] * r[6 + j]);
        o.permanent += abs(r[i]) * (abs(r[3 + j] * r[6 + k]) + abs(r[3 + k] * r[6 + j]));
    }
    return o;
}

/// How the adversary groups the sum: as the library writes it (cofactor expansion along the first
/// row), or expanded into six monomials summed largest first (each passes through up to 5 sums).
enum class Grouping { AsWritten, ExpandedLargestFirst };

/// One conforming result of an operation whose exact value is `exact`: the float on the side
/// that moves det towards `push`, given `effect`, the sign of d(det)/d(result); a result below
/// 2^-126 becomes 0 when that helps more.
inline float adversarialResult(const mpq_class& exact, int effect, int push) {
    const int want = effect * push; // +1: a larger result helps; -1: a smaller one
    float r = floatToward(exact, want >= 0 ? 1 : -1);
    if (want != 0 && flushable(r) && want * -sgn(exactFloat(r)) > 0) r = 0.0f;
    return r;
}

inline int sign(const mpq_class& v) {
    return sgn(v) > 0 ? 1 : (sgn(v) < 0 ? -1 : 0);
}

/// The filter's (det, permanent, max(M, 1)) as the adversary computes them, pushing det towards
/// `push` (+1 or -1).
inline vec3 adversarialEstimate(vec3 a, vec3 b, vec3 c, vec3 d, int push, Grouping grouping) {
    // Flushed inputs: a denormal coordinate may read as 0 in every operation; flush those whose
    // flushing moves the exact determinant of the inputs as read towards push.
    std::array<vec3, 4> p = {a, b, c, d};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            if (!flushable(p[i][k])) continue;
            const mpq_class before = exactOrient3d(p[0], p[1], p[2], p[3]).det;
            std::array<vec3, 4> q = p;
            q[i][k] = 0.0f;
            if (push * sgn(exactOrient3d(q[0], q[1], q[2], q[3]).det - before) > 0) p = q;
        }
    // Differences, each pushed by the sign of its cofactor (det is linear in each row).
    std::array<mpq_class, 9> exactRows;
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) exactRows[3 * r + k] = exactFloat(p[r + 1][k]) - exactFloat(p[0][k]);
    auto cofactor = [&](int r, int k) -> mpq_class { // d(det)/d(row r, column k), exactly
        const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        return exactRows[3 * r1 + k1] * exactRows[3 * r2 + k2] -
               exactRows[3 * r1 + k2] * exactRows[3 * r2 + k1];
    };
    std::array<float, 9> row;
    for (int i = 0; i < 9; ++i) row[i] = adversarialResult(exactRows[i], sign(cofactor(i / 3, i % 3)), push);
    const auto x = [&](int i) { return exactFloat(row[i]); };
    auto product = [&](float f, float g, int effect) {
        return adversarialResult(exactFloat(f) * exactFloat(g), effect, push);
    };
    auto sum = [&](float f, float g) { return adversarialResult(exactFloat(f) + exactFloat(g), 1, push); };

    float det = 0.0f;
    if (grouping == Grouping::AsWritten) {
        // ba.x * (ca.y * da.z - ca.z * da.y) + ba.y * (...) + ba.z * (...), as in glcOrient3dEstimate.
        std::array<float, 3> term;
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3, k = (i + 2) % 3, s = sign(x(i));
            const float left = product(row[3 + j], row[6 + k], s),
                        right = product(row[3 + k], row[6 + j], -s);
            const float minor = adversarialResult(exactFloat(left) - exactFloat(right), s, push);
            term[i] = product(row[i], minor, 1);
        }
        det = sum(sum(term[0], term[1]), term[2]);
    } else {
        // Six signed monomials (ba_i * ca_j) * da_k, summed largest first, left to right.
        std::vector<std::pair<mpq_class, float>> monomials;
        for (int i = 0; i < 3; ++i)
            for (int flip = 0; flip < 2; ++flip) {
                const int j = (i + 1 + flip) % 3, k = (i + 2 - flip) % 3, s = flip == 0 ? 1 : -1;
                const mpq_class exact = s * x(i) * x(3 + j) * x(6 + k);
                const int effectOfPair = s * sign(x(6 + k));
                const float pair = product(row[i], row[3 + j], effectOfPair);
                float monomial = product(pair, row[6 + k], s);
                monomial = s > 0 ? monomial : -monomial;
                monomials.emplace_back(abs(exact), monomial);
            }
        std::stable_sort(monomials.begin(), monomials.end(),
                         [](const auto& l, const auto& r) { return l.first > r.first; });
        det = monomials[0].second;
        for (std::size_t i = 1; i < monomials.size(); ++i) det = sum(det, monomials[i].second);
    }

    // The permanent, every operation rounded down (or flushed): the smallest bound allowed.
    auto down = [](const mpq_class& v) { return adversarialResult(v, 1, -1); };
    auto absolute = [](float f) { return f < 0.0f ? -f : f; };
    float permanent = 0.0f;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        const float l = down(abs(x(3 + j) * x(6 + k))), r = down(abs(x(3 + k) * x(6 + j)));
        const float t = down(abs(x(i)) * exactFloat(down(exactFloat(l) + exactFloat(r))));
        permanent = down(exactFloat(permanent) + exactFloat(t));
    }
    // max(M, 1) is exact (comparisons).
    mpq_class largest = 1;
    float m = 1.0f;
    for (float f : row)
        if (abs(exactFloat(f)) > largest) {
            largest = abs(exactFloat(f));
            m = absolute(f);
        }
    return {det, permanent, m};
}

// ---------------------------------------------------------------------------------------------
// Inputs

struct Quad {
    vec3 a, b, c, d;
};

/// Moves d along the axis of the largest normal component (and, when one float step there is
/// too coarse, the next one) so that the exact det / (u * permanent) lies in
/// direction * (k, k + 1): just above k u P, with the chosen sign. Empty when no float position
/// within a few steps lands there.
inline std::optional<Quad> placeAboveMultipleOfUP(Quad x, int k, int direction) {
    const mpq_class u = powerOfTwo(-23);
    std::array<mpq_class, 3> ba, ca, n;
    for (int i = 0; i < 3; ++i) {
        ba[i] = exactFloat(x.b[i]) - exactFloat(x.a[i]);
        ca[i] = exactFloat(x.c[i]) - exactFloat(x.a[i]);
    }
    for (int i = 0; i < 3; ++i) n[i] = ba[(i + 1) % 3] * ca[(i + 2) % 3] - ba[(i + 2) % 3] * ca[(i + 1) % 3];
    std::array<int, 3> axes = {0, 1, 2};
    std::sort(axes.begin(), axes.end(), [&](int l, int r) { return abs(n[l]) > abs(n[r]); });
    if (sgn(n[axes[0]]) == 0) return std::nullopt;
    auto inWindow = [&](const Quad& y) {
        const ExactOrient o = exactOrient3d(y.a, y.b, y.c, y.d);
        if (sgn(o.permanent) == 0) return false;
        const mpq_class ratio = direction * o.det / (u * o.permanent);
        return ratio > k && ratio < k + 1;
    };
    // Aim at the middle of the window on the main axis (the permanent moves a little with d).
    for (int round = 0; round < 3; ++round) {
        const ExactOrient o = exactOrient3d(x.a, x.b, x.c, x.d);
        const mpq_class target = direction * (k + mpq_class(1, 2)) * u * o.permanent;
        const int i = axes[0];
        x.d[i] = floatNearest(exactFloat(x.d[i]) + (target - o.det) / n[i]);
    }
    if (inWindow(x)) return x;
    // Then float steps on the two largest axes. det is linear in d, so candidates are screened
    // with det0 + n . (d - d0) and the permanent at d0 (it moves by a few ulps), then checked.
    const ExactOrient o = exactOrient3d(x.a, x.b, x.c, x.d);
    auto stepped = [](float f, int steps) {
        for (int s = 0; s < std::abs(steps); ++s)
            f = floatToward(exactFloat(f) + (steps > 0 ? 1 : -1) * powerOfTwo(-200), steps);
        return f;
    };
    for (int s0 = -8; s0 <= 8; ++s0)
        for (int s1 = -8; s1 <= 8; ++s1) {
            Quad y = x;
            y.d[axes[0]] = stepped(x.d[axes[0]], s0);
            y.d[axes[1]] = stepped(x.d[axes[1]], s1);
            const mpq_class det = o.det + n[axes[0]] * (exactFloat(y.d[axes[0]]) - exactFloat(x.d[axes[0]])) +
                                  n[axes[1]] * (exactFloat(y.d[axes[1]]) - exactFloat(x.d[axes[1]]));
            const mpq_class ratio = direction * det / (u * o.permanent);
            if (ratio > k - mpq_class(1, 8) && ratio < k + mpq_class(9, 8) && inWindow(y)) return y;
        }
    return std::nullopt;
}

/// Families of inputs for the relative term: "mixed" (coordinates of mixed exponents, 2^-6 to
/// 2^6, so that the differences round) and "offset" (clusters at a large common offset, 2^8 to
/// 2^38, spread over 1/2 to 1/16 of it). d starts near the plane abc.
enum class RelativeFamily { MixedExponents, LargeOffset };

inline Quad relativeFamilyQuad(std::mt19937& rng, RelativeFamily family) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    auto coordinate = [&](float centre, int lo, int hi) {
        const int e = lo + static_cast<int>(rng() % static_cast<unsigned>(hi - lo + 1));
        return centre + unit(rng) * std::bit_cast<float>(static_cast<std::uint32_t>(e + 127) << 23);
    };
    vec3 centre(0.0f);
    int lo = -6, hi = 6;
    if (family == RelativeFamily::LargeOffset) {
        const int e = 8 + static_cast<int>(rng() % 31u);
        for (int k = 0; k < 3; ++k)
            centre[k] = unit(rng) * std::bit_cast<float>(static_cast<std::uint32_t>(e + 127) << 23);
        hi = e - 1;
        lo = e - 4;
    }
    Quad x;
    for (vec3* v : {&x.a, &x.b, &x.c})
        for (int k = 0; k < 3; ++k) (*v)[k] = coordinate(centre[k], lo, hi);
    // d = a + s (b - a) + t (c - a), rounded: near the plane.
    std::uniform_real_distribution<double> st(-0.5, 1.5);
    const mpq_class s = st(rng), t = st(rng);
    for (int k = 0; k < 3; ++k)
        x.d[k] = floatNearest(exactFloat(x.a[k]) + s * (exactFloat(x.b[k]) - exactFloat(x.a[k])) +
                              t * (exactFloat(x.c[k]) - exactFloat(x.a[k])));
    return x;
}

/// The flush band of the absolute term: four points whose y and z coordinates are O(M) and whose
/// x coordinates are tiny, so det = sum over points of x_p * C_p (C_p: twice the signed area of
/// the other three points' (y, z) triangle, at most 4 M^2 in magnitude). One point's x is normal and
/// contributes `direction * j * max(M, 1)^2 * 2^-126`; the others' x are denormals (which a device may
/// flush), with signs against it when `against`, so that flushing them leaves a float det of
/// the kept contribution's sign and size while the exact det may have the other sign.
inline std::optional<Quad> flushBandQuad(std::mt19937& rng, int j, int direction, bool against) {
    const int e = static_cast<int>(rng() % 5u) - 1; // M = 2^-1 .. 2^3
    const float scale = std::bit_cast<float>(static_cast<std::uint32_t>(e + 127) << 23);
    // (y, z): a at the origin, b, c, d at (M, M), (-M, M), (0, -M) in a random order, so that every
    // difference is at most M and |C_a| = 4 M^2, the others M^2, M^2 and 2 M^2: flushing three
    // x's can outweigh a kept contribution of up to 6.9 M^2. One input in four is moved by up to
    // M/8 at random.
    std::array<vec3, 4> p = {vec3(0.0f), vec3(0.0f, scale, scale), vec3(0.0f, -scale, scale),
                             vec3(0.0f, 0.0f, -scale)};
    std::shuffle(p.begin() + 1, p.end(), rng);
    if (rng() % 4u == 0) {
        std::uniform_real_distribution<float> jitter(-0.125f, 0.125f);
        for (vec3& v : p) v += vec3(0.0f, scale * jitter(rng), scale * jitter(rng));
    }
    // C_q = det with x = 1 at point q and 0 elsewhere.
    std::array<mpq_class, 4> cof;
    for (int q = 0; q < 4; ++q) {
        std::array<vec3, 4> y = p;
        y[q].x = 1.0f;
        cof[q] = exactOrient3d(y[0], y[1], y[2], y[3]).det;
    }
    const int kept = 1 + static_cast<int>(rng() % 3u);
    if (sgn(cof[kept]) == 0) return std::nullopt;
    mpq_class largestDifference = 0;
    for (int q = 1; q < 4; ++q)
        for (int k = 1; k < 3; ++k)
            largestDifference =
                std::max(largestDifference, mpq_class(abs(exactFloat(p[q][k]) - exactFloat(p[0][k]))));
    const mpq_class m = std::max(largestDifference, mpq_class(1));
    p[kept].x = floatNearest(direction * j * m * m * powerOfTwo(-126) / cof[kept]);
    const float largestDenormal = std::bit_cast<float>(0x007fffffu);
    std::uniform_int_distribution<std::uint32_t> denormal(1u, 0x007fffffu);
    for (int q = 0; q < 4; ++q) {
        if (q == kept) continue;
        if (against) {
            const int s = -direction * sign(cof[q]);
            p[q].x = s == 0 ? 0.0f : (s > 0 ? largestDenormal : -largestDenormal);
        } else {
            p[q].x = std::bit_cast<float>(static_cast<std::uint32_t>(denormal(rng) | ((rng() & 1u) << 31)));
        }
    }
    return Quad{p[0], p[1], p[2], p[3]};
}

} // namespace glcollide::test
