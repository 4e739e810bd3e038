// PLY reader (ASCII, binary little- and big-endian): the `vertex` element's x, y, z and the `face`
// element's vertex_indices (or vertex_index) list; other elements and properties are read past.
// Polygons are split into triangle fans; lists of fewer than 3 indices carry no surface.
//
// Our own rather than assimp's: fuzzing (fuzz/mesh_ply_fuzz.cpp, inputs in
// fuzz/regressions/mesh_ply/) found Debian 12's assimp 5.2 PLY reader looping forever on a bad
// header keyword, crashing in post-processing on an index beyond the vertex count, and asking for
// 26 GB on a garbage list count. Every error here names the file and the line (ASCII, header) or
// byte offset (binary body), and no count from the file is trusted before it is checked against
// what the file can hold.
#include "scene/line_reader.hpp"
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide::detail {
namespace {

struct ScalarType {
    std::uint32_t bytes = 0;
    bool integral = true;
    bool isSigned = true;
};

const std::map<std::string, ScalarType>& scalarTypes() {
    static const std::map<std::string, ScalarType> types = {
        {"char", {1, true, true}},    {"int8", {1, true, true}},     {"uchar", {1, true, false}},
        {"uint8", {1, true, false}},  {"short", {2, true, true}},    {"int16", {2, true, true}},
        {"ushort", {2, true, false}}, {"uint16", {2, true, false}},  {"int", {4, true, true}},
        {"int32", {4, true, true}},   {"uint", {4, true, false}},    {"uint32", {4, true, false}},
        {"float", {4, false, true}},  {"float32", {4, false, true}}, {"double", {8, false, true}},
        {"float64", {8, false, true}}};
    return types;
}

struct Property {
    std::string name;
    ScalarType type;
    bool list = false;
    ScalarType countType;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    std::size_t line = 0;
    [[nodiscard]] std::uint64_t minBytes() const { // binary, every list empty
        std::uint64_t b = 0;
        for (const Property& p : properties) b += p.list ? p.countType.bytes : p.type.bytes;
        return b;
    }
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::size_t bodyOffset = 0; ///< first byte after end_header's line
    std::size_t bodyLine = 0;   ///< line number of the first body line (ASCII)
};

Header parseHeader(const std::string& text, const std::string& file) {
    const auto fail = [&](std::size_t line, const std::string& what) {
        throw Error(file + ":" + std::to_string(line) + ": " + what);
    };
    Header h;
    std::size_t pos = 0, lineNo = 0;
    bool ended = false, haveFormat = false;
    while (!ended) {
        if (pos >= text.size()) fail(lineNo, "PLY header has no end_header line");
        const std::size_t eol = text.find('\n', pos);
        std::string line = text.substr(pos, eol == std::string::npos ? std::string::npos : eol - pos);
        pos = eol == std::string::npos ? text.size() : eol + 1;
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (lineNo == 1) {
            if (line != "ply") fail(1, "not a PLY file: the first line must be 'ply'");
            continue;
        }
        std::istringstream tokens(line);
        std::string keyword;
        tokens >> keyword;
        const std::vector<std::string> args{std::istream_iterator<std::string>(tokens),
                                            std::istream_iterator<std::string>()};
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            if (haveFormat || lineNo != 2) fail(lineNo, "'format' must be the second header line, once");
            if (args.size() != 2 || args[1] != "1.0" ||
                (args[0] != "ascii" && args[0] != "binary_little_endian" && args[0] != "binary_big_endian"))
                fail(lineNo, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            h.format = args[0] == "ascii"                  ? Format::Ascii
                       : args[0] == "binary_little_endian" ? Format::BinaryLittleEndian
                                                           : Format::BinaryBigEndian;
            haveFormat = true;
        } else if (!haveFormat) {
            fail(lineNo, "expected the 'format' line after 'ply'");
        } else if (keyword == "element") {
            if (args.size() != 2 || args[1].empty() || args[1].size() > 12 ||
                args[1].find_first_not_of("0123456789") != std::string::npos)
                fail(lineNo, "expected 'element <name> <count>' with a decimal count below 10^12");
            h.elements.push_back({args[0], std::stoull(args[1]), {}, lineNo});
        } else if (keyword == "property") {
            if (h.elements.empty()) fail(lineNo, "'property' before any 'element'");
            const auto& types = scalarTypes();
            Property p;
            if (!args.empty() && args[0] == "list") {
                if (args.size() != 4 || !types.count(args[1]) || !types.count(args[2]) ||
                    !types.at(args[1]).integral)
                    fail(lineNo, "expected 'property list <integer type> <type> <name>'");
                p = {args[3], types.at(args[2]), true, types.at(args[1])};
            } else {
                if (args.size() != 2 || !types.count(args[0]))
                    fail(lineNo, "expected 'property <type> <name>' with a PLY scalar type (char uchar short "
                                 "ushort int uint float double, or int8 ... float64)");
                p = {args[1], types.at(args[0]), false, {}};
            }
            h.elements.back().properties.push_back(p);
        } else if (keyword == "end_header") {
            if (!args.empty()) fail(lineNo, "unexpected text after 'end_header'");
            ended = true;
        } else {
            fail(lineNo, "unknown PLY header keyword '" + keyword + "'");
        }
    }
    h.bodyOffset = pos;
    h.bodyLine = lineNo + 1;

    // Every element must fit in what follows the header: a binary element takes at least its
    // fixed bytes, an ASCII value at least one character and a separator (the last value may end
    // the file without one: one byte of slack). So no count below is trusted beyond the file.
    const bool binary = h.format != Format::Ascii;
    const std::uint64_t remaining = text.size() - pos;
    const std::uint64_t budget = binary ? remaining : remaining + 1;
    std::uint64_t needed = 0;
    for (const Element& e : h.elements) {
        const std::uint64_t each = binary ? e.minBytes() : 2 * e.properties.size();
        if (each != 0 && e.count > (budget - needed) / each)
            fail(e.line, "element '" + e.name + "' declares " + std::to_string(e.count) +
                             " entries, more than the " + std::to_string(remaining) +
                             " bytes after the header can hold");
        needed += e.count * each;
    }
    return h;
}

/// A token for an error message: at most 40 characters, bytes outside printable ASCII as \xNN.
std::string printable(std::string_view token) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (const char c : token.substr(0, 40)) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u < 0x7f) {
            out += c;
        } else {
            out += "\\x";
            out += hex[u >> 4];
            out += hex[u & 15u];
        }
    }
    return token.size() > 40 ? out + "..." : out;
}

