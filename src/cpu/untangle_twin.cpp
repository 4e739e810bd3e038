#include "cpu/untangle_twin.hpp"

#include <glm/geometric.hpp>

#include <algorithm>

namespace glcollide::cpu {
namespace {

constexpr std::array<std::array<int, 2>, 3> kEdges = {{{0, 1}, {1, 2}, {2, 0}}};

/// Edge (p0, p1) through triangle t: crosses its plane strictly at a point inside the closed triangle.
bool pierce(const glm::dvec3& p0, const glm::dvec3& p1, const std::array<glm::dvec3, 3>& t, Piercing& out) {
    const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
    const double d0 = glm::dot(n, p0 - t[0]);
    const double d1 = glm::dot(n, p1 - t[0]);
    if (!((d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0))) return false;
    const double s = d0 / (d0 - d1);
    const glm::dvec3 p = p0 + s * (p1 - p0);
    const double nn = glm::dot(n, n);
    const std::array<double, 3> b = {glm::dot(n, glm::cross(t[1] - p, t[2] - p)) / nn,
                                     glm::dot(n, glm::cross(t[2] - p, t[0] - p)) / nn,
                                     glm::dot(n, glm::cross(t[0] - p, t[1] - p)) / nn};
    if (b[0] < 0.0 || b[1] < 0.0 || b[2] < 0.0) return false;
    out.s = s;
    out.barycentric = b;
    out.point = p;
    return true;
}

glm::dvec3 clampLength(const glm::dvec3& v, double most) {
    const double l = glm::length(v);
    return l > most ? v * (most / l) : v;
}

} // namespace

std::vector<Piercing> intersectionPiercings(const std::array<glm::dvec3, 3>& a,
                                            const std::array<glm::dvec3, 3>& b) {
    std::vector<Piercing> found;
    for (const bool first : {true, false}) {
        const std::array<glm::dvec3, 3>& edges = first ? a : b;
        const std::array<glm::dvec3, 3>& face = first ? b : a;
        for (const std::array<int, 2>& e : kEdges) {
            Piercing p;
            if (found.size() < 2 && pierce(edges[e[0]], edges[e[1]], face, p)) {
                p.edgeOfFirst = first;
                p.edge = e;
                found.push_back(p);
            }
        }
    }
    return found;
}

UntangleResult untangleStep(const UntangleInput& in) {
    const std::size_t nodes = in.positions.size();
    UntangleResult r;
    r.pushSum.assign(nodes, glm::dvec3(0.0));
    r.displacement.assign(nodes, glm::dvec3(0.0));
    for (const std::array<std::uint32_t, 2>& pair : in.pairs) {
        const std::array<std::uint32_t, 3>& fa = in.faces[pair[0]];
        const std::array<std::uint32_t, 3>& fb = in.faces[pair[1]];
        const std::array<glm::dvec3, 3> a = {in.positions[fa[0]], in.positions[fa[1]], in.positions[fa[2]]};
        const std::array<glm::dvec3, 3> b = {in.positions[fb[0]], in.positions[fb[1]], in.positions[fb[2]]};
        const std::vector<Piercing> ends = intersectionPiercings(a, b);
        if (ends.size() < 2) {
            ++r.unresolvedPairs;
            continue;
        }
        for (int k = 0; k < 2; ++k) {
            const Piercing& p = ends[k];
            const glm::dvec3 q = ends[1 - k].point;
            const std::array<std::uint32_t, 3>& edgeFace = p.edgeOfFirst ? fa : fb;
            const std::array<std::uint32_t, 3>& face = p.edgeOfFirst ? fb : fa;
            const std::array<glm::dvec3, 3>& f = p.edgeOfFirst ? b : a;
            const std::uint32_t e0 = edgeFace[p.edge[0]], e1 = edgeFace[p.edge[1]];
            const glm::dvec3 n = glm::normalize(glm::cross(f[1] - f[0], f[2] - f[0]));
            glm::dvec3 push(0.0);
            const std::uint32_t faceObject = in.faceObject[p.edgeOfFirst ? pair[1] : pair[0]];
            const std::uint32_t edgeObject = in.faceObject[p.edgeOfFirst ? pair[0] : pair[1]];
            if (faceObject != edgeObject && in.objectClosed[faceObject]) {
                push = n;
            } else {
                const glm::dvec3 e = in.positions[e1] - in.positions[e0];
                const double sigma = glm::dot(q - p.point, e) * glm::dot(n, e);
                push = sigma > 0.0 ? -n : sigma < 0.0 ? n : glm::dvec3(0.0);
            }
            const std::array<std::uint32_t, 5> node = {e0, e1, face[0], face[1], face[2]};
            const std::array<double, 5> weight = {1.0 - p.s, p.s, -p.barycentric[0], -p.barycentric[1],
                                                  -p.barycentric[2]};
            double w = 0.0;
            for (int i = 0; i < 5; ++i) w += weight[i] * weight[i] * in.inverseMass[node[i]];
            if (!(w > 0.0)) continue; // all five pinned
            for (int i = 0; i < 5; ++i) {
                const double part = weight[i] * in.inverseMass[node[i]] / w;
                r.pushSum[node[i]] += clampLength(part * push, 1.0);
            }
        }
    }
    for (std::size_t i = 0; i < nodes; ++i) {
        const double l = glm::length(r.pushSum[i]);
        r.displacement[i] = in.step * r.pushSum[i] / std::max(1.0, l);
        if (l > 0.0) ++r.movedNodes;
    }
    return r;
}

} // namespace glcollide::cpu
