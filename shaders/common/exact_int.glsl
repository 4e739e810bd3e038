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
// detection later). Big integers live in per-invocation registers (GLC_BIG_REGISTERS of them,
// GLC_BIG_LIMBS limbs each), named by index: no array is ever copied, and every operation touches
// only the n limbs the frame needs, so typical inputs cost a few limbs however large the capacity.
//   GlcFrame f = glcFrameEmpty(); f = glcFrameInclude(f, x); ...   // every input of the expression
//   int n = glcFrameLimbs(f, degree, growthBits);                   // limbs for its values
//   glcBigSetFloat(r, x, f, n);                                     // register r = x / 2^f.low, exact
//   glcBigSetUint(r, v, n); glcBigAdd(r, a, b, n); glcBigSub(r, a, b, n); glcBigNeg(r, a, n);
//   glcBigMul(r, a, b, n) (r distinct from a and b); glcBigSign(r, n)   -- all modulo 2^(32n)
// growthBits bounds how much larger than the product of `degree` inputs (each below 2^(high-low))
// any intermediate value can be: e.g. orient3d multiplies three differences (1 bit each) and sums
// at most 6 products (3 bits), so growthBits = 3 + 3.

#ifndef GLC_EXACT_INT_GLSL
#define GLC_EXACT_INT_GLSL

// 28 limbs = 896 bits. A caller must keep degree * 277 + growthBits + 1 <= 896 for inputs over the
// whole float range (orient3d: 3 * (277 + 1) + 6 + 1 = 841; the CCD cubic's coefficients, whose
// factors are differences of differences, 3 * (277 + 2) + 10 + 1 = 848). glcFrameLimbs clamps to
// the capacity, so a larger polynomial would be computed modulo 2^896: wrong, not an overflow.
#define GLC_BIG_LIMBS 28

#ifndef GLC_PRIVATE
#define GLC_PRIVATE // GLSL globals are per invocation; C++ makes them thread_local
#endif

#define GLC_BIG_REGISTERS 16
// Register r's limb i is glcLimbs[r * n + i]: packed by the evaluation's own limb count n, so a
// small frame touches a small block of memory (on llvmpipe twice as fast as a fixed stride).
GLC_PRIVATE uint glcLimbs[GLC_BIG_REGISTERS * GLC_BIG_LIMBS];

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

// Register r = the small non-negative integer v (a constant factor of a polynomial).
void glcBigSetUint(int r, uint v, int n) {
    glcLimbs[r * n] = v;
    for (int i = 1; i < n; ++i) glcLimbs[r * n + i] = 0u;
}

// Register r = -a modulo 2^(32n): invert and add one (r may be a).
void glcBigNeg(int r, int a, int n) {
    uint carry = 1u;
    for (int i = 0; i < n; ++i) {
        uint c;
        glcLimbs[r * n + i] = uaddCarry(~glcLimbs[a * n + i], carry, c);
        carry = c;
    }
}

// Register r = x / 2^f.low as an exact integer (x must have been included in f).
void glcBigSetFloat(int r, float x, GlcFrame f, int n) {
    for (int i = 0; i < n; ++i) glcLimbs[r * n + i] = 0u;
    uint m = glcMantissa(x);
    if (m == 0u) return;
    int lsb = findLSB(m);
    m = m >> uint(lsb);
    int shift = glcExponent(x) + lsb - f.low; // >= 0 since f.low <= this input's lowest bit
    int q = shift >> 5;
    uint s = uint(shift & 31);
    if (q < n) glcLimbs[r * n + q] = m << s;
    if (s != 0u && q + 1 < n) glcLimbs[r * n + q + 1] = m >> (32u - s);
    if ((floatBitsToUint(x) >> 31) != 0u) glcBigNeg(r, r, n);
}

// Register r = a + b (r may be a or b: limb i is read before it is written).
void glcBigAdd(int r, int a, int b, int n) {
    uint carry = 0u;
    for (int i = 0; i < n; ++i) {
        uint c1, c2;
        uint s = uaddCarry(glcLimbs[a * n + i], glcLimbs[b * n + i], c1);
        glcLimbs[r * n + i] = uaddCarry(s, carry, c2);
        carry = c1 + c2;
    }
}

// Register r = a - b (r may be a or b).
void glcBigSub(int r, int a, int b, int n) {
    uint borrow = 0u;
    for (int i = 0; i < n; ++i) {
        uint b1, b2;
        uint d = usubBorrow(glcLimbs[a * n + i], glcLimbs[b * n + i], b1);
        glcLimbs[r * n + i] = usubBorrow(d, borrow, b2);
        borrow = b1 + b2;
    }
}

// Register r = a * b modulo 2^(32n), r distinct from a and b: schoolbook, keeping only the limbs
// below n. Two's complement operands multiply correctly modulo 2^(32n), so no sign handling is
// needed while the product fits.
void glcBigMul(int r, int a, int b, int n) {
    for (int i = 0; i < n; ++i) glcLimbs[r * n + i] = 0u;
    for (int i = 0; i < n; ++i) {
        uint ai = glcLimbs[a * n + i];
        if (ai == 0u) continue;
        uint carry = 0u;
        for (int j = 0; i + j < n; ++j) {
            uint hi, lo, c1, c2;
            umulExtended(ai, glcLimbs[b * n + j], hi, lo);
            uint t = uaddCarry(lo, glcLimbs[r * n + i + j], c1);
            glcLimbs[r * n + i + j] = uaddCarry(t, carry, c2);
            carry = hi + c1 + c2; // hi <= 2^32 - 2: no overflow
        }
    }
}

// -1, 0 or 1.
int glcBigSign(int a, int n) {
    if ((glcLimbs[a * n + n - 1] >> 31) != 0u) return -1;
    uint nonzero = 0u;
    for (int i = 0; i < n; ++i) nonzero |= glcLimbs[a * n + i];
    return nonzero != 0u ? 1 : 0;
}

#endif // GLC_EXACT_INT_GLSL