/// The body as a stream of values: whitespace-separated tokens (ASCII) or fixed-size fields.
class BodyReader {
  public:
    BodyReader(const std::string& text, const Header& h, const std::string& file)
        : m_text(text), m_format(h.format), m_pos(h.bodyOffset), m_line(h.bodyLine), m_file(file) {}

    /// Reads one value of `type`; integral values must be integers within the type's range.
    double read(const ScalarType& type, const std::string& what) {
        return m_format == Format::Ascii ? readAscii(type, what) : readBinary(type, what);
    }

    /// The current line (ASCII), 0 for binary bodies.
    [[nodiscard]] std::size_t line() const { return m_format == Format::Ascii ? m_line : 0; }

    /// Bytes (binary) or characters (ASCII) not read yet: a list longer than this cannot be there.
    [[nodiscard]] std::size_t remaining() const { return m_text.size() - m_pos; }

    [[noreturn]] void fail(const std::string& what) const {
        if (m_format == Format::Ascii) throw Error(m_file + ":" + std::to_string(m_line) + ": " + what);
        throw Error(m_file + ": byte " + std::to_string(m_pos) + ": " + what);
    }

  private:
    double readAscii(const ScalarType& type, const std::string& what) {
        while (m_pos < m_text.size() && std::isspace(static_cast<unsigned char>(m_text[m_pos]))) {
            if (m_text[m_pos] == '\n') ++m_line;
            ++m_pos;
        }
        if (m_pos >= m_text.size()) fail("unexpected end of file, expected " + what);
        std::size_t end = m_pos;
        while (end < m_text.size() && !std::isspace(static_cast<unsigned char>(m_text[end]))) ++end;
        const std::string_view token(m_text.data() + m_pos, end - m_pos);
        const std::string_view digits = withoutLeadingPlus(token);
        double value = 0.0;
        if (type.integral) {
            long long v = 0;
            const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
            if (ec != std::errc() || p != digits.data() + digits.size())
                fail("expected an integer " + what + ", got '" + printable(token) + "'");
            value = static_cast<double>(v);
        } else {
            const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
            if (ec == std::errc::result_out_of_range)
                fail(what + " '" + printable(token) + "' is outside double range");
            if (ec != std::errc() || p != digits.data() + digits.size())
                fail("expected a number " + what + ", got '" + printable(token) + "'");
        }
        checkRange(type, value, what);
        m_pos = end;
        return value;
    }

    double readBinary(const ScalarType& type, const std::string& what) {
        if (remaining() < type.bytes) fail("file ends inside " + what);
        unsigned char raw[8];
        std::memcpy(raw, m_text.data() + m_pos, type.bytes);
        const bool fileLittle = m_format == Format::BinaryLittleEndian;
        if (fileLittle != (std::endian::native == std::endian::little))
            for (std::uint32_t i = 0; i < type.bytes / 2; ++i) std::swap(raw[i], raw[type.bytes - 1 - i]);
        double value = 0.0;
        if (!type.integral) {
            if (type.bytes == 4) {
                float f;
                std::memcpy(&f, raw, 4);
                value = f;
            } else {
                std::memcpy(&value, raw, 8);
            }
        } else {
            std::uint64_t u = 0;
            std::memcpy(&u, raw, type.bytes); // native order now; little-endian hosts only matter here
            if (std::endian::native == std::endian::big) u >>= 8 * (8 - type.bytes);
            if (type.isSigned) {
                const std::uint64_t sign = std::uint64_t{1} << (8 * type.bytes - 1);
                value = static_cast<double>(static_cast<std::int64_t>((u ^ sign) - sign));
            } else {
                value = static_cast<double>(u);
            }
        }
        m_pos += type.bytes;
        return value;
    }

