// Gmsh MSH reader (ASCII 4.1 and 2.2), written from the format description; no gmsh code.
#include "scene/line_reader.hpp"
#include "scene/scene_detail.hpp"

#include <algorithm>
#include <unordered_map>

namespace glcollide::detail {
namespace {

constexpr long long kTet4 = 4;
constexpr long long kTet10 = 11;

struct RawTet {
    long long tags[4];
    std::size_t line;
};

struct Reader {
    LineReader in;
    int major = 0;
    std::vector<glm::dvec3> positions;
    std::unordered_map<long long, std::uint32_t> index; // node tag -> position index
    std::vector<RawTet> tets;
    bool sawNodes = false;
    bool sawElements = false;

    explicit Reader(const std::filesystem::path& p) : in(p) {}

    void addNode(long long tag, const std::vector<std::string_view>& xyz, std::size_t first) {
        const glm::dvec3 p(in.toDouble(xyz[first], "x coordinate"),
                           in.toDouble(xyz[first + 1], "y coordinate"),
                           in.toDouble(xyz[first + 2], "z coordinate"));
        if (!index.emplace(tag, static_cast<std::uint32_t>(positions.size())).second)
            in.fail("node tag " + std::to_string(tag) + " appears twice");
        positions.push_back(p);
    }

    void expectEnd(const std::string& name) {
        auto t = in.require("$End" + name);
        if (t.size() != 1 || t[0] != "$End" + name)
            in.fail("expected $End" + name + ", got '" + (t.empty() ? std::string() : std::string(t[0])) +
                    "'");
    }

    void readFormat() {
        auto t = in.require("the MSH version line");
        in.expectTokens(t, 3, "'version file-type data-size'");
        const std::string version(t[0]);
        if (in.toInt(t[1], "file type") != 0)
            in.fail("binary MSH files are not supported; save the mesh as ASCII "
                    "(gmsh: Mesh.Binary = 0, format 4.1 or 2.2)");
        if (version == "4.1")
            major = 4;
        else if (version == "2.2" || version == "2.1" || version == "2")
            major = 2;
        else
            in.fail("MSH version " + version + " is not supported (supported: 4.1 and 2.2 ASCII)");
        expectEnd("MeshFormat");
    }

    void readNodes41() {
        auto h = in.require("the $Nodes header");
        in.expectTokens(h, 4, "'numEntityBlocks numNodes minNodeTag maxNodeTag'");
        const long long blocks = in.toInt(h[0], "block count");
        const long long total = in.toInt(h[1], "node count");
        if (blocks < 0 || total < 0) in.fail("negative count in the $Nodes header");
        const std::size_t before = positions.size();
        for (long long b = 0; b < blocks; ++b) {
            auto bh = in.require("a node block header");
            in.expectTokens(bh, 4, "'entityDim entityTag parametric numNodesInBlock'");
            const long long parametric = in.toInt(bh[2], "parametric flag");
            const long long n = in.toInt(bh[3], "node count of the block");
            if (n < 0) in.fail("negative node count in a block");
            std::vector<long long> tags;
            // n comes from the file: never reserve from it unchecked (a fuzzed header asked for 24 TB).
            tags.reserve(static_cast<std::size_t>(std::min<long long>(n, 1 << 16)));
            for (long long i = 0; i < n; ++i) {
                auto t = in.require("a node tag");
                in.expectTokens(t, 1, "a node tag");
                tags.push_back(in.toInt(t[0], "node tag"));
            }
            for (long long i = 0; i < n; ++i) {
                auto t = in.require("node coordinates");
                in.expectTokens(t, parametric != 0 ? 4 : 3, "'x y z'");
                addNode(tags[static_cast<std::size_t>(i)], t, 0);
            }
        }
        if (positions.size() - before != static_cast<std::size_t>(total))
            in.fail("the $Nodes header announces " + std::to_string(total) + " nodes, the blocks hold " +
                    std::to_string(positions.size() - before));
        expectEnd("Nodes");
    }

    void readElements41() {
        auto h = in.require("the $Elements header");
        in.expectTokens(h, 4, "'numEntityBlocks numElements minElementTag maxElementTag'");
        const long long blocks = in.toInt(h[0], "block count");
        if (blocks < 0) in.fail("negative block count in the $Elements header");
        for (long long b = 0; b < blocks; ++b) {
            auto bh = in.require("an element block header");
            in.expectTokens(bh, 4, "'entityDim entityTag elementType numElementsInBlock'");
            const long long type = in.toInt(bh[2], "element type");
            const long long n = in.toInt(bh[3], "element count of the block");
            if (n < 0) in.fail("negative element count in a block");
            if (type == kTet10) in.fail(secondOrderMessage());
            for (long long i = 0; i < n; ++i) {
                auto t = in.require("an element line");
                if (type != kTet4) continue; // other element types carry nothing we simulate
                if (t.size() != 5)
                    in.fail("expected 'tag n1 n2 n3 n4' for a tetrahedron, got " + std::to_string(t.size()) +
                            " value(s)");
                addTet(t, 1);
            }
        }
        expectEnd("Elements");
    }

