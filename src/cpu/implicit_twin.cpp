#include "cpu/implicit_twin.hpp"

#include "core/gpu_layout.hpp"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace glcollide::cpu {
namespace {

/// k·max(0, 1 − L/l) across the spring and k·(1 − max(0, 1 − L/l)) along it: K_s = kT·I + kA·u uᵀ.
struct SpringStiffness {
    double transverse = 0, along = 0;
};

SpringStiffness stiffnessOf(const model::FlatSpring& s, double length) {
    const double t = std::max(0.0, 1.0 - s.restLength / length); // the definiteness clamp
    return {s.stiffness * t, s.stiffness * (1.0 - t)};
}

/// Calls f(j, block) for every spring of node i that has a direction, in row order (none without
/// the springs effect): the one walk of a row that assembly and the product share.
template <typename F>
void forEachSpringBlock(const ImplicitParams& p, const std::vector<model::FlatSpring>& springs,
                        const model::Csr& rows, const NodeState& state, std::size_t i, F&& f) {
    if (!p.springs) return;
    for (std::uint32_t k = rows.offsets[i]; k < rows.offsets[i + 1]; ++k) {
        const model::FlatSpring& s = springs[rows.items[k]];
        const std::uint32_t j = s.a == i ? s.b : s.a;
        const SpringBlock blk = springBlock(s, state.positions[i], state.positions[j], state.velocities[i],
                                            state.velocities[j], p.h);
        if (blk.valid) f(j, blk);
    }
}

/// Calls f(i, a_i, contact) for every row a contact adds to: a free node (inverse mass > 0) with a
/// weight that is not 0 (implicit_contact.glsl's hasRow).
template <typename F> void forEachContactRow(const ImplicitContactSet* set, const NodeState& state, F&& f) {
    if (!set) return;
    for (const ContactGeometry& c : set->contacts)
        for (std::size_t k = 0; k < 4; ++k)
            if (state.inverseMasses[c.nodes[k]] > 0.0 && c.weights[k] != 0.0) f(c.nodes[k], c.weights[k], c);
}

/// Σ_j a_j x_j over the contact's nodes (x_j of pinned nodes included unless `freeOnly`).
glm::dvec3 weightedSum(const ContactGeometry& c, const std::vector<glm::dvec3>& x, const NodeState& state,
                       bool freeOnly) {
    glm::dvec3 sum(0.0);
    for (std::size_t k = 0; k < 4; ++k)
        if (!freeOnly || state.inverseMasses[c.nodes[k]] > 0.0) sum += c.weights[k] * x[c.nodes[k]];
    return sum;
}

/// The pair's relative normal velocity u·Σ a_j v_j at `velocities`.
double normalSpeed(const ContactGeometry& c, const std::vector<glm::dvec3>& velocities) {
    glm::dvec3 relative(0.0);
    for (std::size_t k = 0; k < 4; ++k) relative += c.weights[k] * velocities[c.nodes[k]];
    return glm::dot(c.normal, relative);
}

/// Whether the pair closes at `velocities`: u·Σ a_j v_j below −GLC_APPROACH_SLACK·Σ |a_j||v_j|
/// (implicit_contact_find.comp's approaching).
bool approaching(const ContactGeometry& c, const std::vector<glm::dvec3>& velocities) {
    glm::dvec3 relative(0.0);
    double scale = 0.0;
    for (std::size_t k = 0; k < 4; ++k) {
        relative += c.weights[k] * velocities[c.nodes[k]];
        scale += std::abs(c.weights[k]) * glm::length(velocities[c.nodes[k]]);
    }
    return glm::dot(c.normal, relative) < -GLC_APPROACH_SLACK * scale;
}

/// The assembled per-node pieces of the system: right-hand side and diagonal blocks.
struct Assembly {
    std::vector<glm::dvec3> b;
    std::vector<glm::dmat3> diagonal;
};

double massFactor(const ImplicitParams& p) {
    return 1.0 + p.h * p.airDamping;
}

/// `startVelocities`: the Newton step's system (b = h·f − m·(v − v0), no stiffness term).
Assembly assemble(const ImplicitParams& p, const std::vector<model::FlatSpring>& springs,
                  const model::Csr& rows, const NodeState& state, const ImplicitContactSet* contacts,
                  const std::vector<glm::dvec3>* startVelocities = nullptr) {
    const std::size_t n = state.positions.size();
    Assembly a{std::vector<glm::dvec3>(n, glm::dvec3(0.0)), std::vector<glm::dmat3>(n, glm::dmat3(0.0))};
    for (std::size_t i = 0; i < n; ++i) {
        const double w = state.inverseMasses[i];
        if (w <= 0.0) continue;
        glm::dvec3 f = state.forces[i];
        glm::dvec3 stiffnessTimesVelocity(0.0);
        glm::dmat3 d(massFactor(p) / w);
        forEachSpringBlock(p, springs, rows, state, i, [&](std::uint32_t j, const SpringBlock& blk) {
            f += blk.force * blk.u;
            d += glm::dmat3(blk.alpha) + blk.beta * glm::outerProduct(blk.u, blk.u);
            const glm::dvec3 dv = state.velocities[j] - state.velocities[i];
            stiffnessTimesVelocity +=
                blk.transverseStiffness * dv + blk.alongStiffness * glm::dot(blk.u, dv) * blk.u;
        });
        a.b[i] = startVelocities ? p.h * f - (state.velocities[i] - (*startVelocities)[i]) / w
                                 : p.h * f + p.h * p.h * stiffnessTimesVelocity;
        a.diagonal[i] = d;
    }
    forEachContactRow(contacts, state, [&](std::uint32_t i, double ai, const ContactGeometry& c) {
        const double k = contacts->stiffness;
        const glm::dvec3 vRel = weightedSum(c, state.velocities, state, false);
        a.b[i] += p.h * ai * k * c.depth * c.normal;
        if (!startVelocities) a.b[i] -= p.h * p.h * k * ai * glm::dot(c.normal, vRel) * c.normal;
        a.diagonal[i] += p.h * p.h * k * ai * ai * glm::outerProduct(c.normal, c.normal);
    });
    return a;
}

/// q = A·x over the free nodes (pinned entries of x are ignored, pinned rows of q are 0).
std::vector<glm::dvec3> multiply(const ImplicitParams& p, const std::vector<model::FlatSpring>& springs,
                                 const model::Csr& rows, const NodeState& state,
                                 const std::vector<glm::dvec3>& x, const ImplicitContactSet* contacts) {
    const std::size_t n = state.positions.size();
    std::vector<glm::dvec3> q(n, glm::dvec3(0.0));
    for (std::size_t i = 0; i < n; ++i) {
        const double w = state.inverseMasses[i];
        if (w <= 0.0) continue;
        glm::dvec3 sum = (massFactor(p) / w) * x[i];
        forEachSpringBlock(p, springs, rows, state, i, [&](std::uint32_t j, const SpringBlock& blk) {
            const glm::dvec3 xj = state.inverseMasses[j] > 0.0 ? x[j] : glm::dvec3(0.0);
            const glm::dvec3 d = x[i] - xj;
            sum += blk.alpha * d + blk.beta * glm::dot(blk.u, d) * blk.u;
        });
        q[i] = sum;
    }
    forEachContactRow(contacts, state, [&](std::uint32_t i, double ai, const ContactGeometry& c) {
        const glm::dvec3 xRel = weightedSum(c, x, state, true); // pinned nodes are not in the system
        q[i] += p.h * p.h * contacts->stiffness * ai * glm::dot(c.normal, xRel) * c.normal;
    });
    return q;
}

double dotAll(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
    double s = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) s += glm::dot(a[i], b[i]);
    return s;
}

} // namespace

