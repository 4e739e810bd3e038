// Tet mesh topology: orientation and boundary extraction.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace glcollide::detail {

double tetDet(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
    return glm::dot(b - a, glm::cross(c - a, d - a));
}

void orientTets(TetMesh& mesh, const std::string& file) {
    const auto where = [&](std::size_t t) {
        if (t < mesh.tetLines.size()) return file + ":" + std::to_string(mesh.tetLines[t]);
        return file + ": tet " + std::to_string(t);
    };
    const std::size_t n = mesh.positions.size();
    std::map<Tet, std::size_t> seen; // sorted nodes -> first tet
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        Tet& tet = mesh.tets[t];
        for (int i = 0; i < 4; ++i) {
            if (tet[i] >= n)
                throw Error(where(t) + ": node index " + std::to_string(tet[i]) +
                            " out of range (the mesh has " + std::to_string(n) + " nodes)");
            for (int j = 0; j < i; ++j)
                if (tet[i] == tet[j])
                    throw Error(where(t) + ": tetrahedron repeats node " + std::to_string(tet[i]));
        }
        Tet key = tet;
        std::sort(key.begin(), key.end());
        if (const auto [it, inserted] = seen.emplace(key, t); !inserted)
            throw Error(where(t) + ": tetrahedron uses the same four nodes as " +
                        (it->second < mesh.tetLines.size()
                             ? "the one of line " + std::to_string(mesh.tetLines[it->second])
                             : "tet " + std::to_string(it->second)) +
                        " (a duplicated tetrahedron)");
        const glm::dvec3& a = mesh.positions[tet[0]];
        const glm::dvec3& b = mesh.positions[tet[1]];
        const glm::dvec3& c = mesh.positions[tet[2]];
        const glm::dvec3& d = mesh.positions[tet[3]];
        const double det = tetDet(a, b, c, d);
        // Flat relative to its own size: the 1e-12 is far above double rounding of the
        // determinant (~1e-15 relative) and far below any tet a mesher would emit on purpose.
        double longest = 0.0;
        for (const glm::dvec3& e : {b - a, c - a, d - a, c - b, d - b, d - c})
            longest = std::max(longest, glm::length(e));
        if (!(std::abs(det) > 1e-12 * longest * longest * longest))
            throw Error(where(t) + ": degenerate (zero-volume) tetrahedron");
        // Orientation is only a labelling convention for one tet; mixed conventions in a file are
        // harmless once fixed here, and boundary extraction relies on it.
        if (det < 0.0) std::swap(tet[2], tet[3]);
    }
}

std::vector<Face> boundaryFaces(const std::vector<Tet>& tets, const std::string& what) {
    // Faces of a positively oriented tet (a, b, c, d), wound outward.
    static constexpr int kLocal[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    struct Entry {
        Face key;      // sorted indices
        Face oriented; // as wound by its tet
        std::size_t seq;
    };
    std::vector<Entry> entries;
    entries.reserve(tets.size() * 4);
    for (std::size_t t = 0; t < tets.size(); ++t)
        for (int f = 0; f < 4; ++f) {
            Face face{tets[t][kLocal[f][0]], tets[t][kLocal[f][1]], tets[t][kLocal[f][2]]};
            Face key = face;
            std::sort(key.begin(), key.end());
            entries.push_back({key, face, t * 4 + static_cast<std::size_t>(f)});
        }
    std::sort(entries.begin(), entries.end(),
              [](const Entry& x, const Entry& y) { return std::tie(x.key, x.seq) < std::tie(y.key, y.seq); });
    std::vector<Entry> single;
    for (std::size_t i = 0; i < entries.size();) {
        std::size_t j = i + 1;
        while (j < entries.size() && entries[j].key == entries[i].key) ++j;
        if (j - i == 1) single.push_back(entries[i]);
        if (j - i > 2)
            throw Error(what + ": triangle (" + std::to_string(entries[i].key[0]) + ", " +
                        std::to_string(entries[i].key[1]) + ", " + std::to_string(entries[i].key[2]) +
                        ") is shared by " + std::to_string(j - i) + " tetrahedra (non-manifold mesh)");
        i = j;
    }
    std::sort(single.begin(), single.end(), [](const Entry& x, const Entry& y) { return x.seq < y.seq; });
    std::vector<Face> out;
    out.reserve(single.size());
    for (const Entry& e : single) out.push_back(e.oriented);
    return out;
}

} // namespace glcollide::detail
