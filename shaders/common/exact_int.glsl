// Exact integer arithmetic on float inputs: the sign of a polynomial expression in float
// coordinates, decided with no floating-point operation at all, so the answer cannot depend on
// how a compiler treats floating point (contraction into FMA, reassociation, flushing of
// denormals, rounding mode, extended precision). Everything below is 32-bit unsigned integer
// arithmetic whose results GLSL defines exactly (uaddCarry, usubBorrow, umulExtended, shifts,
// bitwise operations) and that C++ defines the same way.
//
// Compiled as GLSL (shaders include it) and as C++ (src/cpu/shader_library.hpp includes it inside
// a namespace with glm), so the CPU runs the very same code. Rules for this shared text: no
// swizzles, no out/inout parameters of our own, no array constructors, float literals with `f`.
//
// Model. Every finite float is m * 2^e with an integer m < 2^24. For one evaluation, a frame is
// chosen from all the inputs it involves: `low` = the lowest set bit (as a power of two) of any
// input, `high` = one past the highest. In units of 2^low every input is an integer of at most
// high - low <= 277 bits (2^-149 to 2^128). A homogeneous polynomial of degree k evaluated on
// these integers is 2^(-k*low) times its value on the floats: the same sign. Integers are held in
// two's complement modulo 2^(32n) in n limbs (least significant first), n chosen by the frame so
// that every intermediate value fits; then arithmetic modulo 2^(32n) IS integer arithmetic, and
// truncated multiplication is exact. docs/narrow-phase.md gives the sizes.
//
// API (for orientation predicates here and the coplanarity cubic of continuous collision
// detection later):
//   GlcFrame f = glcFrameEmpty(); f = glcFrameInclude(f, x); ...   // every input of the expression
//   int n = glcFrameLimbs(f, degree, growthBits);                   // limbs for its values
//   GlcBig a = glcBigFromFloat(x, f, n);                            // exact: x / 2^f.low
//   glcBigAdd / glcBigSub / glcBigMul / glcBigNeg (all modulo 2^(32n)), glcBigSign
// growthBits bounds how much larger than the product of `degree` inputs (each below 2^(high-low))
// any intermediate value can be: e.g. orient3d multiplies three differences (1 bit each) and sums
// at most 6 products (3 bits), so growthBits = 3 + 3.

#ifndef GLC_EXACT_INT_GLSL
#define GLC_EXACT_INT_GLSL

// 28 limbs = 896 bits: degree 3 over the full float range needs 3 * 277 = 831 bits plus growth
// and sign (glcFrameLimbs never asks for more: it clamps, and the bound is shown in the docs).
#define GLC_BIG_LIMBS 28

struct GlcBig {
    uint limb[GLC_BIG_LIMBS];
};

struct GlcFrame {
    int low;  // lowest set bit over the inputs, as an exponent of 2 (meaningless while empty)
    int high; // one past the highest set bit over the inputs; high <= low: all inputs are zero
};

// The float's magnitude as mantissa and exponent, denormals included: |x| = mant * 2^exp.
// Read from the bits, so a device that flushes denormals in arithmetic still gets their value.
uint glcMantissa(float x) {
    uint bits = floatBitsToUint(x);
    uint e = (bits >> 23) & 0xffu;
    uint m = bits & 0x7fffffu;
    return e == 0u ? m : (m | 0x800000u);
}

int glcExponent(float x) {
    int e = int((floatBitsToUint(x) >> 23) & 0xffu);
    return (e == 0 ? 1 : e) - 150; // 127 bias + 23 fraction bits
}

GlcFrame glcFrameEmpty() {
    GlcFrame f;
    f.low = 1000;
    f.high = -1000;
    return f;
}

GlcFrame glcFrameInclude(GlcFrame f, float x) {
    uint m = glcMantissa(x);
    if (m != 0u) {
        int e = glcExponent(x);
        f.low = min(f.low, e + findLSB(m));
        f.high = max(f.high, e + findMSB(m) + 1);
    }
    return f;
}