SpringBlock springBlock(const model::FlatSpring& s, const glm::dvec3& xi, const glm::dvec3& xj,
                        const glm::dvec3& vi, const glm::dvec3& vj, double h) {
    SpringBlock b;
    const glm::dvec3 d = xj - xi;
    const double length = glm::length(d);
    if (length <= 0.0) return b; // coincident ends: no direction, as in SpringUpdate
    b.u = d / length;
    const SpringStiffness st = stiffnessOf(s, length);
    b.transverseStiffness = st.transverse;
    b.alongStiffness = st.along;
    b.alpha = h * h * st.transverse;
    b.beta = h * s.damping + h * h * st.along;
    b.force = s.stiffness * (length - s.restLength) + s.damping * glm::dot(vj - vi, b.u);
    b.valid = true;
    return b;
}

ImplicitContactSet implicitContacts(const ContactParams& params, const ContactInput& in,
                                    const FeaturePairList& pairs) {
    ContactParams band = params; // the thickness plus the margin, taken off each depth again
    band.thickness = params.thickness + params.solveMargin;
    ImplicitContactSet set{{}, params.stiffness};
    for (ContactGeometry c : contactGeometries(band, in, pairs, Crossings::AtAnyDepth)) {
        c.depth -= params.solveMargin;
        if (!(c.depth > 0.0)) {
            if (!approaching(c, *in.velocities)) continue;
            c.depth = 0.0; // within the margin: stiffness, no force
        } else if (const double vn = normalSpeed(c, *in.velocities); params.leavingStep > 0.0 &&
                                                                     vn > params.leavingSpeed &&
                                                                     vn * params.leavingStep >= c.depth) {
            continue; // leaving: its own motion takes it out of the thickness within the step
        }
        set.contacts.push_back(c);
    }
    return set;
}

