// Procedural bodies: cloth grid, tube, tet box, tetrahedral ball under an icosphere. Built in the body's
// local frame.
#include "scene/scene_detail.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace glcollide::detail {
namespace {

std::uint32_t u32(int v) {
    return static_cast<std::uint32_t>(v);
}

Spring springBetween(std::uint32_t a, std::uint32_t b, SpringKind kind) {
    Spring s;
    s.a = a;
    s.b = b;
    s.kind = kind;
    return s;
}

// generateSphere: radial depth of a transition cell between two icosphere shells, in units of the
// outer shell's mean edge (both on the unit sphere). Chosen by scanning 0.5 … 1.1 for the largest
// minimum dihedral angle over subdivisions 1 … 5 (one value for all cells, 0.8 at best, gives 38.4°
// at s = 5; these give 40.6°, and 53.4° at s = 1): 0.9 where the shells are nearly flat, 0.75 for
// the innermost cell, over the 12-node icosahedron.
constexpr double kCellDepth = 0.9;
constexpr double kInnermostCellDepth = 0.75;

void fillNodeDefaults(Body& body) {
    body.velocities.assign(body.positions.size(), glm::dvec3(0.0));
    body.masses.assign(body.positions.size(), 0.0);
    body.pinned.assign(body.positions.size(), 0);
}

} // namespace

Body generateCloth(double width, double height, int nx, int ny, bool withShear, bool withBend) {
    Body body;
    const auto idx = [nx](int i, int j) { return u32(j * nx + i); };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            body.positions.emplace_back(-0.5 * width + width * i / (nx - 1),
                                        0.5 * height - height * j / (ny - 1), 0.0);
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            // Row j is above row j + 1, so (bottom-left, bottom-right, top-right) is CCW from +Z.
            const std::uint32_t tl = idx(i, j), tr = idx(i + 1, j);
            const std::uint32_t bl = idx(i, j + 1), br = idx(i + 1, j + 1);
            body.faces.push_back({bl, br, tr});
            body.faces.push_back({bl, tr, tl});
        }
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            if (i + 1 < nx)
                body.springs.push_back(springBetween(idx(i, j), idx(i + 1, j), SpringKind::Structural));
            if (j + 1 < ny)
                body.springs.push_back(springBetween(idx(i, j), idx(i, j + 1), SpringKind::Structural));
        }
    if (withShear)
        for (int j = 0; j + 1 < ny; ++j)
            for (int i = 0; i + 1 < nx; ++i) {
                body.springs.push_back(springBetween(idx(i, j), idx(i + 1, j + 1), SpringKind::Shear));
                body.springs.push_back(springBetween(idx(i + 1, j), idx(i, j + 1), SpringKind::Shear));
            }
    if (withBend)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (i + 2 < nx)
                    body.springs.push_back(springBetween(idx(i, j), idx(i + 2, j), SpringKind::Bend));
                if (j + 2 < ny)
                    body.springs.push_back(springBetween(idx(i, j), idx(i, j + 2), SpringKind::Bend));
            }
    fillNodeDefaults(body);
    return body;
}

namespace {
/// The bent tube's axis at arc length s from the top (generateTube): its point and the angle by
/// which its tangent has turned from −Y towards +X (about +Z).
struct AxisPoint {
    glm::dvec3 point;
    double turned = 0.0;
};
AxisPoint bentAxis(double length, double bendRadians, double s) {
    const double third = length / 3.0;
    const glm::dvec3 bendStart(0.0, 0.5 * length - third, 0.0);
    // The arc of radius third / bendRadians, written without that radius: it stays finite for the
    // smallest angle (a subnormal one gives the straight tube's points).
    const auto onArc = [&](double angle) {
        const double half = std::sin(0.5 * angle);
        return bendStart + third * glm::dvec3(2.0 * half * half, -std::sin(angle), 0.0) / bendRadians;
    };
    if (s <= third) return {{0.0, 0.5 * length - s, 0.0}, 0.0};
    if (s <= 2.0 * third) {
        const double angle = bendRadians * (s - third) / third;
        return {onArc(angle), angle};
    }
    const glm::dvec3 tangent(std::sin(bendRadians), -std::cos(bendRadians), 0.0);
    return {onArc(bendRadians) + (s - 2.0 * third) * tangent, bendRadians};
}
} // namespace