    void checkRange(const ScalarType& type, double v, const std::string& what) const {
        if (!type.integral) return;
        const double bits = 8.0 * type.bytes;
        const double lo = type.isSigned ? -std::exp2(bits - 1) : 0.0;
        const double hi = type.isSigned ? std::exp2(bits - 1) - 1 : std::exp2(bits) - 1;
        if (v < lo || v > hi)
            fail(what + " " + std::to_string(static_cast<long long>(v)) + " is outside its PLY type's range");
    }

    const std::string& m_text;
    Format m_format;
    std::size_t m_pos;
    std::size_t m_line;
    const std::string& m_file;
};

} // namespace

PlyMesh readPlyAsStored(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(file + ": cannot open file");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const Header header = parseHeader(text, file);

    PlyMesh mesh;
    std::vector<glm::dvec3>& positions = mesh.positions;
    bool haveVertices = false;
    BodyReader body(text, header, file);
    for (const Element& e : header.elements) {
        const bool isVertex = e.name == "vertex", isFace = e.name == "face";
        int xyz[3] = {-1, -1, -1};
        int indices = -1;
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            if (isVertex && !p.list && (p.name == "x" || p.name == "y" || p.name == "z"))
                xyz[p.name[0] - 'x'] = static_cast<int>(k);
            if (isFace && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
                if (!p.type.integral)
                    throw Error(file + ":" + std::to_string(e.line) +
                                ": face indices must have an integer type");
                indices = static_cast<int>(k);
            }
        }
        if (isVertex) {
            if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
                throw Error(file + ":" + std::to_string(e.line) +
                            ": element 'vertex' needs properties x, y and z");
            haveVertices = true;
        }
        if (isFace && indices < 0)
            throw Error(file + ":" + std::to_string(e.line) +
                        ": element 'face' has no list property vertex_indices");
        if (isFace && !haveVertices)
            throw Error(file + ":" + std::to_string(e.line) +
                        ": element 'face' comes before element 'vertex'");
        for (std::uint64_t i = 0; i < e.count; ++i) {
            const std::string where = e.name + " " + std::to_string(i);
            glm::dvec3 position(0.0);
            std::vector<std::uint32_t> polygon;
            for (std::size_t k = 0; k < e.properties.size(); ++k) {
                const Property& p = e.properties[k];
                if (!p.list) {
                    const double v = body.read(p.type, "property '" + p.name + "' of " + where);
                    for (int axis = 0; axis < 3; ++axis)
                        if (static_cast<int>(k) == xyz[axis]) position[axis] = v;
                    continue;
                }
                const double n = body.read(p.countType, "the length of list '" + p.name + "' of " + where);
                if (n < 0.0) body.fail("negative length of list '" + p.name + "' of " + where);
                // Each entry takes at least one byte (binary) or one character (ASCII).
                if (n > static_cast<double>(body.remaining()))
                    body.fail("list '" + p.name + "' of " + where + " has " +
                              std::to_string(static_cast<long long>(n)) +
                              " entries, more than the rest of the file can hold");
                for (double j = 0; j < n; ++j) {
                    const double v = body.read(p.type, "entry of list '" + p.name + "' of " + where);
                    if (static_cast<int>(k) != indices) continue;
                    if (v < 0.0 || v >= static_cast<double>(positions.size()))
                        body.fail(where + " uses vertex " + std::to_string(static_cast<long long>(v)) +
                                  " of " + std::to_string(positions.size()));
                    polygon.push_back(static_cast<std::uint32_t>(v));
                }
            }
            if (isVertex) {
                if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
                    body.fail("vertex " + std::to_string(i) + " has a non-finite coordinate");
                positions.push_back(position);
            }
            for (std::size_t j = 2; j < polygon.size(); ++j) {
                mesh.faces.push_back({polygon[0], polygon[j - 1], polygon[j]});
                mesh.faceElement.push_back(mesh.faceElements);
                if (body.line() != 0) mesh.faceLines.push_back(body.line());
            }
            if (isFace) ++mesh.faceElements;
        }
    }
    if (!haveVertices) throw Error(file + ": the PLY file has no element 'vertex'");
    return mesh;
}

SurfaceMesh readPly(const std::filesystem::path& path) {
    PlyMesh mesh = readPlyAsStored(path);
    return weldSurface(std::move(mesh.positions), mesh.faces, path.string(), mesh.faceLines);
}

} // namespace glcollide::detail
