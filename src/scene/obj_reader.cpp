// Wavefront OBJ reader: `v` positions (extra values such as w or vertex colours ignored) and `f`
// polygons (indices i, i/t, i//n or i/t/n; negative indices count back from the last vertex so
// far), split into triangle fans. Points (`p`), lines (`l`), texture coordinates, normals,
// groups, smoothing and materials carry no surface and are skipped; free-form geometry (`curv`,
// `surf`, ...) is refused rather than silently dropped. Lines ending in '\' continue on the next.
//
// Our own rather than assimp's so that every error names the file and line (assimp's OBJ errors
// carry none) and so that a file's geometry is never half-read; assimp stays for glTF/GLB.
#include "scene/line_reader.hpp"
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide::detail {
namespace {

bool isFreeForm(std::string_view keyword) {
    for (const char* k : {"cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole",
                          "scrv", "sp", "end", "con"})
        if (keyword == k) return true;
    return false;
}

} // namespace

SurfaceMesh readObj(const std::filesystem::path& path) {
    LineReader in(path);
    const std::string& file = in.file();
    std::vector<glm::dvec3> positions;
    std::vector<Face> faces;
    std::vector<std::size_t> faceLines;
    std::string_view raw;
    std::string joined;
    bool anyGeometry = false;
    while (in.next(raw)) {
        // Continuation lines: the statement's line number is that of its last line.
        joined.assign(raw);
        while (!joined.empty() && joined.back() == '\\') {
            joined.pop_back();
            std::string_view more;
            if (!in.next(more)) break;
            joined += ' ';
            joined += more;
        }
        std::string_view line = joined;
        if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        const std::vector<std::string_view> t = LineReader::split(line);
        if (t.empty()) continue;
        const std::string_view keyword = t[0];
        if (keyword == "v") {
            in.expectTokens(t, 4, "'v x y z'");
            glm::dvec3 p;
            for (int k = 0; k < 3; ++k) {
                const std::string_view token = t[static_cast<std::size_t>(k) + 1];
                const std::string_view digits = withoutLeadingPlus(token);
                const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), p[k]);
                if (ec == std::errc::result_out_of_range)
                    in.fail("vertex " + std::to_string(positions.size() + 1) + " coordinate '" +
                            std::string(token) + "' is outside double range");
                if (ec != std::errc() || end != digits.data() + digits.size())
                    in.fail("expected a number as vertex coordinate, got '" + std::string(token) + "'");
                if (!std::isfinite(p[k]))
                    in.fail("vertex " + std::to_string(positions.size() + 1) +
                            " has a non-finite coordinate");
            }
            positions.push_back(p);
            anyGeometry = true;
        } else if (keyword == "f" || keyword == "fo") {
            if (t.size() < 4)
                in.fail("a face needs at least 3 vertices, got " + std::to_string(t.size() - 1));
            std::vector<std::uint32_t> polygon;
            for (std::size_t k = 1; k < t.size(); ++k) {
                const std::string_view corner = t[k];
                const std::string_view first = corner.substr(0, corner.find('/'));
                long long index = 0;
                const auto [end, ec] = std::from_chars(first.data(), first.data() + first.size(), index);
                if (ec != std::errc() || end != first.data() + first.size() || index == 0)
                    in.fail("expected a vertex index (1-based, or negative from the end) in '" +
                            std::string(corner) + "'");
                const long long count = static_cast<long long>(positions.size());
                const long long resolved = index > 0 ? index - 1 : count + index;
                if (resolved < 0 || resolved >= count)
                    in.fail("face uses vertex " + std::to_string(index) + ", but " + std::to_string(count) +
                            " vertices are defined before it");
                polygon.push_back(static_cast<std::uint32_t>(resolved));
            }
            for (std::size_t j = 2; j < polygon.size(); ++j) {
                faces.push_back({polygon[0], polygon[j - 1], polygon[j]});
                faceLines.push_back(in.line());
            }
            anyGeometry = true;
        } else if (isFreeForm(keyword)) {
            in.fail("free-form geometry ('" + std::string(keyword) +
                    "') is not supported; export triangles or polygons");
        }
        // vt vn vp p l o g s mg usemtl mtllib and unknown statements carry no surface.
    }
    if (!anyGeometry) throw Error(file + ": the file contains no mesh");
    return weldSurface(std::move(positions), faces, file, faceLines);
}

} // namespace glcollide::detail
