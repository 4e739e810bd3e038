#pragma once
// Exact Bernstein coefficients of radial culling's phi(t) = n(t) . (p0(t) - q(t)) (GMP): the oracle
// the certified float classification (shaders/common/radial_sign.glsl) is judged by. Points move
// linearly from their position at t = 0 to their position at t = 1.

#include <glm/vec3.hpp>
#include <gmpxx.h>

#include <array>

namespace glcollide::cpu {

/// p0, p1, p2, q: the triangle's vertices and the observer.
using RadialPoints = std::array<glm::vec3, 4>;

/// The four exact Bernstein coefficients of phi over [0, 1], the middle two times 3:
/// B0, 3 B1, 3 B2, B3 (docs/culling.md, "Classification").
std::array<mpq_class, 4> exactRadialCoefficients(const RadialPoints& start, const RadialPoints& end);

/// The same four sums with every product of coordinate differences taken in absolute value: the
/// scale each coefficient's float rounding is relative to.
std::array<mpq_class, 4> exactRadialMagnitudes(const RadialPoints& start, const RadialPoints& end);

/// True when all four are > 0 (phi > 0 over the whole substep).
bool exactlyRadialPositive(const RadialPoints& start, const RadialPoints& end);

/// phi(t), exactly, from the points interpolated at t.
mpq_class exactRadialPhi(const RadialPoints& start, const RadialPoints& end, const mpq_class& t);

} // namespace glcollide::cpu
