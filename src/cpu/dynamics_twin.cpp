#include "cpu/dynamics_twin.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace glcollide::cpu {

void nodeForce(const NodeForceParams& params, const std::vector<std::uint32_t>& faceIndices,
               const model::Csr& nodeFaces, NodeState& state) {
    const std::size_t n = state.positions.size();
    state.forces.assign(n, glm::dvec3(0.0));
    for (std::size_t i = 0; i < n; ++i) {
        const double w = state.inverseMasses[i];
        if (w <= 0.0) continue;
        const double m = 1.0 / w;
        glm::dvec3 f(0.0);
        if (params.gravity) f += m * params.gravityAcceleration;
        if (params.damping) f -= (params.dampingCoefficient * m) * state.velocities[i];
        if (params.wind) {
            for (std::uint32_t k = nodeFaces.offsets[i]; k < nodeFaces.offsets[i + 1]; ++k) {
                const std::uint32_t face = nodeFaces.items[k];
                const std::uint32_t a = faceIndices[3 * face], b = faceIndices[3 * face + 1],
                                    c = faceIndices[3 * face + 2];
                const glm::dvec3 twiceAreaNormal = glm::cross(state.positions[b] - state.positions[a],
                                                              state.positions[c] - state.positions[a]);
                const double twiceArea = glm::length(twiceAreaNormal);
                if (twiceArea <= 0.0) continue; // a degenerate face catches no wind
                const glm::dvec3 normal = twiceAreaNormal / twiceArea;
                const glm::dvec3 faceVelocity =
                    (state.velocities[a] + state.velocities[b] + state.velocities[c]) / 3.0;
                const double normalSpeed = glm::dot(params.windVelocity - faceVelocity, normal);
                // drag · area · normal speed, one third to each corner.
                f += (params.windDrag * twiceArea * normalSpeed / 6.0) * normal;
            }
        }
        state.forces[i] = f;
    }
}

void springUpdate(const std::vector<model::FlatSpring>& springs, const model::Csr& nodeSprings,
                  NodeState& state) {
    const std::size_t n = state.positions.size();
    state.forces.resize(n, glm::dvec3(0.0));
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 f(0.0);
        for (std::uint32_t k = nodeSprings.offsets[i]; k < nodeSprings.offsets[i + 1]; ++k) {
            const model::FlatSpring& s = springs[nodeSprings.items[k]];
            const std::uint32_t j = s.a == i ? s.b : s.a;
            const glm::dvec3 d = state.positions[j] - state.positions[i];
            const double length = glm::length(d);
            if (length <= 0.0) continue; // coincident ends: no direction, no force
            const glm::dvec3 dir = d / length;
            const double magnitude = s.stiffness * (length - s.restLength) +
                                     s.damping * glm::dot(state.velocities[j] - state.velocities[i], dir);
            f += magnitude * dir;
        }
        state.forces[i] += f;
    }
}

void nodeUpdate(const NodeUpdateParams& params, NodeState& state) {
    const std::size_t n = state.positions.size();
    for (std::size_t i = 0; i < n; ++i) {
        const double w = state.inverseMasses[i];
        if (w <= 0.0) {
            state.velocities[i] = glm::dvec3(0.0);
            continue;
        }
        glm::dvec3 v = state.velocities[i];
        if (params.forces) v += (params.h * w) * state.forces[i];
        glm::dvec3 x = state.positions[i] + params.h * v;
        if (params.ground && x.y < params.groundHeight) {
            x.y = params.groundHeight;
            if (v.y < 0.0) {
                const double normalSpeed = -v.y;
                v.y = params.restitution * normalSpeed;
                const double tangentialSpeed = std::sqrt(v.x * v.x + v.z * v.z);
                if (tangentialSpeed > 0.0) {
                    // Coulomb: the normal impulse (1+e)·|vn| bounds the tangential change.
                    const double scale = std::max(0.0, 1.0 - params.friction * (1.0 + params.restitution) *
                                                                 normalSpeed / tangentialSpeed);
                    v.x *= scale;
                    v.z *= scale;
                }
            }
        }
        state.positions[i] = x;
        state.velocities[i] = v;
    }
}

