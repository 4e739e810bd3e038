#include "cpu/contact_twin.hpp"

#include "model/features.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <optional>
#include <stdexcept>

namespace glcollide::cpu {
namespace {

// contact_vertex_face.comp's ownsClosestFeature: the interior always counts, the edge opposite vertex
// k (w[k] = 0) with its ownership bit, vertex k (w[k] = 1) with its bit and only from the lower
// node of the vertex-vertex pair.
bool ownsClosestFeature(std::uint32_t p, const std::array<std::uint32_t, 3>& face, const glm::dvec3& w,
                        std::uint32_t owned) {
    const int zeros = (w.x == 0.0) + (w.y == 0.0) + (w.z == 0.0);
    if (zeros == 0) return true;
    for (int k = 0; k < 3; ++k) {
        if (zeros == 2 && w[k] == 1.0)
            return (owned & (GLC_OWN_VERTEX0 << k)) != 0 && p < face[static_cast<std::size_t>(k)];
        if (zeros == 1 && w[k] == 0.0) return (owned & (GLC_OWN_EDGE01 << ((k + 1) % 3))) != 0;
    }
    return true;
}

// The face's object's kind, as contact_pair.glsl's vertexFaceContact reads it from GpuObject.
struct FaceKind {
    bool closed = false;       ///< the face's object is closed: the distance decides near its edges
    bool keepsOutside = false; ///< and the vertex is another object's: kept on the outside
};

FaceKind faceKind(const ContactInput& in, std::uint32_t node, std::uint32_t face) {
    if ((*in.faceClosed)[face] == 0) return {};
    if (!in.nodeObject || !in.faceObject)
        throw std::invalid_argument("cpu::ContactInput: a closed face needs nodeObject and faceObject");
    return {true, (*in.nodeObject)[node] != (*in.faceObject)[face]};
}

// contact_pair.glsl's coplanarSide: a vertex in another object's face plane then and now goes to the
// positive side of the normal turned towards a fixed direction when its object's nodes come first.
// Objects' nodes are consecutive, so the vertex's node comes before the face object's nodes exactly
// when it comes before the face's first node.
double coplanarSide(const ContactInput& in, std::uint32_t node, std::uint32_t face,
                    const std::array<std::uint32_t, 3>& f, const glm::dvec3& n) {
    if (!in.nodeObject || !in.faceObject)
        throw std::invalid_argument(
            "cpu::ContactInput: a vertex in a face's plane needs nodeObject and faceObject");
    if ((*in.nodeObject)[node] == (*in.faceObject)[face]) return 0.0;
    const double lower = node < f[0] ? 1.0 : -1.0;
    const double towards = glm::dot(n, glm::dvec3(0.5772, 0.5774, 0.5776)); // GLC_COPLANAR_DIRECTION
    return lower * (towards > 0.0 ? 1.0 : (towards < 0.0 ? -1.0 : 0.0));
}

// contact_pair.glsl: which feature pairs are contacts, and their nodes, weights, normal and depth.
struct Geometry {
    const ContactParams& p;
    const ContactInput& in;
    Crossings crossings = Crossings::WithinThickness;

    const glm::dvec3& x(std::uint32_t n) const { return (*in.positions)[n]; }
    const glm::dvec3& v(std::uint32_t n) const { return (*in.velocities)[n]; }
    glm::dvec3 previous(std::uint32_t n) const {
        return x(n) - (p.sidesFromPrevious ? p.substep : 0.0) * v(n);
    }

    // Whether `node` was strictly on the face's `side` at the start of the substep.
    bool crossedFacePlane(std::uint32_t node, const std::array<std::uint32_t, 3>& f, double side) const {
        const glm::dvec3 pa = previous(f[0]);
        const double sPrev =
            glm::dot(glm::cross(previous(f[1]) - pa, previous(f[2]) - pa), previous(node) - pa);
        return side != 0.0 && side * sPrev > 0.0;
    }