ImplicitSolveStats implicitVelocityUpdate(const ImplicitParams& params,
                                          const std::vector<model::FlatSpring>& springs,
                                          const model::Csr& nodeSprings, NodeState& state,
                                          const ImplicitContactSet* contacts) {
    const std::size_t n = state.positions.size();
    const Assembly a = assemble(params, springs, nodeSprings, state, contacts);
    std::vector<glm::dmat3> inverse(n, glm::dmat3(0.0));
    for (std::size_t i = 0; i < n; ++i)
        if (state.inverseMasses[i] > 0.0) inverse[i] = glm::inverse(a.diagonal[i]);
    const auto precondition = [&](const std::vector<glm::dvec3>& r) {
        std::vector<glm::dvec3> z(n);
        for (std::size_t i = 0; i < n; ++i) z[i] = inverse[i] * r[i];
        return z;
    };
    std::vector<glm::dvec3> dv(n, glm::dvec3(0.0)), r = a.b, z = precondition(r), direction = z;
    double rz = dotAll(r, z), rr = dotAll(r, r), previousRz = 0.0;
    const double bb = rr;
    const double inverseTol2 = 1.0 / (params.tolerance * params.tolerance);
    ImplicitSolveStats stats;
    for (int k = 0;; ++k) {
        if (rr * inverseTol2 <= bb || rz <= 0.0) { // the GPU's rule
            stats.iterations = k;
            stats.converged = true;
            break;
        }
        if (k == params.maxIterations) {
            stats.iterations = k;
            break;
        }
        const double beta = k == 0 ? 0.0 : rz / previousRz;
        for (std::size_t i = 0; i < n; ++i) direction[i] = z[i] + beta * direction[i];
        const std::vector<glm::dvec3> q = multiply(params, springs, nodeSprings, state, direction, contacts);
        const double pq = dotAll(direction, q);
        const double alpha = pq > 0.0 ? rz / pq : 0.0; // as the GPU: no step without p·q > 0
        for (std::size_t i = 0; i < n; ++i) {
            dv[i] += alpha * direction[i];
            r[i] -= alpha * q[i];
        }
        z = precondition(r);
        previousRz = rz;
        rz = dotAll(r, z);
        rr = dotAll(r, r);
    }
    stats.relativeResidual = bb > 0.0 ? std::sqrt(rr / bb) : 0.0;
    for (std::size_t i = 0; i < n; ++i) state.velocities[i] += dv[i];
    return stats;
}

