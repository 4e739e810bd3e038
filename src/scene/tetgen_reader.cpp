// TetGen .node/.ele reader, written from the format description; no TetGen code.
#include "scene/line_reader.hpp"
#include "scene/scene_detail.hpp"

namespace glcollide::detail {

TetMesh readTetGen(const std::filesystem::path& nodePath) {
    TetMesh mesh;
    long long base = 0;
    {
        LineReader in(nodePath);
        auto h = in.nextData('#');
        if (h.empty()) in.failAtEnd("empty .node file, expected '<#points> <dim> <#attributes> <#markers>'");
        const long long n = in.toInt(h[0], "point count");
        const long long dim = h.size() > 1 ? in.toInt(h[1], "dimension") : 3;
        const long long attrs = h.size() > 2 ? in.toInt(h[2], "attribute count") : 0;
        const long long markers = h.size() > 3 ? in.toInt(h[3], "boundary marker flag") : 0;
        if (n <= 0) in.fail("the .node file announces no points");
        if (dim != 3) in.fail("dimension " + std::to_string(dim) + " is not supported (only 3)");
        if (attrs < 0 || markers < 0 || markers > 1)
            in.fail("invalid attribute count or boundary marker flag");
        const auto perLine = static_cast<std::size_t>(4 + attrs + markers);
        for (long long i = 0; i < n; ++i) {
            auto t = in.nextData('#');
            if (t.empty())
                in.failAtEnd("unexpected end of file: " + std::to_string(n) + " points announced, " +
                             std::to_string(i) + " found");
            if (t.size() != perLine)
                in.fail("expected 'index x y z' plus " + std::to_string(attrs) + " attribute(s) and " +
                        std::to_string(markers) + " marker(s) = " + std::to_string(perLine) +
                        " values, got " + std::to_string(t.size()));
            const long long id = in.toInt(t[0], "point index");
            // The first index fixes the numbering: TetGen writes 0- or 1-based (-z) files.
            if (i == 0) {
                if (id != 0 && id != 1)
                    in.fail("the first point index must be 0 or 1, got " + std::to_string(id));
                base = id;
            }
            if (id != base + i)
                in.fail("point index " + std::to_string(id) + " out of sequence, expected " +
                        std::to_string(base + i));
            mesh.positions.emplace_back(in.toDouble(t[1], "x coordinate"), in.toDouble(t[2], "y coordinate"),
                                        in.toDouble(t[3], "z coordinate"));
        }
    }
    std::filesystem::path elePath = nodePath;
    elePath.replace_extension(".ele");
    LineReader in(elePath);
    auto h = in.nextData('#');
    if (h.empty()) in.failAtEnd("empty .ele file, expected '<#tets> <nodes per tet> <#attributes>'");
    const long long n = in.toInt(h[0], "tetrahedron count");
    const long long perTet = h.size() > 1 ? in.toInt(h[1], "nodes per tetrahedron") : 4;
    const long long attrs = h.size() > 2 ? in.toInt(h[2], "region attribute count") : 0;
    if (n <= 0) in.fail("the .ele file announces no tetrahedra");
    if (perTet == 10) in.fail("10-node (second-order) tetrahedra are not supported; run TetGen without -o2");
    if (perTet != 4) in.fail("nodes per tetrahedron must be 4, got " + std::to_string(perTet));
    if (attrs < 0) in.fail("negative attribute count");
    const auto perLine = static_cast<std::size_t>(5 + attrs);
    const long long count = static_cast<long long>(mesh.positions.size());
    for (long long i = 0; i < n; ++i) {
        auto t = in.nextData('#');
        if (t.empty())
            in.failAtEnd("unexpected end of file: " + std::to_string(n) + " tetrahedra announced, " +
                         std::to_string(i) + " found");
        if (t.size() != perLine)
            in.fail("expected 'index n1 n2 n3 n4' plus " + std::to_string(attrs) + " attribute(s), got " +
                    std::to_string(t.size()) + " values");
        Tet tet{};
        for (std::size_t k = 0; k < 4; ++k) {
            const long long v = in.toInt(t[k + 1], "node index");
            if (v < base || v >= base + count)
                in.fail("node index " + std::to_string(v) + " out of range [" + std::to_string(base) + ", " +
                        std::to_string(base + count - 1) + "] (the .node file is " + std::to_string(base) +
                        "-based)");
            tet[k] = static_cast<std::uint32_t>(v - base);
        }
        mesh.tets.push_back(tet);
        mesh.tetLines.push_back(in.line());
    }
    orientTets(mesh, in.file());
    return mesh;
}

} // namespace glcollide::detail
