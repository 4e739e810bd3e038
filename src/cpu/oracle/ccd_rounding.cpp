#include "cpu/oracle/ccd_rounding.hpp"

#include "core/ccd_cover.hpp"

#include <glcollide/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace glcollide::cpu {
namespace {

/// Bits of |z| (z != 0): 2^(bits-1) <= |z| < 2^bits.
long bitLength(const mpz_class& z) {
    return static_cast<long>(mpz_sizeinbase(z.get_mpz_t(), 2));
}

/// n / d < 2^e, for n, d > 0.
bool belowPowerOfTwo(const mpz_class& n, const mpz_class& d, long e) {
    mpz_class lhs = n, rhs = d;
    if (e >= 0)
        mpz_mul_2exp(rhs.get_mpz_t(), rhs.get_mpz_t(), static_cast<mp_bitcnt_t>(e));
    else
        mpz_mul_2exp(lhs.get_mpz_t(), lhs.get_mpz_t(), static_cast<mp_bitcnt_t>(-e));
    return lhs < rhs;
}

/// The binary exponent e with 2^e <= |x| < 2^(e+1), x != 0: the bit lengths give it within one.
long binaryExponent(const mpq_class& x) {
    const mpz_class n = abs(x.get_num()), d = x.get_den();
    long e = bitLength(n) - bitLength(d);
    if (belowPowerOfTwo(n, d, e)) --e;
    return e;
}

/// x * 2^k, exactly.
mpq_class timesPowerOfTwo(const mpq_class& x, long k) {
    mpq_class r;
    if (k >= 0)
        mpq_mul_2exp(r.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(k));
    else
        mpq_div_2exp(r.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(-k));
    return r;
}

} // namespace

float nearestFloat(const mpq_class& x) {
    if (sgn(x) == 0) return 0.0f;
    const mpz_class n = abs(x.get_num()), d = x.get_den();
    const long e = binaryExponent(x);
    if (e >= 128) throw Error("the value " + x.get_str() + " is outside float range (|v| <= 3.4028235e38)");
    if (e < -150) return sgn(x) < 0 ? -0.0f : 0.0f; // |x| < 2^-150: below half the least subnormal
    // The weight of the significand's last bit: 2^(e-23) for normal floats, 2^-149 for subnormals.
    const long lsb = std::max(e, -126L) - 23;
    // m = |x| / 2^lsb rounded to nearest, ties to even.
    mpz_class num = n, den = d;
    if (lsb < 0)
        mpz_mul_2exp(num.get_mpz_t(), num.get_mpz_t(), static_cast<mp_bitcnt_t>(-lsb));
    else
        mpz_mul_2exp(den.get_mpz_t(), den.get_mpz_t(), static_cast<mp_bitcnt_t>(lsb));
    mpz_class m, r;
    mpz_fdiv_qr(m.get_mpz_t(), r.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
    const int half = cmp(mpz_class(2 * r), den);
    if (half > 0 || (half == 0 && mpz_odd_p(m.get_mpz_t()))) ++m;
    // m <= 2^24; m = 2^24 is the carry into the next binade, still exact. 2^128 and up overflow.
    if (lsb + bitLength(m) > 128)
        throw Error("the value " + x.get_str() + " is outside float range (|v| <= 3.4028235e38)");
    const float magnitude = std::ldexp(static_cast<float>(m.get_ui()), static_cast<int>(lsb)); // exact
    return sgn(x) < 0 ? -magnitude : magnitude;
}

float floatAtLeast(const mpq_class& x) {
    float f = nearestFloat(x);
    if (mpq_class(f) < x) {
        f = std::nextafter(f, std::numeric_limits<float>::infinity());
        if (std::isinf(f))
            throw Error("the value " + x.get_str() + " is outside float range (|v| <= 3.4028235e38)");
    }
    return f;
}

float coverRounding(const std::array<glm::vec3, 8>& points, const mpq_class& minSeparation,
                    const mpq_class& roundingError) {
    float largest = 0.0f;
    for (const glm::vec3& p : points)
        largest = std::max({largest, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    return ccdCoveredSeparation(floatAtLeast(minSeparation + 2 * roundingError), largest);
}

std::array<long, 3> contactAxisScale(const RationalCcdQuery& query) {
    std::array<long, 3> scale{};
    for (int k = 0; k < 3; ++k) {
        mpq_class largest = 0;
        for (const RationalPoint& p : query) {
            const mpq_class& x = k == 0 ? p.x : k == 1 ? p.y : p.z;
            if (abs(x) > largest) largest = abs(x);
        }
        scale[static_cast<std::size_t>(k)] = sgn(largest) == 0 ? 0 : -(binaryExponent(largest) + 1);
    }
    return scale;
}

RoundedCcdQuery roundCcdQuery(const RationalCcdQuery& query, const mpq_class& minSeparation) {
    RoundedCcdQuery rounded;
    if (sgn(minSeparation) == 0) rounded.axisScale = contactAxisScale(query);
    rounded.roundingError = 0;
    for (std::size_t i = 0; i < query.size(); ++i) {
        const mpq_class* exact[3] = {&query[i].x, &query[i].y, &query[i].z};
        for (int k = 0; k < 3; ++k) {
            const mpq_class x = timesPowerOfTwo(*exact[k], rounded.axisScale[static_cast<std::size_t>(k)]);
            const float f = nearestFloat(x);
            rounded.points[i][k] = f;
            const mpq_class error = abs(x - mpq_class(f));
            if (error > rounded.roundingError) rounded.roundingError = error;
        }
    }
    rounded.minSeparation = coverRounding(rounded.points, minSeparation, rounded.roundingError);
    return rounded;
}

} // namespace glcollide::cpu