// Limbs for values up to 2^(degree * (high - low) + growthBits) in magnitude, plus the sign bit.
int glcFrameLimbs(GlcFrame f, int degree, int growthBits) {
    int bits = degree * max(f.high - f.low, 0) + growthBits + 1;
    return min((bits + 31) / 32, GLC_BIG_LIMBS);
}

GlcBig glcBigZero() {
    GlcBig r;
    for (int i = 0; i < GLC_BIG_LIMBS; ++i) r.limb[i] = 0u;
    return r;
}

// The small non-negative integer v (a constant factor of a polynomial).
GlcBig glcBigFromUint(uint v) {
    GlcBig r = glcBigZero();
    r.limb[0] = v;
    return r;
}

// -a modulo 2^(32n): invert and add one.
GlcBig glcBigNeg(GlcBig a, int n) {
    GlcBig r = glcBigZero();
    uint carry = 1u;
    for (int i = 0; i < n; ++i) {
        uint c;
        r.limb[i] = uaddCarry(~a.limb[i], carry, c);
        carry = c;
    }
    return r;
}

// x / 2^f.low as an exact integer (x must have been included in f).
GlcBig glcBigFromFloat(float x, GlcFrame f, int n) {
    GlcBig r = glcBigZero();
    uint m = glcMantissa(x);
    if (m == 0u) return r;
    int lsb = findLSB(m);
    m = m >> uint(lsb);
    int shift = glcExponent(x) + lsb - f.low; // >= 0 since f.low <= this input's lowest bit
    int q = shift >> 5;
    uint s = uint(shift & 31);
    if (q < n) r.limb[q] = m << s;
    if (s != 0u && q + 1 < n) r.limb[q + 1] = m >> (32u - s);
    return (floatBitsToUint(x) >> 31) != 0u ? glcBigNeg(r, n) : r;
}

GlcBig glcBigAdd(GlcBig a, GlcBig b, int n) {
    GlcBig r = glcBigZero();
    uint carry = 0u;
    for (int i = 0; i < n; ++i) {
        uint c1, c2;
        uint s = uaddCarry(a.limb[i], b.limb[i], c1);
        r.limb[i] = uaddCarry(s, carry, c2);
        carry = c1 + c2;
    }
    return r;
}

GlcBig glcBigSub(GlcBig a, GlcBig b, int n) {
    GlcBig r = glcBigZero();
    uint borrow = 0u;
    for (int i = 0; i < n; ++i) {
        uint b1, b2;
        uint d = usubBorrow(a.limb[i], b.limb[i], b1);
        r.limb[i] = usubBorrow(d, borrow, b2);
        borrow = b1 + b2;
    }
    return r;
}

// a * b modulo 2^(32n): schoolbook, keeping only the limbs below n. Two's complement operands
// multiply correctly modulo 2^(32n), so no sign handling is needed while the product fits.
GlcBig glcBigMul(GlcBig a, GlcBig b, int n) {
    GlcBig r = glcBigZero();
    for (int i = 0; i < n; ++i) {
        uint ai = a.limb[i];
        if (ai == 0u) continue;
        uint carry = 0u;
        for (int j = 0; i + j < n; ++j) {
            uint hi, lo, c1, c2;
            umulExtended(ai, b.limb[j], hi, lo);
            uint t = uaddCarry(lo, r.limb[i + j], c1);
            r.limb[i + j] = uaddCarry(t, carry, c2);
            carry = hi + c1 + c2; // hi <= 2^32 - 2: no overflow
        }
    }
    return r;
}

// -1, 0 or 1.
int glcBigSign(GlcBig a, int n) {
    if ((a.limb[n - 1] >> 31) != 0u) return -1;
    uint nonzero = 0u;
    for (int i = 0; i < n; ++i) nonzero |= a.limb[i];
    return nonzero != 0u ? 1 : 0;
}

#endif // GLC_EXACT_INT_GLSL