Body generateTube(double radius, double length, int around, int along, double bendDegrees) {
    Body body;
    const auto idx = [around](int i, int j) { return u32(j * around + (i % around)); };
    const double bend = bendDegrees * std::numbers::pi / 180.0;
    for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {
            const double angle = 2.0 * std::numbers::pi * i / around;
            if (bend == 0.0) { // straight: the formula of the scenes written before bends
                body.positions.emplace_back(radius * std::cos(angle), 0.5 * length - length * j / (along - 1),
                                            radius * std::sin(angle));
                continue;
            }
            // The ring's frame turns with the tangent: its +X direction becomes (cos, sin, 0).
            const AxisPoint axis = bentAxis(length, bend, length * j / (along - 1));
            const glm::dvec3 across(std::cos(axis.turned), std::sin(axis.turned), 0.0);
            body.positions.push_back(axis.point + radius * std::cos(angle) * across +
                                     glm::dvec3(0.0, 0.0, radius * std::sin(angle)));
        }
    // Along a ring (i -> i + 1) the tangent is (-sin, 0, cos); down the tube (j -> j + 1) it is -Y;
    // their cross product (cos, 0, sin) points away from the axis: (a, b, c) and (a, c, d) face out.
    for (int j = 0; j + 1 < along; ++j)
        for (int i = 0; i < around; ++i) {
            const std::uint32_t a = idx(i, j), b = idx(i + 1, j), c = idx(i + 1, j + 1), d = idx(i, j + 1);
            body.faces.push_back({a, b, c});
            body.faces.push_back({a, c, d});
        }
    fillNodeDefaults(body);
    return body;
}

Body generateTetBox(const glm::dvec3& size, const std::array<int, 3>& cells) {
    Body body;
    const int px = cells[0] + 1, py = cells[1] + 1, pz = cells[2] + 1;
    const auto idx = [px, py](int i, int j, int k) { return u32((k * py + j) * px + i); };
    const glm::dvec3 step = size / glm::dvec3(cells[0], cells[1], cells[2]);
    for (int k = 0; k < pz; ++k)
        for (int j = 0; j < py; ++j)
            for (int i = 0; i < px; ++i) body.positions.push_back(-0.5 * size + glm::dvec3(i, j, k) * step);
    // Freudenthal split: one tet per axis order, each walking from the cell's min corner to its
    // max corner. Every cell face gets the diagonal through its own min corner, so neighbours agree.
    static constexpr int kOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < cells[2]; ++k)
        for (int j = 0; j < cells[1]; ++j)
            for (int i = 0; i < cells[0]; ++i)
                for (const auto& order : kOrders) {
                    int c[3] = {i, j, k};
                    Tet tet{};
                    tet[0] = idx(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[order[s]];
                        tet[s + 1] = idx(c[0], c[1], c[2]);
                    }
                    const auto& p = body.positions;
                    if (tetDet(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) < 0.0) std::swap(tet[2], tet[3]);
                    body.tets.push_back(tet);
                }
    body.faces = boundaryFaces(body.tets, "tet_box");
    body.springs = tetEdgeSprings(body.tets);
    fillNodeDefaults(body);
    return body;
}

