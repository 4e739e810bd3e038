// The CCD query CSV reader (cpu/oracle/ccd_query_csv.hpp) and the rounding of its rationals to the
// float queries the GPU decides (cpu/oracle/ccd_rounding.hpp). Expected values come from GMP
// arithmetic written out independently here, from the hardware's double -> float conversion
// (correctly rounded, and exact rationals in: a single rounding), or from the IEEE binary32 format
// itself (its largest value, least normal and least subnormal).

#include "cpu/ccd_library.hpp"
#include "cpu/oracle/ccd_query_csv.hpp"
#include "cpu/oracle/ccd_rounding.hpp"

#include <glcollide/error.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace glcollide {
namespace {

using cpu::CcdCsvQuery;
using cpu::parseCcdQueryCsv;

mpq_class pow2(long e) {
    mpz_class one = 1;
    if (e >= 0) {
        mpz_mul_2exp(one.get_mpz_t(), one.get_mpz_t(), static_cast<mp_bitcnt_t>(e));
        return mpq_class(one);
    }
    mpz_class den = 1;
    mpz_mul_2exp(den.get_mpz_t(), den.get_mpz_t(), static_cast<mp_bitcnt_t>(-e));
    return mpq_class(one, den);
}

/// Eight rows of a query whose point i is (i, i + 1/2, -i/3), as integer pairs, with a ground truth.
std::string integerQuery(int truth) {
    std::string text;
    for (int i = 0; i < 8; ++i)
        text += std::to_string(i) + ",1," + std::to_string(2 * i + 1) + ",2," + std::to_string(-i) + ",3," +
                std::to_string(truth) + "\n";
    return text;
}

/// Compares with the canonical form of the expected values (mpq_class(num, den) is not reduced).
void expectPoint(const cpu::RationalPoint& p, mpq_class x, mpq_class y, mpq_class z) {
    x.canonicalize();
    y.canonicalize();
    z.canonicalize();
    EXPECT_EQ(p.x, x);
    EXPECT_EQ(p.y, y);
    EXPECT_EQ(p.z, z);
}

/// Parsing `text` throws Error whose message starts with "test.csv:<line>: " and contains `what`.
void expectError(const std::string& text, std::size_t line, const std::string& what) {
    try {
        (void)parseCcdQueryCsv(text, "test.csv");
        ADD_FAILURE() << "no error for:\n" << text;
    } catch (const Error& e) {
        const std::string message = e.what();
        const std::string where = "test.csv:" + std::to_string(line) + ": ";
        EXPECT_EQ(message.rfind(where, 0), 0u) << message;
        EXPECT_NE(message.find(what), std::string::npos) << message;
    }
}

TEST(CcdQueryCsv, ReadsIntegerPairsWithTheGroundTruth) {
    const std::vector<CcdCsvQuery> qs = parseCcdQueryCsv(integerQuery(1) + integerQuery(0), "t.csv");
    ASSERT_EQ(qs.size(), 2u);
    for (int i = 0; i < 8; ++i)
        expectPoint(qs[0].points[static_cast<std::size_t>(i)], i, mpq_class(2 * i + 1, 2), mpq_class(-i, 3));
    EXPECT_EQ(qs[0].truth, std::optional<bool>(true));
    EXPECT_EQ(qs[1].truth, std::optional<bool>(false));
    EXPECT_EQ(qs[1].lines[0], 9u);
    EXPECT_EQ(qs[1].lines[7], 16u);
}

TEST(CcdQueryCsv, ReadsDecimalsExactly) {
    // Rows of 3 decimals; the exact values are written as fractions.
    const std::string text = "# vertex, then the triangle\n"
                             "1.25e-3, -0.1, .5\n"
                             "5., +7, 1E2\n"
                             "\n"
                             "  0.3333333333333333333333333333  ,\t-2.5e+1 , 0\n"
                             "-0e5,123456789012345678901234567890.5,1e-30\n"
                             "1,2,3\n1,2,3\n1,2,3\n1,2,3\n";
    const std::vector<CcdCsvQuery> qs = parseCcdQueryCsv(text, "t.csv");
    ASSERT_EQ(qs.size(), 1u);
    expectPoint(qs[0].points[0], mpq_class(1, 800), mpq_class(-1, 10), mpq_class(1, 2));
    expectPoint(qs[0].points[1], 5, 7, 100);
    const mpz_class tenTo28("10000000000000000000000000000");
    expectPoint(qs[0].points[2], mpq_class(mpz_class("3333333333333333333333333333"), tenTo28), -25, 0);
    expectPoint(qs[0].points[3], 0, mpq_class(mpz_class("1234567890123456789012345678905"), 10),
                mpq_class(1, mpz_class("1000000000000000000000000000000")));
    EXPECT_FALSE(qs[0].truth.has_value());
    EXPECT_EQ(qs[0].lines[2], 5u); // blank and comment lines keep their numbers
}

TEST(CcdQueryCsv, ReadsNumbersBeyond64Bits) {
    // The benchmark's denominators reach 2^71; numerators here exceed 2^100.
    const mpz_class big = (mpz_class(1) << 100) + 12345; // 1267650600228229401496703217721
    const mpz_class den = mpz_class(1) << 71;            // 2361183241434822606848
    std::string text;
    for (int i = 0; i < 8; ++i)
        text += big.get_str() + "," + den.get_str() + ",-" + big.get_str() + ",1,1," + den.get_str() + "\n";
    const std::vector<CcdCsvQuery> qs = parseCcdQueryCsv(text, "t.csv");
    ASSERT_EQ(qs.size(), 1u);
    expectPoint(qs[0].points[5], mpq_class(big, den), 0 - mpq_class(big), mpq_class(1, den));
}

TEST(CcdQueryCsv, BadRowsNameTheirLine) {
    const std::string row = "1,2,3,4,5,6\n";
    std::string seven;
    for (int i = 0; i < 7; ++i) seven += row;
    expectError("# c\n" + row + "1,2\n", 3, "got 2 fields");
    expectError(row + "1,2,3,4,5\n", 2, "got 5 fields");
    expectError("1,2,x,4,5,6\n", 1, "field 3 'x' is not an integer");
    expectError("1,2,3,4,5,1 2\n", 1, "field 6 '1 2' is not an integer");
    expectError("1,2,3.5,4,5,6\n", 1, "field 3 '3.5' is not an integer");
    expectError(row + "1,0,3,4,5,6\n", 2, "field 2 '0' is not a positive denominator");
    expectError("1,2,3,-4,5,6\n", 1, "field 4 '-4' is not a positive denominator");
    expectError("1,2,abc\n", 1, "field 3 'abc' is not a decimal number");
    expectError("1,nan,3\n", 1, "field 2 'nan' is not a decimal number");
    expectError("inf,2,3\n", 1, "field 1 'inf' is not a decimal number");
    expectError("1,2,1e\n", 1, "field 3 '1e' is not a decimal number");
    expectError("1,.,3\n", 1, "field 2 '.' is not a decimal number");
    expectError("1,2,1e39\n", 1, "outside float range");
    expectError("1,-1e39,3\n", 1, "outside float range");
    expectError("1,2,3,4,-340282356779733661637539395458142568448,1\n", 1,
                "outside float range"); // -(2^128 - 2^103)
    expectError("1,2,3,4,5,6,2\n", 1, "field 7 '2' (ground truth) is not 0 or 1");
    expectError("1,2,3,7\n", 1, "field 4 '7' (ground truth) is not 0 or 1");
    expectError(seven + "1,2,3,4,5,6,1\n", 8, "ground-truth column is here but not on line 1");
    expectError("1,2,3,4,5,6,1\n" + row, 2, "ground-truth column is missing here but on line 1");
    expectError("1,2,3,4,5,6,1\n1,2,3,4,5,6,0\n", 2, "ground truth 0 differs from line 1");
    expectError(seven + row + "\n" + row + row + "# end\n", 10,
                "the file ends inside this query: 2 of its 8 rows");
}

TEST(CcdQueryCsv, FloatRangeEndsWhereRoundingReachesInfinity) {
    // 2^128 - 2^103 is halfway between the largest float and 2^128: it rounds up (ties to even).
    const mpq_class threshold = pow2(128) - pow2(103);
    auto rows = [](const std::string& x) {
        std::string text;
        for (int i = 0; i < 8; ++i) text += x + ",0,0\n";
        return text;
    };
    expectError(rows(threshold.get_str()), 1, "outside float range");
    const std::vector<CcdCsvQuery> qs = parseCcdQueryCsv(rows(mpq_class(threshold - 1).get_str()), "t.csv");
    EXPECT_EQ(cpu::nearestFloat(qs[0].points[0].x), std::numeric_limits<float>::max());
}

TEST(CcdQueryCsv, ExactDecimalRefusesAbsurdExponents) {
    EXPECT_TRUE(cpu::parseExactDecimal("1e-100000").has_value());
    EXPECT_FALSE(cpu::parseExactDecimal("1e-100001").has_value());
    EXPECT_EQ(cpu::parseExactDecimal("0e99999"), std::optional<mpq_class>(0));
    EXPECT_FALSE(cpu::parseExactDecimal("0e100001").has_value()); // the limit holds for 0 too
}

// ---------------------------------------------------------------------------------------------
// Rounding to float.

TEST(CcdRounding, NearestFloatEqualsTheHardwareConversionOfExactDoubles) {
    // A double is an exact rational, and the double -> float conversion rounds it correctly, once.
    std::mt19937_64 random(2211);
    std::uniform_int_distribution<int> exponent(-160, 130);
    std::uniform_real_distribution<double> significand(1.0, 2.0);
    for (int i = 0; i < 20000; ++i) {
        const double d = std::ldexp(significand(random), exponent(random)) * (i % 2 ? -1.0 : 1.0);
        if (std::fabs(d) >= std::ldexp(1.0, 128) - std::ldexp(1.0, 103)) continue; // would overflow
        EXPECT_EQ(cpu::nearestFloat(mpq_class(d)), static_cast<float>(d)) << d;
    }
}

TEST(CcdRounding, NearestFloatRoundsOnceWhereDoubleRoundingFails) {
    // 1 + 2^-24 + 2^-80: above the halfway point 1 + 2^-24, so the nearest float is 1 + 2^-23.
    // get_d() truncates to the double 1 + 2^-24, an exact tie, which the float conversion rounds
    // to even: 1. That is the error nearestFloat exists to avoid.
    const mpq_class x = 1 + pow2(-24) + pow2(-80);
    EXPECT_EQ(cpu::nearestFloat(x), 1.0f + 0x1p-23f);
    EXPECT_EQ(static_cast<float>(x.get_d()), 1.0f); // the trap, for the record
    // Exact ties go to even.
    EXPECT_EQ(cpu::nearestFloat(1 + pow2(-24)), 1.0f);
    EXPECT_EQ(cpu::nearestFloat(1 + 3 * pow2(-24)), 1.0f + 0x1p-22f);
    EXPECT_EQ(cpu::nearestFloat(-(1 + 3 * pow2(-24))), -(1.0f + 0x1p-22f));
    // Subnormals: the least is 2^-149; half of it rounds to 0 (even), a hair more to 2^-149.
    EXPECT_EQ(cpu::nearestFloat(pow2(-150)), 0.0f);
    EXPECT_EQ(cpu::nearestFloat(pow2(-150) + pow2(-400)), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(cpu::nearestFloat(3 * pow2(-150)), 2 * std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(cpu::nearestFloat(pow2(-126) - pow2(-151)), std::numeric_limits<float>::min()); // carry
    // 1/3 rounds up to 11184811 / 2^25 (11184811 * 3 = 2^25 + 1).
    EXPECT_EQ(mpq_class(cpu::nearestFloat(mpq_class(1, 3))), mpq_class(11184811, 33554432));
    EXPECT_THROW((void)cpu::nearestFloat(pow2(128) - pow2(103)), Error);
    EXPECT_EQ(cpu::nearestFloat(pow2(128) - pow2(103) - pow2(-10)), std::numeric_limits<float>::max());
}

TEST(CcdRounding, FloatAtLeastIsTheLeastFloatAbove) {
    for (const mpq_class& x :
         {mpq_class(1, 3), mpq_class(2, 3), mpq_class(1, 10), mpq_class(pow2(-149) / 3), mpq_class(5)}) {
        const float f = cpu::floatAtLeast(x);
        EXPECT_GE(mpq_class(f), x);
        EXPECT_LT(mpq_class(std::nextafter(f, -1.0f)), x);
    }
    EXPECT_THROW((void)cpu::floatAtLeast(pow2(128) - pow2(104) + 1), Error); // above the largest float
}

cpu::RationalCcdQuery pointsOf(const mpq_class& value) {
    cpu::RationalCcdQuery q;
    for (std::size_t i = 0; i < q.size(); ++i)
        q[i] = {mpq_class(static_cast<long>(i)), mpq_class(1, 4), value};
    return q;
}

TEST(CcdRounding, FloatQueriesAreUncoveredAndContactQueriesScaledPerAxis) {
    // Every coordinate is a float: nothing is widened. Contact (separation 0): each axis scaled by
    // the power of two that brings its largest magnitude into [0.5, 1): x up to 7 by 2^-3, y = 1/4
    // by 2, z up to 3/8 by 2.
    const cpu::RoundedCcdQuery contact = cpu::roundCcdQuery(pointsOf(mpq_class(-3, 8)), 0);
    EXPECT_EQ(contact.roundingError, 0);
    EXPECT_EQ(contact.minSeparation, 0.0f);
    EXPECT_EQ(contact.axisScale, (std::array<long, 3>{-3, 1, 1}));
    EXPECT_EQ(contact.points[7], glm::vec3(0.875f, 0.5f, -0.75f));
    // A positive separation is a Euclidean distance: no axis is scaled.
    const cpu::RoundedCcdQuery apart = cpu::roundCcdQuery(pointsOf(mpq_class(-3, 8)), mpq_class(1, 4));
    EXPECT_EQ(apart.axisScale, (std::array<long, 3>{0, 0, 0}));
    EXPECT_EQ(apart.points[7], glm::vec3(7.0f, 0.25f, -0.375f));
    EXPECT_EQ(apart.minSeparation, 0.25f);
}

TEST(CcdRounding, ContactQueriesRoundTheSameAtEveryScaleOfEveryAxis) {
    // The axis scaling makes the float query a function of the rationals up to a power of two per
    // axis: scaled copies (2^-30 on x, 2^17 on y, 2^3 on z) give the same bits.
    cpu::RationalCcdQuery q = pointsOf(mpq_class(1, 3));
    q[2].y = mpq_class(-5, 7);
    cpu::RationalCcdQuery scaled = q;
    for (auto& p : scaled) {
        p.x /= pow2(30);
        p.y *= pow2(17);
        p.z *= 8;
    }
    const cpu::RoundedCcdQuery a = cpu::roundCcdQuery(q, 0), b = cpu::roundCcdQuery(scaled, 0);
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.minSeparation, b.minSeparation);
    EXPECT_EQ(b.axisScale[0], a.axisScale[0] + 30);
    EXPECT_EQ(b.axisScale[1], a.axisScale[1] - 17);
    EXPECT_EQ(b.axisScale[2], a.axisScale[2] - 3);
}

TEST(CcdRounding, ContactCoversWeighOnEachAxisByItsOwnMagnitude) {
    // x near 1000 beside z near 1/1000: without the axis scaling, the cover (2^-14 from x's rounding)
    // would be 16 times z's whole magnitude; scaled, it is at most 2^-24, an ulp of a coordinate
    // in [0.5, 1), on every axis.
    cpu::RationalCcdQuery q;
    for (std::size_t i = 0; i < q.size(); ++i)
        q[i] = {mpq_class(3001 + static_cast<long>(i), 3), mpq_class(1, 4),
                mpq_class(1, 1000 + static_cast<long>(i))};
    const cpu::RoundedCcdQuery r = cpu::roundCcdQuery(q, 0);
    EXPECT_GT(r.minSeparation, 0.0f);
    EXPECT_LE(r.minSeparation, 0x1p-24f);
    EXPECT_GE(mpq_class(r.minSeparation), 2 * r.roundingError);
}

TEST(CcdRounding, TheCoverIsTheLeastFloatAboveTheSeparationPlusTwiceTheRoundingError) {
    const mpq_class third(1, 3), d(1, 10);
    const cpu::RoundedCcdQuery r = cpu::roundCcdQuery(pointsOf(third), d);
    const mpq_class e = abs(third - mpq_class(cpu::nearestFloat(third)));
    EXPECT_EQ(r.roundingError, e); // 1/3's error is the largest: the other coordinates are floats
    EXPECT_GE(mpq_class(r.minSeparation), d + 2 * e);
    EXPECT_LT(mpq_class(std::nextafter(r.minSeparation, 0.0f)), d + 2 * e);
}

TEST(CcdRounding, TheCoverStaysNormalAfterTheFloatCcdNormalizesAtEveryMagnitude) {
    // A tiny rounding error (from the coordinate 2^-140 / 3) beside coordinates of every magnitude,
    // for contact (axes scaled) and for a tiny positive separation (2^-300, axes kept): the cover
    // and the cover times ccd.glsl's own normalizing scale are normal floats.
    for (const mpq_class& separation : {mpq_class(0), pow2(-300)})
        for (long e : {-140L, -126L, -100L, -20L, 0L, 3L, 40L, 100L, 127L}) {
            cpu::RationalCcdQuery q = pointsOf(0);
            for (auto& p : q) p.x = pow2(e);
            q[5].z = pow2(-140) / 3;
            const cpu::RoundedCcdQuery r = cpu::roundCcdQuery(q, separation);
            float largest = 0.0f;
            for (const glm::vec3& p : r.points)
                largest = std::max({largest, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
            const float leastNormal = std::numeric_limits<float>::min();
            EXPECT_GE(r.minSeparation, leastNormal) << e;
            EXPECT_GE(r.minSeparation * shader::glcCcdNormalizingScale(largest), leastNormal) << e;
            EXPECT_GE(mpq_class(r.minSeparation), separation + 2 * r.roundingError) << e;
        }
}

TEST(CcdRounding, TheCoverStaysNormalAfterTheFloatCcdNormalizes) {
    // A positive separation, 2^-300, keeps the axes. Coordinates up to 2^100: the float CCD scales
    // by 2^-101 (largest into [0.5, 1)). A tiny rounding error (from the coordinate 2^-140 / 3)
    // widens the separation by less than 2^-126 / 2^-101 = 2^-25, which the normalized separation
    // would lose to a device flushing subnormals: the cover is raised to 2^-125 * 2^100 = 2^-25
    // (core/ccd_cover.hpp).
    const mpq_class tinySeparation = pow2(-300);
    cpu::RationalCcdQuery q = pointsOf(0);
    q[3].x = pow2(100);
    q[5].z = pow2(-140) / 3;
    const cpu::RoundedCcdQuery r = cpu::roundCcdQuery(q, tinySeparation);
    EXPECT_GT(r.roundingError, 0);
    EXPECT_LT(2 * r.roundingError, pow2(-126));
    EXPECT_EQ(r.minSeparation, 0x1p-25f);
    // Largest coordinate 7 (scale 2^-3): raised to 7 * 2^-125 (>= 2^-126 / 2^-3 = 2^-123 / 2).
    cpu::RationalCcdQuery small = pointsOf(0);
    small[5].z = pow2(-140) / 3;
    EXPECT_EQ(cpu::roundCcdQuery(small, tinySeparation).minSeparation, std::ldexp(7.0f, -125));
    // Coordinates near 2^-100 (scale 2^100): raised to the least normal float, 2^-126, not 2^-225.
    cpu::RationalCcdQuery tiny;
    for (auto& p : tiny) p = {pow2(-100), pow2(-101), pow2(-140) / 3};
    EXPECT_EQ(cpu::roundCcdQuery(tiny, tinySeparation).minSeparation, std::numeric_limits<float>::min());
}

} // namespace
} // namespace glcollide
