#pragma once
// A user-given observer of radial culling (decision 0025, "User observers"): a point given in an
// object's coordinates must move with the object. It is tied to four of the object's nodes as an
// affine combination, Σ w_k x_k with Σ w_k = 1, equal to the point at the initial positions and
// carried exactly by any affine motion of those four (a rigid motion, a scaling, a shear), and
// roughly by the deformations the object goes through. GL-free.

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glcollide::model {

struct ObserverFrame {
    std::array<std::uint32_t, 4> nodes{}; ///< indices into the positions given to observerFrame
    std::array<double, 4> weights{};      ///< Σ = 1; the point = Σ weights[k]·positions[nodes[k]]
};

/// Local frames (session 18): a frame spread over the whole object follows it only while the
/// object moves roughly affinely; a sleeve twisting about its axis turns its two ends against each
/// other, and a point tied to nodes of both lands anywhere (docs/culling.md, "Segment observers").
/// So the frame is taken from the point's nearest nodes where they allow it: the kLocalFrameNodes
/// nearest first, then twice as many, and so on, until their four spread nodes form a tetrahedron
/// of 6·volume > kLocalFrameShape·(their largest extent)³ whose weights for the point all lie
/// within ±kLocalFrameWeight (the point not far outside it).
///   kLocalFrameNodes: range >= 4; suggested 16 (a ring of a tube and its neighbour at 32).
///   kLocalFrameShape: range (0, 1/6]; suggested 10⁻³ (a tet flatter than that amplifies the
///                     nodes' rounding into the point; a regular tet of edge s has 6·volume 0.7 s³).
///   kLocalFrameWeight: range >= 1; suggested 2 (an extrapolation beyond that amplifies motion
///                      that is not affine).
inline constexpr std::size_t kLocalFrameNodes = 16;
inline constexpr double kLocalFrameShape = 1e-3;
inline constexpr double kLocalFrameWeight = 2.0;

/// The frame of `point` over `positions` (one object's nodes): four nodes spread as far as the
/// nodes they are chosen from allow — the node farthest from those nodes' mean, the node farthest
/// from it, the node farthest from the line through both, the node farthest from the plane through
/// the three (ties: the lowest index) — and the point's barycentric weights in their tetrahedron;
/// chosen from the point's nearest nodes (above), or else from all of them. Throws
/// std::invalid_argument when all the nodes span (almost) no volume — six times the tetrahedron's volume
/// below 10⁻⁶ of the cube of the object's largest extent (a flat or straight object) — whose frame
/// could not follow a point out of its plane.
ObserverFrame observerFrame(const std::vector<glm::dvec3>& positions, const glm::dvec3& point);

} // namespace glcollide::model