namespace {
std::vector<glm::dvec3> denseSolve(const ImplicitParams& params,
                                   const std::vector<model::FlatSpring>& springs,
                                   const model::Csr& nodeSprings, const NodeState& state,
                                   const ImplicitContactSet* contacts,
                                   const std::vector<glm::dvec3>* startVelocities) {
    const std::size_t n = state.positions.size();
    std::vector<std::size_t> freeIndex(n, n);
    std::vector<std::size_t> freeNodes;
    for (std::size_t i = 0; i < n; ++i)
        if (state.inverseMasses[i] > 0.0) {
            freeIndex[i] = freeNodes.size();
            freeNodes.push_back(i);
        }
    const std::size_t m = 3 * freeNodes.size();
    // Column c of A is A·e_c: build it with the same product the solver uses.
    std::vector<double> A(m * m, 0.0), b(m, 0.0);
    const Assembly a = assemble(params, springs, nodeSprings, state, contacts, startVelocities);
    for (std::size_t c = 0; c < m; ++c) {
        std::vector<glm::dvec3> e(n, glm::dvec3(0.0));
        e[freeNodes[c / 3]][static_cast<int>(c % 3)] = 1.0;
        const std::vector<glm::dvec3> col = multiply(params, springs, nodeSprings, state, e, contacts);
        for (std::size_t r = 0; r < m; ++r) A[r * m + c] = col[freeNodes[r / 3]][static_cast<int>(r % 3)];
    }
    for (std::size_t r = 0; r < m; ++r) b[r] = a.b[freeNodes[r / 3]][static_cast<int>(r % 3)];
    // Cholesky A = L Lᵀ in place (lower triangle).
    for (std::size_t j = 0; j < m; ++j) {
        double d = A[j * m + j];
        for (std::size_t k = 0; k < j; ++k) d -= A[j * m + k] * A[j * m + k];
        d = std::sqrt(d);
        A[j * m + j] = d;
        for (std::size_t i = j + 1; i < m; ++i) {
            double s = A[i * m + j];
            for (std::size_t k = 0; k < j; ++k) s -= A[i * m + k] * A[j * m + k];
            A[i * m + j] = s / d;
        }
    }
    for (std::size_t i = 0; i < m; ++i) { // L y = b
        for (std::size_t k = 0; k < i; ++k) b[i] -= A[i * m + k] * b[k];
        b[i] /= A[i * m + i];
    }
    for (std::size_t i = m; i-- > 0;) { // Lᵀ x = y
        for (std::size_t k = i + 1; k < m; ++k) b[i] -= A[k * m + i] * b[k];
        b[i] /= A[i * m + i];
    }
    std::vector<glm::dvec3> dv(n, glm::dvec3(0.0));
    for (std::size_t r = 0; r < m; ++r) dv[freeNodes[r / 3]][static_cast<int>(r % 3)] = b[r];
    return dv;
}
} // namespace

std::vector<glm::dvec3> implicitVelocityChangeDense(const ImplicitParams& params,
                                                    const std::vector<model::FlatSpring>& springs,
                                                    const model::Csr& nodeSprings, const NodeState& state,
                                                    const ImplicitContactSet* contacts) {
    return denseSolve(params, springs, nodeSprings, state, contacts, nullptr);
}

std::vector<glm::dvec3> implicitNewtonChangeDense(const ImplicitParams& params,
                                                  const std::vector<model::FlatSpring>& springs,
                                                  const model::Csr& nodeSprings, const NodeState& state,
                                                  const std::vector<glm::dvec3>& startVelocities,
                                                  const ImplicitContactSet* contacts) {
    return denseSolve(params, springs, nodeSprings, state, contacts, &startVelocities);
}

std::vector<glm::dvec3> implicitNewtonRightHandSide(const ImplicitParams& params,
                                                    const std::vector<model::FlatSpring>& springs,
                                                    const model::Csr& nodeSprings, const NodeState& state,
                                                    const std::vector<glm::dvec3>& startVelocities,
                                                    const ImplicitContactSet* contacts) {
    return assemble(params, springs, nodeSprings, state, contacts, &startVelocities).b;
}

std::vector<glm::dvec3> implicitRightHandSide(const ImplicitParams& params,
                                              const std::vector<model::FlatSpring>& springs,
                                              const model::Csr& nodeSprings, const NodeState& state,
                                              const ImplicitContactSet* contacts) {
    return assemble(params, springs, nodeSprings, state, contacts).b;
}

std::vector<glm::dvec3> implicitSystemProduct(const ImplicitParams& params,
                                              const std::vector<model::FlatSpring>& springs,
                                              const model::Csr& nodeSprings, const NodeState& state,
                                              const std::vector<glm::dvec3>& x,
                                              const ImplicitContactSet* contacts) {
    return multiply(params, springs, nodeSprings, state, x, contacts);
}

double implicitRightHandSideNorm(const ImplicitParams& params, const std::vector<model::FlatSpring>& springs,
                                 const model::Csr& nodeSprings, const NodeState& state,
                                 const ImplicitContactSet* contacts) {
    const Assembly a = assemble(params, springs, nodeSprings, state, contacts);
    return std::sqrt(dotAll(a.b, a.b));
}

} // namespace glcollide::cpu
