#pragma once
// C++ view of the exact-predicate shader library (shaders/common/exact_int.glsl, orient.glsl,
// tri_tri_robust.glsl): the same text compiled as C++, glm standing in for the GLSL vector types
// and float built-ins, so the CPU runs the very code the GPU runs. The integer built-ins are
// defined here as the GLSL specification defines them (glm 0.9.9's usubBorrow returns y - x, the
// negation of GLSL's x - y; the tests below caught it). Header-only on purpose: every translation
// unit that includes it compiles the library with its own flags, which is how
// tests/CMakeLists.txt builds it with fast-math and FMA contraction to mimic a relaxed GPU compiler.
//
// Everything sits in an unnamed namespace (internal linkage: one private copy per translation
// unit, no clash between a strict and a relaxed build) inside glcollide::shader. The GLSL
// per-invocation globals of the exact pass become thread_local.

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

#include <glcollide/error.hpp>

#include <bit>
#include <cstdint>
#include <string>

namespace glcollide::shader {
namespace {

using glm::abs;
using glm::cross;
using glm::floatBitsToInt;
using glm::floatBitsToUint;
using glm::max;
using glm::min;
using uint = std::uint32_t;
using vec3 = glm::vec3;
using ivec3 = glm::ivec3;
using uvec3 = glm::uvec3;

// GLSL 4.30, section 8.8 "Integer Functions".
uint uaddCarry(uint x, uint y, uint& carry) {
    const std::uint64_t sum = std::uint64_t{x} + y;
    carry = static_cast<uint>(sum >> 32);
    return static_cast<uint>(sum);
}
uint usubBorrow(uint x, uint y, uint& borrow) {
    borrow = x < y ? 1u : 0u;
    return x - y; // modulo 2^32
}
void umulExtended(uint x, uint y, uint& msb, uint& lsb) {
    const std::uint64_t product = std::uint64_t{x} * y;
    msb = static_cast<uint>(product >> 32);
    lsb = static_cast<uint>(product);
}
int findLSB(uint x) {
    return x == 0u ? -1 : std::countr_zero(x);
}
int findMSB(uint x) {
    return std::bit_width(x) - 1;
} // -1 for 0

// A translation unit uses only part of the library: unused internal functions are expected.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
// Test seam: the float evaluation behind glcOrient3dFilter (det, permanent, max(M, 1)), replaceable
// per thread by tests that model another conforming compiler (a worst-case rounding, a rewriting,
// a filter whose results differ between reruns). Null: the library's own glcOrient3dEstimate.
// Shaders never define GLC_ORIENT3D_ESTIMATE, so the GPU always runs the library's evaluation.
using Orient3dEstimate = vec3 (*)(vec3 a, vec3 b, vec3 c, vec3 d);
thread_local Orient3dEstimate orient3dEstimateOverride = nullptr;
vec3 glcOrient3dEstimate(vec3 a, vec3 b, vec3 c, vec3 d); // defined in common/orient.glsl
vec3 orient3dEstimateSeam(vec3 a, vec3 b, vec3 c, vec3 d) {
    return orient3dEstimateOverride != nullptr ? orient3dEstimateOverride(a, b, c, d)
                                               : glcOrient3dEstimate(a, b, c, d);
}
#define GLC_ORIENT3D_ESTIMATE orient3dEstimateSeam

#define GLC_PRIVATE thread_local
#include "common/tri_tri_robust.glsl"
#undef GLC_PRIVATE
#undef GLC_ORIENT3D_ESTIMATE
#pragma GCC diagnostic pop

/// The robust answer as the GPU composes it: the filtered pass, then the exact pass for the pairs
/// it left undecided. Throws Error when the exact pass could not finish (glcExactFailed), as the
/// passes do on the device: no answer is taken from a voided run.
inline bool robustTrianglesIntersect(vec3 a0, vec3 a1, vec3 a2, vec3 b0, vec3 b1, vec3 b2) {
    const int filtered = glcTriTriFiltered(a0, a1, a2, b0, b1, b2);
    if (filtered != GLC_UNDECIDED) return filtered == 1;
    const bool hit = glcTriTriExact(a0, a1, a2, b0, b1, b2);
    if (glcExactFailed)
        throw Error("robust tri-tri: the exact pass could not finish (more than " +
                    std::to_string(GLC_MAX_EXACT) +
                    " recorded signs, or a predicate on a point that is not an input corner)");
    return hit;
}

} // namespace
} // namespace glcollide::shader
