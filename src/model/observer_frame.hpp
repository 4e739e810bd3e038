#pragma once
// A user-given observer of radial culling (decision 0025, "User observers"): a point given in an
// object's coordinates must move with the object. It is tied to four of the object's nodes as an
// affine combination, Σ w_k x_k with Σ w_k = 1, equal to the point at the initial positions and
// carried exactly by any affine motion of those four (a rigid motion, a scaling, a shear), and
// roughly by the deformations the object goes through. GL-free.

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::model {

struct ObserverFrame {
    std::array<std::uint32_t, 4> nodes{}; ///< indices into the positions given to observerFrame
    std::array<double, 4> weights{};      ///< Σ = 1; the point = Σ weights[k]·positions[nodes[k]]
};

/// The frame of `point` over `positions` (one object's nodes): four nodes spread as far as the
/// object allows — the node farthest from the nodes' mean, the node farthest from it, the node
/// farthest from the line through both, the node farthest from the plane through the three (ties:
/// the lowest index) — and the point's barycentric weights in their tetrahedron. Throws
/// std::invalid_argument when the nodes span (almost) no volume — six times the tetrahedron's volume
/// below 10⁻⁶ of the cube of the object's largest extent (a flat or straight object) — whose frame
/// could not follow a point out of its plane.
ObserverFrame observerFrame(const std::vector<glm::dvec3>& positions, const glm::dvec3& point);

} // namespace glcollide::model