Body generateSphere(double radius, int subdivisions) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p = glm::normalize(p);
    std::vector<Face> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    // levelFaces[k]: the level-k triangles; vertexCount[k]: level k uses vertices [0, vertexCount[k])
    // of v (refinement only appends); mids[k][j]: the level-k midpoints (ab, bc, ca) of level-(k-1)
    // face j. Face j's children are faces 4j .. 4j + 3 of level k.
    std::vector<std::vector<Face>> levelFaces{faces};
    std::vector<std::size_t> vertexCount{v.size()};
    std::vector<std::vector<Face>> mids{{}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            const auto id = static_cast<std::uint32_t>(v.size() - 1);
            mid.emplace(key, id);
            return id;
        };
        std::vector<Face> next, nextMids;
        next.reserve(faces.size() * 4);
        nextMids.reserve(faces.size());
        for (const Face& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                                ca = midpoint(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
            nextMids.push_back({ab, bc, ca});
        }
        faces = std::move(next);
        levelFaces.push_back(faces);
        vertexCount.push_back(v.size());
        mids.push_back(std::move(nextMids));
    }
    // Wind outward explicitly rather than trusting the hand-written table above.
    for (Face& f : faces) {
        const glm::dvec3 n = glm::cross(v[f[1]] - v[f[0]], v[f[2]] - v[f[0]]);
        if (glm::dot(n, v[f[0]] + v[f[1]] + v[f[2]]) < 0.0) std::swap(f[1], f[2]);
    }

    // The ball: one icosphere shell per level k = subdivisions (the surface) down to 0, shell k at
    // shellRadius[k] with the directions v[0 .. vertexCount[k]), and a centre node. Shells k-1
    // (inner) and k (outer) are joined by one transition cell per level-(k-1) triangle, so element
    // size halves from each shell to the next one out and every level's node count is about a
    // quarter of the next one's: all interior nodes together are about a third of the surface's.
    // Each cell is made about as deep as it is wide: depth = kCellDepth × level k's mean edge.
    const auto levels = static_cast<std::size_t>(subdivisions);
    std::vector<double> shellRadius(levels + 1, radius);
    for (std::size_t k = levels; k >= 1; --k) {
        double sum = 0.0;
        for (const Face& f : levelFaces[k])
            for (int i = 0; i < 3; ++i) sum += glm::length(v[f[i]] - v[f[(i + 1) % 3]]);
        const double meanEdge = sum / static_cast<double>(3 * levelFaces[k].size()); // unit sphere
        shellRadius[k - 1] = shellRadius[k] * (1.0 - (k == 1 ? kInnermostCellDepth : kCellDepth) * meanEdge);
    }

    Body body;
    for (const auto& p : v) body.positions.push_back(radius * p);
    // Surface nodes keep their icosphere indices; then the inner shells, outermost first; then the
    // centre (the last node).
    std::vector<std::uint32_t> base(levels + 1, 0); // node of (shell k, vertex i) = base[k] + i
    for (std::size_t k = levels; k-- > 0;) {
        base[k] = static_cast<std::uint32_t>(body.positions.size());
        for (std::size_t i = 0; i < vertexCount[k]; ++i) body.positions.push_back(shellRadius[k] * v[i]);
    }
    body.positions.emplace_back(0.0);
    const auto centre = static_cast<std::uint32_t>(body.positions.size() - 1);

    const auto& p = body.positions;
    const auto addTet = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        Tet tet{a, b, c, d};
        if (tetDet(p[a], p[b], p[c], p[d]) < 0.0) std::swap(tet[2], tet[3]);
        body.tets.push_back(tet);
    };
    for (std::size_t k = 1; k <= levels; ++k) {
        const std::vector<Face>& parents = levelFaces[k - 1];
        for (std::size_t j = 0; j < parents.size(); ++j) {
            // The cell over parent triangle j: its corners on the inner shell (in), the same
            // directions on the outer shell (out) and the outer shell's edge midpoints (m[i] on
            // edge i, i + 1), i.e. the parent's 4 children.
            std::uint32_t in[3], out[3], m[3];
            for (std::size_t i = 0; i < 3; ++i) {
                in[i] = base[k - 1] + parents[j][i];
                out[i] = base[k] + parents[j][i];
                m[i] = base[k] + mids[k][j][i];
            }
            // One tet under each corner child. The cell's side over parent edge (i, i + 1) is
            // planar (it lies in the plane through the origin and that edge) and is cut into
            // (in[i], out[i], m[i]), (in[i], in[i+1], m[i]), (in[i+1], out[i+1], m[i]): symmetric in
            // the edge's two ends, so the neighbouring cell cuts it the same way.
            for (std::size_t i = 0; i < 3; ++i) addTet(in[i], out[i], m[i], m[(i + 2) % 3]);
            // The rest is the octahedron in[0..2], m[0..2], where in[i] is opposite m[i + 1]. Split
            // it into 4 tets around its shortest diagonal (inside the cell: no neighbour sees it).
            std::size_t d = 0;
            for (std::size_t i = 1; i < 3; ++i)
                if (glm::length(p[in[i]] - p[m[(i + 1) % 3]]) < glm::length(p[in[d]] - p[m[(d + 1) % 3]]))
                    d = i;
            const std::uint32_t ring[4] = {in[(d + 1) % 3], m[d], m[(d + 2) % 3], in[(d + 2) % 3]};
            for (std::size_t i = 0; i < 4; ++i) addTet(in[d], m[(d + 1) % 3], ring[i], ring[(i + 1) % 4]);
        }
    }
    // Innermost: the level-0 shell (an icosahedron) and the centre, valence 12.
    for (const Face& f : levelFaces[0]) addTet(base[0] + f[0], base[0] + f[1], base[0] + f[2], centre);
    body.faces = faces;
    body.springs = tetEdgeSprings(body.tets);
    fillNodeDefaults(body);
    return body;
}

} // namespace glcollide::detail