    std::optional<ContactGeometry> vertexFace(std::uint32_t node, std::uint32_t face,
                                              const std::array<std::uint32_t, 3>& f, std::uint32_t faceOwned,
                                              FaceKind kind) const {
        const glm::dvec3 &xp = x(node), &xa = x(f[0]), &xb = x(f[1]), &xc = x(f[2]);
        glm::dvec3 n = glm::cross(xb - xa, xc - xa);
        const double area2 = glm::length(n);
        if (!(area2 > 0.0)) return std::nullopt;
        n /= area2;
        const glm::dvec3 wts = closestOnTriangle(xp, xa, xb, xc);
        if (!ownsClosestFeature(node, f, wts, faceOwned)) return std::nullopt;
        const glm::dvec3 diff = xp - (wts.x * xa + wts.y * xb + wts.z * xc);
        const double d = glm::length(diff), s = glm::dot(n, xp - xa), h = p.thickness;
        double side = 1.0;
        if (!kind.keepsOutside) {
            const glm::dvec3 pa = previous(f[0]);
            const double sPrev =
                glm::dot(glm::cross(previous(f[1]) - pa, previous(f[2]) - pa), previous(node) - pa);
            side = sPrev > 0.0 ? 1.0 : (sPrev < 0.0 ? -1.0 : (s > 0.0 ? 1.0 : (s < 0.0 ? -1.0 : 0.0)));
            if (side == 0.0) side = coplanarSide(in, node, face, f, n);
        }
        const double sideDistance = side * s;
        const bool inside = wts.x > 0.0 && wts.y > 0.0 && wts.z > 0.0;
        glm::dvec3 u;
        double depth = 0.0;
        if (crossings == Crossings::AtAnyDepth && inside && !(sideDistance > -h) &&
            crossedFacePlane(node, f, side)) {
            u = side * n;
            depth = h - sideDistance;
        } else if (side != 0.0 && (inside || d == 0.0) && sideDistance < h && sideDistance > -h) {
            u = side * n;
            depth = h - sideDistance;
        } else if (d < h && d > 0.0 && (side != 0.0 || !inside)) { // contact_pair.glsl: no noise normal
            if (kind.closed || sideDistance >= 0.0) {
                u = diff / d;
                depth = h - d;
            } else {
                u = side * n;
                depth = h - sideDistance;
            }
        } else {
            return std::nullopt;
        }
        return ContactGeometry{{node, f[0], f[1], f[2]}, {1.0, -wts.x, -wts.y, -wts.z}, u, depth};
    }

