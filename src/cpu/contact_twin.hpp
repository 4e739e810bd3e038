#pragma once
// CPU twin of the ContactResponse pass (shaders/passes/contact_response.comp) in double
// precision: the same contact rules, case by case, on the same inputs. Forces are not quantised
// (the GPU's fixed-point sums differ from these by at most 0.5/forceScale per contribution).

#include "core/contact_params.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glcollide::cpu {

struct ContactInput {
    const std::vector<glm::dvec3>* positions = nullptr;      ///< m, per node
    const std::vector<glm::dvec3>* velocities = nullptr;     ///< m/s, per node
    const std::vector<std::uint32_t>* faceIndices = nullptr; ///< 3 per face
    const std::vector<std::uint32_t>* faceOwned = nullptr;   ///< GLC_OWN_* bits per face
    const std::vector<std::uint8_t>* faceClosed = nullptr;   ///< 1 when the face's object is closed
};

struct ContactResult {
    std::vector<glm::dvec3> forces;           ///< N, per node
    std::uint32_t contacts = 0;               ///< vertex-face and edge-edge contacts that produced a force
    std::vector<std::uint32_t> contributions; ///< per node: contacts that added to its force
};

/// Penalty contact forces of the candidate face pairs.
ContactResult contactForces(const ContactParams& params, const ContactInput& in,
                            const std::vector<std::array<std::uint32_t, 2>>& candidates);

/// Barycentric weights of the point of triangle abc closest to p (Ericson §5.1.5).
glm::dvec3 closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& c);
/// Parameters (s, t) of the closest points of segments p0p1 and q0q1 (Ericson §5.1.9).
std::array<double, 2> closestSegmentParams(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& q0,
                                           const glm::dvec3& q1);

} // namespace glcollide::cpu