Energy energy(const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& velocities,
              const std::vector<double>& masses, const std::vector<double>& inverseMasses,
              const glm::dvec3* gravity, const std::vector<model::FlatSpring>* springs) {
    Energy e;
    for (std::size_t i = 0; i < positions.size(); ++i) {
        if (inverseMasses[i] <= 0.0) continue; // pinned nodes neither move nor change energy
        const double kinetic = 0.5 * masses[i] * glm::dot(velocities[i], velocities[i]);
        const double gravitational = gravity ? -masses[i] * glm::dot(*gravity, positions[i]) : 0.0;
        e.kinetic += kinetic;
        e.gravitational += gravitational;
        e.magnitude += kinetic + std::abs(gravitational);
    }
    if (springs)
        for (const model::FlatSpring& s : *springs) {
            const double length = glm::length(positions[s.b] - positions[s.a]);
            const double stretch = length - s.restLength;
            e.elastic += 0.5 * s.stiffness * stretch * stretch;
            // A float length − L is off relative to length + L, not to the stretch.
            e.magnitude += 0.5 * s.stiffness * stretch * stretch +
                           s.stiffness * std::abs(stretch) * (length + s.restLength);
        }
    return e;
}

Potential incrementalPotential(const PotentialParams& p, const std::vector<glm::dvec3>& startPositions,
                               const std::vector<glm::dvec3>& startVelocities,
                               const std::vector<glm::dvec3>& velocities,
                               const std::vector<double>& inverseMasses,
                               const std::vector<model::FlatSpring>* springs) {
    const std::size_t n = startPositions.size();
    std::vector<glm::dvec3> x(n), v(n);
    for (std::size_t i = 0; i < n; ++i) {
        const bool free = inverseMasses[i] > 0.0;
        v[i] = free ? velocities[i] : glm::dvec3(0.0); // pinned nodes keep x0 (their v is not read)
        x[i] = free ? startPositions[i] + p.h * velocities[i] : startPositions[i];
    }
    Potential phi;
    for (std::size_t i = 0; i < n; ++i) {
        if (inverseMasses[i] <= 0.0) continue;
        const double m = 1.0 / inverseMasses[i];
        const glm::dvec3 dv = v[i] - startVelocities[i];
        const double inertia = 0.5 * m * glm::dot(dv, dv);
        const double air = 0.5 * p.h * p.airDamping * m * glm::dot(v[i], v[i]);
        const double gravity = -m * glm::dot(p.gravity, x[i]);
        const double depth = std::max(p.groundLevel - x[i].y, 0.0);
        const double ground = p.groundStiffness > 0.0 ? 0.5 * p.groundStiffness * depth * depth : 0.0;
        const double groundScale =
            p.groundStiffness > 0.0
                ? ground + p.groundStiffness * depth * (std::abs(x[i].y) + std::abs(p.groundLevel))
                : 0.0;
        phi.total += inertia + air + gravity + ground;
        phi.magnitude += inertia +
                         m * glm::length(dv) * (glm::length(v[i]) + glm::length(startVelocities[i])) + air +
                         std::abs(gravity) + groundScale;
    }
    if (springs)
        for (const model::FlatSpring& s : *springs) {
            const glm::dvec3 d = x[s.b] - x[s.a];
            const double length = glm::length(d);
            const double stretch = length - s.restLength;
            const double elastic = 0.5 * s.stiffness * stretch * stretch;
            phi.total += elastic;
            phi.magnitude += elastic + s.stiffness * std::abs(stretch) * (length + s.restLength);
            if (!(length > 0.0) || s.damping == 0.0) continue;
            // Velocities as the shader reads them: a pinned node's own (unchanged) velocity.
            const glm::dvec3 va = inverseMasses[s.a] > 0.0 ? v[s.a] : velocities[s.a];
            const glm::dvec3 vb = inverseMasses[s.b] > 0.0 ? v[s.b] : velocities[s.b];
            const double rate = glm::dot(vb - va, d / length);
            const double dissipation = 0.5 * p.h * s.damping * rate * rate;
            phi.total += dissipation;
            phi.magnitude +=
                dissipation + p.h * s.damping * std::abs(rate) * (glm::length(va) + glm::length(vb));
        }
    return phi;
}

} // namespace glcollide::cpu