    std::optional<ContactGeometry> edgeEdge(std::uint32_t p0, std::uint32_t p1, std::uint32_t q0,
                                            std::uint32_t q1) const {
        const auto [s, t] = closestSegmentParams(x(p0), x(p1), x(q0), x(q1));
        if (!(s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)) return std::nullopt; // an endpoint: vertex-face
        const glm::dvec3 diff = (x(p0) + s * (x(p1) - x(p0))) - (x(q0) + t * (x(q1) - x(q0)));
        const double d = glm::length(diff);
        const glm::dvec3 diffPrev = (previous(p0) + s * (previous(p1) - previous(p0))) -
                                    (previous(q0) + t * (previous(q1) - previous(q0)));
        const bool crossed = glm::dot(diffPrev, diff) < 0.0;
        if (!(d < p.thickness) && !(crossings == Crossings::AtAnyDepth && crossed)) return std::nullopt;
        glm::dvec3 u;
        double depth = 0.0;
        if (d > 0.0 && glm::dot(diffPrev, diff) >= 0.0) {
            u = diff / d;
            depth = p.thickness - d;
        } else if (d > 0.0) {
            u = -diff / d;
            depth = p.thickness + d;
        } else {
            const double dPrev = glm::length(diffPrev);
            if (!(dPrev > 0.0)) return std::nullopt;
            u = diffPrev / dPrev;
            depth = p.thickness;
        }
        return ContactGeometry{{p0, p1, q0, q1}, {1.0 - s, s, t - 1.0, -t}, u, depth};
    }
};

/// Calls f(contact) for every contact among `pairs`, in list order (vertex-face, then edge-edge).
template <typename F>
void forEachContact(const ContactParams& params, const ContactInput& in, const FeaturePairList& pairs, F&& f,
                    Crossings crossings = Crossings::WithinThickness) {
    const Geometry geometry{params, in, crossings};
    const std::vector<std::uint32_t>& idx = *in.faceIndices;
    for (const IndexPair& vf : pairs.vertexFace) {
        const auto [node, face] = vf;
        const std::array<std::uint32_t, 3> nodes{idx[3 * face], idx[3 * face + 1], idx[3 * face + 2]};
        if (const auto c =
                geometry.vertexFace(node, face, nodes, (*in.faceOwned)[face], faceKind(in, node, face)))
            f(*c);
    }
    for (const IndexPair& ee : pairs.edgeEdge) {
        const auto [edgeA, edgeB] = ee;
        const auto a = model::faceEdge(idx, edgeA / 3, static_cast<int>(edgeA % 3));
        const auto b = model::faceEdge(idx, edgeB / 3, static_cast<int>(edgeB % 3));
        if (const auto c = geometry.edgeEdge(a[0], a[1], b[0], b[1])) f(*c);
    }
}

// The two passes of the response: Count counts the active contacts per node, Apply adds the
// forces (contact_force.glsl's u_countPass).
enum class Pass { Count, Apply };

struct Solver {
    const ContactParams& p;
    const ContactInput& in;
    ContactResult& out;
    std::vector<std::uint32_t>& approaching; // per node: active contacts, from the count pass
    Pass pass = Pass::Count;

    const glm::dvec3& v(std::uint32_t n) const { return (*in.velocities)[n]; }
    double w(std::uint32_t n) const { return in.inverseMasses ? (*in.inverseMasses)[n] : 1.0; }
    double normalForce(double depth, double normalSpeed) const {
        return std::clamp(p.stiffness * depth - p.damping * normalSpeed, 0.0, p.forceCap);
    }

    // contact_force.glsl's actingCount: the largest count of acting contacts on the moved nodes.
    std::uint32_t actingCount(const std::array<std::uint32_t, 4>& n,
                              const std::array<double, 4>& share) const {
        std::uint32_t count = 1;
        for (std::size_t i = 0; i < 4; ++i)
            if (share[i] > 0.0) count = std::max(count, approaching[n[i]]);
        return count;
    }

    // contact_force.glsl's frictionForce: against vt, at most μ·f and at most what stops vt.
    glm::dvec3 frictionForce(const glm::dvec3& vt, double f, double perSpeed) const {
        const double speed = glm::length(vt);
        if (!(speed > 0.0)) return glm::dvec3(0.0);
        const double magnitude = std::min(p.friction * f, speed * perSpeed);
        return vt * (-magnitude / speed);
    }

    // contact_force.glsl's addContactForce: F on side A, spread by the signed weights.
    bool addContactForce(const std::array<std::uint32_t, 4>& n, const std::array<double, 4>& a,
                         const glm::dvec3& F) {
        for (std::size_t i = 0; i < 4; ++i) {
            out.forces[n[i]] += a[i] * F;
            ++out.contributions[n[i]];
        }
        ++out.contacts;
        return true;
    }

