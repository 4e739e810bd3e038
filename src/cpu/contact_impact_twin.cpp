#include "cpu/contact_impact_twin.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace glcollide::cpu {
namespace {

struct Impact {
    bool acting = false;
    std::array<double, 4> share{};
    double perSpeed = 0.0, target = 0.0, impactSpeed = 0.0, normalPerImpulse = 1.0;
    bool met = false;
};

template <typename Value> glm::dvec3 weightedSum(const ContactGeometry& c, const std::vector<Value>& values) {
    glm::dvec3 sum(0.0);
    for (int k = 0; k < 4; ++k) sum += c.weights[k] * glm::dvec3(values[c.nodes[k]]);
    return sum;
}

Impact impactOf(const ContactGeometry& c, const ContactParams& contact, const ContactImpactParams& params,
                const ContactImpactInput& in, const std::vector<double>& w) {
    Impact im;
    double wSum = 0.0, movingWeights = 0.0;
    for (int k = 0; k < 4; ++k) {
        const double wk = w[c.nodes[k]];
        im.share[k] = c.weights[k] * c.weights[k] * wk;
        wSum += im.share[k];
        if (wk > 0.0) movingWeights += c.weights[k];
    }
    if (!(wSum > 0.0)) return {};
    const glm::dvec3& u = c.normal;
    const double vn0 = glm::dot(weightedSum(c, *in.startVelocity), u);
    const double d0 = glm::dot(weightedSum(c, *in.start), u);
    const double an = glm::dot(params.gravity, u) * movingWeights;
    const double gap = std::max(d0 - contact.thickness, 0.0);
    if (!(vn0 < 0.0 || (an < 0.0 && gap > 0.0))) return {};
    const double impactSpeed = std::sqrt(std::max(vn0 * vn0 - 2.0 * an * gap, 0.0));
    if (!(impactSpeed > params.restingSpeed)) return {};
    im.acting = true;
    im.perSpeed = 1.0 / (wSum * contact.substep);
    im.target = params.restitution * impactSpeed;
    im.impactSpeed = impactSpeed;
    im.met = gap > 0.0;
    return im;
}

} // namespace

double contactImpactScale(double largestChange) {
    const double units = 2147483647.0 / 1024.0;
    return largestChange > 0.0 ? std::exp2(std::floor(std::log2(units / (4.0 * largestChange)))) : 1.0;
}

ContactImpactResult contactImpact(const ContactParams& contact, const ContactImpactParams& params,
                                  const ContactImpactInput& in, const FeaturePairList& pairs,
                                  std::vector<glm::dvec3>& velocity) {
    if (!in.end.positions || !in.end.inverseMasses || !in.start || !in.startVelocity)
        throw std::invalid_argument(
            "contactImpact: positions, inverse masses, start and start velocities needed");
    ContactParams geometry = contact;
    geometry.sidesFromPrevious = false;           // sides from x1 itself
    geometry.thickness = 2.0 * contact.thickness; // the band searched
    const std::vector<ContactGeometry> contacts = contactGeometries(geometry, in.end, pairs);
    const std::vector<double>& w = *in.end.inverseMasses;
    const std::size_t nodes = velocity.size();
    std::vector<Impact> impacts;
    std::vector<int> count(nodes, 0);
    std::uint32_t acting = 0;
    double largestChange = 0.0;
    for (const ContactGeometry& c : contacts) {
        impacts.push_back(impactOf(c, contact, params, in, w));
        // Beyond the thickness only a pair that still approaches after the step takes part.
        const bool inBand = geometry.thickness - c.depth <= contact.thickness;
        if (!inBand && !(glm::dot(weightedSum(c, velocity), c.normal) < 0.0)) impacts.back().acting = false;
        if (!impacts.back().acting) continue;
        ++acting;
        Impact& im = impacts.back();
        // Friction's normal impulse per unit of λ (contact_impact.comp, mode 0).
        const double change = im.target - glm::dot(weightedSum(c, velocity), c.normal);
        im.normalPerImpulse = im.met && change > 0.0 ? (im.target + im.impactSpeed) / change : 1.0;
        double wSum = 0.0, reach = 0.0;
        for (int k = 0; k < 4; ++k) {
            wSum += im.share[k];
            reach = std::max(reach, std::abs(c.weights[k]) * w[c.nodes[k]]);
        }
        largestChange = std::max(
            largestChange, std::abs(im.target - glm::dot(weightedSum(c, velocity), c.normal)) * reach / wSum);
        for (int k = 0; k < 4; ++k)
            if (impacts.back().share[k] > 0.0) ++count[c.nodes[k]];
    }
    std::vector<double> impulse(contacts.size(), 0.0); // λ per pair, N over the substep
    // One dispatch: every pair's force from the velocities before it, then the apply.
    const auto dispatch = [&](bool frictionPass) {
        std::vector<glm::dvec3> sums(nodes, glm::dvec3(0.0));
        for (std::size_t p = 0; p < contacts.size(); ++p) {
            const Impact& im = impacts[p];
            if (!im.acting) continue;
            const ContactGeometry& c = contacts[p];
            int largest = 1;
            for (int k = 0; k < 4; ++k)
                if (im.share[k] > 0.0) largest = std::max(largest, count[c.nodes[k]]);
            const double perSpeed = im.perSpeed / largest;
            const glm::dvec3 vRel = weightedSum(c, velocity);
            const double vn = glm::dot(vRel, c.normal);
            glm::dvec3 F(0.0);
            if (!frictionPass) {
                const double before = impulse[p];
                impulse[p] = std::clamp(before + (im.target - vn) * perSpeed, 0.0, contact.forceCap);
                F = (impulse[p] - before) * c.normal;
            } else {
                const glm::dvec3 vt = vRel - vn * c.normal;
                const double speed = glm::length(vt);
                if (!(speed > 0.0)) continue;
                F = -vt *
                    (std::min(contact.friction * im.normalPerImpulse * impulse[p], speed * perSpeed) / speed);
            }
            for (int k = 0; k < 4; ++k) sums[c.nodes[k]] += c.weights[k] * F;
        }
        for (std::size_t i = 0; i < nodes; ++i)
            if (w[i] > 0.0) velocity[i] += contact.substep * w[i] * sums[i];
    };
    for (int round = 0; round < params.iterations; ++round) dispatch(false);
    if (contact.friction > 0.0) dispatch(true);
    return {acting, std::vector<std::uint32_t>(count.begin(), count.end()), largestChange};
}

} // namespace glcollide::cpu
