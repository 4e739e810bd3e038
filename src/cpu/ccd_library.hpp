#pragma once
// C++ view of the float CCD (shaders/common/ccd.glsl), compiled as C++ like the exact-predicate
// library (cpu/shader_library.hpp, whose GLSL built-ins and unnamed namespace it extends).
// Header-only on purpose: each translation unit compiles it with its own flags, which is how the
// relaxed-float test build runs it under fast-math, FMA contraction and FTZ/DAZ.

#include "cpu/shader_library.hpp"

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/vec4.hpp>

namespace glcollide::shader {
namespace {

using glm::clamp;
using glm::dot;
using glm::sqrt;
using glm::trunc;
using glm::uintBitsToFloat;
using vec4 = glm::vec4;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
#define GLC_PRIVATE thread_local
#include "common/ccd.glsl"
#undef GLC_PRIVATE
#pragma GCC diagnostic pop

} // namespace
} // namespace glcollide::shader