    // contact_force.glsl's respond.
    bool respond(const std::array<std::uint32_t, 4>& n, const std::array<double, 4>& a, const glm::dvec3& u,
                 double depth) {
        glm::dvec3 vRel(0.0);
        std::array<double, 4> share{};
        double wSum = 0.0;
        for (std::size_t i = 0; i < 4; ++i) {
            vRel += a[i] * v(n[i]);
            share[i] = a[i] * a[i] * w(n[i]);
            wSum += share[i];
        }
        const double vn = glm::dot(vRel, u);
        const bool bridson = p.velocityResponse && p.substep > 0.0 && wSum > 0.0;
        const bool friction = p.friction > 0.0 && p.substep > 0.0 && wSum > 0.0;
        const bool beforeSolve = bridson && !p.repulsion; // before an implicit solve (contact_force.glsl)
        const double target =
            bridson && !beforeSolve ? depth / std::max(10.0 * p.substep, p.relaxationTime) : 0.0;
        // A bounce leaving the thickness gets no penalty from the solve (ContactParams::leavingStep).
        const bool leaving = p.leavingStep > 0.0 && vn > p.leavingSpeed && vn * p.leavingStep >= depth;
        const double penalty = leaving ? 0.0 : std::min(p.stiffness * std::max(depth, 0.0), p.forceCap);
        const bool active = beforeSolve ? vn < 0.0 || (friction && penalty > 0.0) : bridson && vn < target;
        double f = normalForce(depth, vn);
        // Bridson's acting contacts; with the penalty and friction, the pushing ones.
        const bool counted = bridson ? active : friction && f > 0.0;
        if (pass == Pass::Count) {
            if (counted)
                for (std::size_t i = 0; i < 4; ++i)
                    if (share[i] > 0.0) ++approaching[n[i]];
            return false;
        }
        const double perSpeed =
            counted ? 1.0 / (wSum * p.substep * static_cast<double>(actingCount(n, share))) : 0.0;
        if (beforeSolve) {
            if (!active) return false;
            const double inelastic = std::max(-vn, 0.0) * perSpeed;
            glm::dvec3 F = inelastic * u;
            if (friction) {
                glm::dvec3 vAfter = vRel; // + h Σ a_i w_i f_i: what the solve will add
                if (p.predictedForces && in.predictedForces)
                    for (std::size_t i = 0; i < 4; ++i)
                        vAfter += p.substep * a[i] * w(n[i]) * (*in.predictedForces)[n[i]];
                F += frictionForce(vAfter - glm::dot(vAfter, u) * u, inelastic + penalty, perSpeed);
            }
            if (F == glm::dvec3(0.0)) return false;
            return addContactForce(n, a, F);
        }
        if (bridson) {
            if (!active) return false;
            const double vAfter = std::max(vn, 0.0);
            f = (vAfter - vn) * perSpeed + std::min(f, (target - vAfter) * perSpeed);
        }
        f = std::min(f, p.forceCap);
        if (!(f > 0.0)) return false;
        glm::dvec3 F = f * u;
        if (friction) F += frictionForce(vRel - vn * u, f, perSpeed);
        return addContactForce(n, a, F);
    }
};

} // namespace

glm::dvec3 closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const double v = d1 / (d1 - d3);
        return {1.0 - v, v, 0.0};
    }
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const double w = d2 / (d2 - d6);
        return {1.0 - w, 0.0, w};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0.0, 1.0 - w, w};
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    return {1.0 - v - w, v, w};
}

