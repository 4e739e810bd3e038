// Procedural bodies: cloth grid, tet box, icosphere ball. Built in the body's local frame.
#include "scene/scene_detail.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
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
        std::vector<Face> next;
        next.reserve(faces.size() * 4);
        for (const Face& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                                ca = midpoint(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        faces = std::move(next);
    }
    // Wind outward explicitly rather than trusting the hand-written table above.
    for (Face& f : faces) {
        const glm::dvec3 n = glm::cross(v[f[1]] - v[f[0]], v[f[2]] - v[f[0]]);
        if (glm::dot(n, v[f[0]] + v[f[1]] + v[f[2]]) < 0.0) std::swap(f[1], f[2]);
    }
    Body body;
    for (const auto& p : v) body.positions.push_back(radius * p);
    body.positions.emplace_back(0.0);
    const auto centre = static_cast<std::uint32_t>(body.positions.size() - 1);
    body.faces = faces;
    // An outward face sees the centre behind it, so (a, c, b, centre) is positively oriented.
    for (const Face& f : faces) body.tets.push_back({f[0], f[2], f[1], centre});
    body.springs = tetEdgeSprings(body.tets);
    fillNodeDefaults(body);
    return body;
}

} // namespace glcollide::detail