    void readNodes22() {
        auto h = in.require("the node count");
        in.expectTokens(h, 1, "the node count");
        const long long n = in.toInt(h[0], "node count");
        if (n < 0) in.fail("negative node count");
        for (long long i = 0; i < n; ++i) {
            auto t = in.require("a node line");
            in.expectTokens(t, 4, "'id x y z'");
            addNode(in.toInt(t[0], "node id"), t, 1);
        }
        expectEnd("Nodes");
    }

    void readElements22() {
        auto h = in.require("the element count");
        in.expectTokens(h, 1, "the element count");
        const long long n = in.toInt(h[0], "element count");
        if (n < 0) in.fail("negative element count");
        for (long long i = 0; i < n; ++i) {
            auto t = in.require("an element line");
            in.expectTokens(t, 3, "'id type ntags ...'");
            const long long type = in.toInt(t[1], "element type");
            if (type == kTet10) in.fail(secondOrderMessage());
            if (type != kTet4) continue;
            const long long ntags = in.toInt(t[2], "tag count");
            if (ntags < 0 || t.size() != static_cast<std::size_t>(3 + ntags + 4))
                in.fail("expected 'id 4 ntags <ntags tags> n1 n2 n3 n4' for a tetrahedron");
            addTet(t, static_cast<std::size_t>(3 + ntags));
        }
        expectEnd("Elements");
    }

    static std::string secondOrderMessage() {
        return "10-node (second-order) tetrahedra are not supported; export linear 4-node tets";
    }

    void addTet(const std::vector<std::string_view>& t, std::size_t first) {
        RawTet raw{};
        for (int k = 0; k < 4; ++k)
            raw.tags[k] = in.toInt(t[first + static_cast<std::size_t>(k)], "node tag");
        raw.line = in.line();
        tets.push_back(raw);
    }

    void skipSection(const std::string& name) {
        std::string_view line;
        const std::string end = "$End" + name;
        while (in.next(line))
            if (LineReader::split(line) == std::vector<std::string_view>{end}) return;
        in.failAtEnd("unexpected end of file inside section $" + name + " (no " + end + ")");
    }

    TetMesh read() {
        std::string_view line;
        bool sawFormat = false;
        while (in.next(line)) {
            auto t = LineReader::split(line);
            if (t.empty()) continue;
            if (t[0].empty() || t[0][0] != '$' || t.size() != 1)
                in.fail("expected a section header such as $Nodes, got '" + std::string(line) + "'");
            const std::string name(t[0].substr(1));
            if (!sawFormat && name != "MeshFormat")
                in.fail("not a Gmsh MSH file: it must start with $MeshFormat");
            if (name == "MeshFormat") {
                readFormat();
                sawFormat = true;
            } else if (name == "Nodes") {
                if (sawNodes) in.fail("a second $Nodes section");
                major == 4 ? readNodes41() : readNodes22();
                sawNodes = true;
            } else if (name == "Elements") {
                if (sawElements) in.fail("a second $Elements section");
                major == 4 ? readElements41() : readElements22();
                sawElements = true;
            } else {
                skipSection(name); // $Entities, $PhysicalNames, IPC's $Surface, ...
            }
        }
        if (!sawFormat) in.failAtEnd("empty file, expected $MeshFormat");
        if (!sawNodes) in.failAtEnd("no $Nodes section");
        if (!sawElements) in.failAtEnd("no $Elements section");
        if (tets.empty()) in.failAtEnd("no 4-node tetrahedra (element type 4) in $Elements");

        TetMesh mesh;
        mesh.positions = std::move(positions);
        for (const RawTet& raw : tets) {
            Tet tet{};
            for (int k = 0; k < 4; ++k) {
                auto it = index.find(raw.tags[k]);
                if (it == index.end())
                    throw Error(in.file() + ":" + std::to_string(raw.line) + ": node tag " +
                                std::to_string(raw.tags[k]) + " is not defined in $Nodes");
                tet[static_cast<std::size_t>(k)] = it->second;
            }
            mesh.tets.push_back(tet);
            mesh.tetLines.push_back(raw.line);
        }
        orientTets(mesh, in.file());
        return mesh;
    }
};

} // namespace

TetMesh readGmsh(const std::filesystem::path& path) {
    return Reader(path).read();
}

} // namespace glcollide::detail
