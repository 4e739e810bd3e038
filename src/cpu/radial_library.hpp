#pragma once
// C++ view of radial view-based culling's classification and footprints
// (shaders/common/radial_sign.glsl, radial_footprint.glsl, radial_cells.glsl), compiled as C++ like the float
// CCD (cpu/ccd_library.hpp). Header-only on purpose: each translation unit compiles it with its own flags,
// which is how the relaxed-float test build runs it under fast-math, FMA contraction and FTZ/DAZ.

#include "core/gpu_layout.hpp" // GLC_RADIAL_CELL_* of shaders/common/layout.glsl
#include "cpu/shader_library.hpp"

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace glcollide::shader {
namespace {

using glm::dot;
using glm::length;
using glm::sqrt;
using vec2 = glm::vec2;
using vec4 = glm::vec4;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
#define GLC_PRECISE // C++ compilers evaluate the differences as written (no GLSL `precise` needed)
#include "common/radial_sign.glsl"
#include "common/radial_footprint.glsl"
#include "common/radial_cells.glsl"
#undef GLC_PRECISE
#pragma GCC diagnostic pop

} // namespace
} // namespace glcollide::shader