std::array<double, 2> closestSegmentParams(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& q0,
                                           const glm::dvec3& q1) {
    const glm::dvec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
    double s = 0.0, t = 0.0;
    if (a <= 0.0 && e <= 0.0) return {0.0, 0.0};
    if (a <= 0.0) {
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        const double c = glm::dot(d1, r);
        if (e <= 0.0) {
            s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            const double b = glm::dot(d1, d2);
            const double denom = a * e - b * b;
            s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = std::clamp(-c / a, 0.0, 1.0);
            } else if (t > 1.0) {
                t = 1.0;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    return {s, t};
}

FeaturePairList featurePairs(const std::vector<std::uint32_t>& faceIndices,
                             const std::vector<std::uint32_t>& faceOwned,
                             const std::vector<IndexPair>& candidates) {
    FeaturePairList out;
    for (const auto& [a, b] : candidates) {
        const std::uint32_t oa = faceOwned[a], ob = faceOwned[b];
        for (std::uint32_t k = 0; k < 3; ++k) {
            if (oa & (GLC_OWN_VERTEX0 << k)) out.vertexFace.push_back({faceIndices[3 * a + k], b});
            if (ob & (GLC_OWN_VERTEX0 << k)) out.vertexFace.push_back({faceIndices[3 * b + k], a});
        }
        for (std::uint32_t e = 0; e < 3; ++e) {
            if (!(oa & (GLC_OWN_EDGE01 << e))) continue;
            for (std::uint32_t g = 0; g < 3; ++g)
                if (ob & (GLC_OWN_EDGE01 << g)) out.edgeEdge.push_back({3 * a + e, 3 * b + g});
        }
    }
    std::sort(out.vertexFace.begin(), out.vertexFace.end());
    std::sort(out.edgeEdge.begin(), out.edgeEdge.end());
    return out;
}

namespace {

constexpr std::uint32_t kNoFace = 0xffffffffu;

std::size_t nodeCountOf(const std::vector<std::uint32_t>& faceIndices) {
    return faceIndices.empty() ? 0
                               : std::size_t{*std::max_element(faceIndices.begin(), faceIndices.end())} + 1;
}

bool sharesNode(const std::vector<std::uint32_t>& faceIndices, std::uint32_t f, std::uint32_t g) {
    for (std::uint32_t i = 0; i < 3; ++i)
        for (std::uint32_t j = 0; j < 3; ++j)
            if (faceIndices[3 * std::size_t{f} + i] == faceIndices[3 * std::size_t{g} + j]) return true;
    return false;
}

} // namespace

FeaturePairList ccdFeaturePairs(const std::vector<std::uint32_t>& faceIndices,
                                const std::vector<std::uint32_t>& faceOwned,
                                const std::vector<std::uint32_t>& featureOwners,
                                const std::vector<IndexPair>& candidates) {
    FeaturePairList out = featurePairs(faceIndices, faceOwned, candidates);
    const auto vertexOwner = [&](std::uint32_t f, std::uint32_t k) {
        return featureOwners[6 * std::size_t{f} + k];
    };
    const auto edgeOwner = [&](std::uint32_t f, std::uint32_t k) {
        return featureOwners[6 * std::size_t{f} + 3 + k];
    };
    // Each node's faces, in increasing order (model::nodeFaceTable).
    const std::vector<std::uint32_t> around = model::nodeFaceTable(faceIndices, nodeCountOf(faceIndices));
    const auto corner = [&](std::uint32_t f, std::uint32_t k) { return faceIndices[3 * std::size_t{f} + k]; };
    const auto hasNode = [&](std::uint32_t f, std::uint32_t n) {
        return corner(f, 0) == n || corner(f, 1) == n || corner(f, 2) == n;
    };
    const auto lowestFaceApart = [&](std::uint32_t node, std::uint32_t other) {
        for (std::uint32_t k = around[node]; k < around[node + 1]; ++k)
            if (!sharesNode(faceIndices, around[k], other)) return around[k];
        return kNoFace;
    };
    const auto lowestFacePairApart = [&](std::uint32_t edgeA, std::uint32_t edgeB) {
        const auto a = model::faceEdge(faceIndices, edgeA / 3, static_cast<int>(edgeA % 3));
        const auto b = model::faceEdge(faceIndices, edgeB / 3, static_cast<int>(edgeB % 3));
        IndexPair best{kNoFace, kNoFace};
        for (std::uint32_t i = around[a[0]]; i < around[a[0] + 1]; ++i)
            for (std::uint32_t j = around[b[0]]; j < around[b[0] + 1]; ++j) {
                const std::uint32_t f = around[i], g = around[j];
                if (!hasNode(f, a[1]) || !hasNode(g, b[1]) || sharesNode(faceIndices, f, g)) continue;
                best = std::min(best, IndexPair{std::min(f, g), std::max(f, g)});
            }
        return best;
    };
    for (const auto& [a, b] : candidates) {
        for (std::uint32_t k = 0; k < 3; ++k) {
            if (sharesNode(faceIndices, vertexOwner(a, k), b) && lowestFaceApart(corner(a, k), b) == a)
                out.vertexFace.push_back({corner(a, k), b});
            if (sharesNode(faceIndices, vertexOwner(b, k), a) && lowestFaceApart(corner(b, k), a) == b)
                out.vertexFace.push_back({corner(b, k), a});
        }
        const IndexPair key{std::min(a, b), std::max(a, b)};
        for (std::uint32_t e = 0; e < 3; ++e)
            for (std::uint32_t g = 0; g < 3; ++g)
                if (sharesNode(faceIndices, edgeOwner(a, e), edgeOwner(b, g)) &&
                    lowestFacePairApart(3 * a + e, 3 * b + g) == key)
                    out.edgeEdge.push_back({3 * a + e, 3 * b + g});
    }
    std::sort(out.vertexFace.begin(), out.vertexFace.end());
    std::sort(out.edgeEdge.begin(), out.edgeEdge.end());
    return out;
}

ContactResult contactForces(const ContactParams& params, const ContactInput& in,
                            const FeaturePairList& pairs) {
    ContactResult out;
    out.forces.assign(in.positions->size(), glm::dvec3(0.0));
    out.contributions.assign(in.positions->size(), 0u);
    out.approaching.assign(in.positions->size(), 0u);
    Solver solver{params, in, out, out.approaching};
    for (const Pass pass : {Pass::Count, Pass::Apply}) { // every count before any force
        solver.pass = pass;
        forEachContact(params, in, pairs, [&](const ContactGeometry& c) {
            solver.respond(c.nodes, c.weights, c.normal, c.depth);
        });
    }
    return out;
}

std::vector<ContactGeometry> contactGeometries(const ContactParams& params, const ContactInput& in,
                                               const FeaturePairList& pairs, Crossings crossings) {
    std::vector<ContactGeometry> contacts;
    forEachContact(
        params, in, pairs, [&](const ContactGeometry& c) { contacts.push_back(c); }, crossings);
    return contacts;
}

namespace {

struct Interval {
    double lo, hi;
};

// [n.lo, n.hi] / [d.lo, d.hi] for d.lo > 0.
Interval quotient(Interval n, Interval d) {
    const double q[4] = {n.lo / d.lo, n.lo / d.hi, n.hi / d.lo, n.hi / d.hi};
    return {*std::min_element(q, q + 4), *std::max_element(q, q + 4)};
}

// Edge-edge: contact_pair.glsl counts the pair exactly when the closest points of the two lines,
// s0 = (b·f − c·e)/D and t0 = (a·f − b·c)/D with D = a·e − b² (closestSegmentParams' dot products),
// both lie strictly inside (0, 1) and the pair is closer than the thickness. With every dot product
// off by up to `slack` of itself, s0 and t0 lie in intervals; when those straddle the square's
// border, or D may be ≤ 0 (nearly parallel edges: the float s0 is then any number), a float
// evaluation may decide either way. Such a pair's contact, counted at any pair of points, is at
// most as deep as the segments' distance allows: ½·k·(h − distance)².
double edgeEdgeAmbiguity(const ContactParams& params, const glm::dvec3& p0, const glm::dvec3& p1,
                         const glm::dvec3& q0, const glm::dvec3& q1, double slack, bool counted) {
    const glm::dvec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r), c = glm::dot(d1, r),
                 b = glm::dot(d1, d2);
    const auto [s, t] = closestSegmentParams(p0, p1, q0, q1);
    const double distance = glm::length((p0 + s * d1) - (q0 + t * d2));
    if (!(distance < params.thickness) || !(a > 0.0) || !(e > 0.0)) return 0.0;
    const double depthEnergy =
        0.5 * params.stiffness * (params.thickness - distance) * (params.thickness - distance);
    const double D = a * e - b * b, dD = 2.0 * slack * (a * e + b * b);
    if (!(D - dD > 0.0)) return depthEnergy; // nearly parallel: either way
    const double ns = b * f - c * e, dns = 2.0 * slack * (std::abs(b * f) + std::abs(c * e));
    const double nt = a * f - b * c, dnt = 2.0 * slack * (std::abs(a * f) + std::abs(b * c));
    const Interval den{D - dD, D + dD};
    const Interval si = quotient({ns - dns, ns + dns}, den), ti = quotient({nt - dnt, nt + dnt}, den);
    const bool surelyInside = si.lo > 0.0 && si.hi < 1.0 && ti.lo > 0.0 && ti.hi < 1.0;
    const bool surelyOutside = si.hi <= 0.0 || si.lo >= 1.0 || ti.hi <= 0.0 || ti.lo >= 1.0;
    return (counted ? surelyInside : surelyOutside) ? 0.0 : depthEnergy;
}

} // namespace

double ambiguousContactEnergy(const ContactParams& params, const ContactInput& in,
                              const FeaturePairList& pairs, double relativeSlack) {
    const std::vector<glm::dvec3>& x = *in.positions;
    std::vector<glm::dvec3> moved = x; // a face's nodes move here, then back
    ContactInput variant = in;
    variant.positions = &moved;
    const Geometry geometry{params, variant, Crossings::WithinThickness};
    const std::vector<std::uint32_t>& idx = *in.faceIndices;
    double sum = 0.0;
    // Vertex-face: the face scaled about its centroid by 1 ± slack moves every boundary of its
    // closest-feature regions (its edges, its corners) by slack of the face's size, either way.
    for (const IndexPair& vf : pairs.vertexFace) {
        const std::uint32_t node = vf[0], face = vf[1]; // not a structured binding: the lambda captures them
        const std::array<std::uint32_t, 3> f{idx[3 * face], idx[3 * face + 1], idx[3 * face + 2]};
        const auto contact = [&] {
            return geometry.vertexFace(node, face, f, (*in.faceOwned)[face], faceKind(in, node, face));
        };
        const std::optional<ContactGeometry> nominal = contact();
        double largest = nominal ? nominal->depth : 0.0;
        bool differs = false;
        const glm::dvec3 centroid = (x[f[0]] + x[f[1]] + x[f[2]]) / 3.0;
        for (const double scale : {1.0 + relativeSlack, 1.0 - relativeSlack}) {
            for (const std::uint32_t n : f) moved[n] = centroid + scale * (x[n] - centroid);
            const std::optional<ContactGeometry> c = contact();
            for (const std::uint32_t n : f) moved[n] = x[n];
            differs = differs || c.has_value() != nominal.has_value();
            largest = std::max(largest, c ? c->depth : 0.0);
        }
        if (differs) sum += 0.5 * params.stiffness * largest * largest;
    }
    for (const IndexPair& ee : pairs.edgeEdge) {
        const auto a = model::faceEdge(idx, ee[0] / 3, static_cast<int>(ee[0] % 3));
        const auto b = model::faceEdge(idx, ee[1] / 3, static_cast<int>(ee[1] % 3));
        sum += edgeEdgeAmbiguity(params, x[a[0]], x[a[1]], x[b[0]], x[b[1]], relativeSlack,
                                 geometry.edgeEdge(a[0], a[1], b[0], b[1]).has_value());
    }
    return sum;
}

ContactResult contactForces(const ContactParams& params, const ContactInput& in,
                            const std::vector<IndexPair>& candidates) {
    return contactForces(params, in, featurePairs(*in.faceIndices, *in.faceOwned, candidates));
}

} // namespace glcollide::cpu
