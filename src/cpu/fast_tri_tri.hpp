#pragma once
// CPU twin of the fast narrow phase (shaders/common/tri_tri.glsl without GLC_PRECISION_ROBUST):
// Moeller 1997, "A Fast Triangle-Triangle Intersection Test" (NoDivTriTriIsect), in float,
// operation for operation in the shader's order. It reproduces the GPU's fast answers wherever
// the GPU rounds the same way (no FMA contraction, no denormal flushing on the decisive values);
// docs/narrow-phase.md reports how often the two differ and how fast differs from the oracle.

#include <glm/vec3.hpp>

#include <array>

namespace glcollide::cpu {

using FloatTriangle = std::array<glm::vec3, 3>;

/// Absolute coplanarity threshold on the unnormalised plane distances N.x + d (length^3): the
/// paper's EPSILON.
inline constexpr float kFastTriTriEpsilon = 0.000001f;

/// Moeller's test in float: true when the triangles are judged to intersect. Not exact: see
/// docs/narrow-phase.md for its measured disagreements with cpu::exactTrianglesIntersect.
bool fastTrianglesIntersect(const FloatTriangle& a, const FloatTriangle& b);

} // namespace glcollide::cpu
