#pragma once
// Exact triangle-triangle intersection in rational arithmetic (GMP): the oracle the collision
// tests and benchmarks compare the GPU narrow phase with. Inputs are doubles, which GMP rationals
// represent exactly, so every sign below is exact: no epsilon anywhere.
//
// Semantics: triangles are closed point sets (touching at a vertex or along an edge counts as
// intersecting); coplanar pairs are decided in their common plane; a zero-area triangle is the
// segment between its two farthest vertices (or the point, when all three coincide), so
// degenerate input is decided exactly too instead of being dropped.
//
// Where things live: src/model/ holds the model the GPU and the twins share (no GL, no GMP);
// src/cpu/ the CPU twins of the GPU passes; src/cpu/oracle/ (here) the references they and the GPU
// are judged by: exact_tri_tri (GMP), ground_truth (exact intersecting pairs of a scene, deepest
// penetration) and tri_tri_cases (the triangle pairs, with the oracle on a float pair).

#include <glm/vec3.hpp>

#include <array>

namespace glcollide::cpu {

using Triangle = std::array<glm::dvec3, 3>;

/// True when the closed triangles share at least one point. Exact for all finite inputs.
bool exactTrianglesIntersect(const Triangle& a, const Triangle& b);

} // namespace glcollide::cpu
