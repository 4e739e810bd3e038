// Checks that run before assimp reads a file, where assimp 5.2 (Debian 12) misbehaves on malformed
// input instead of failing (found by the fuzz targets; the inputs are in fuzz/regressions/):
// - PLY: some malformed headers make its reader loop forever. The header grammar is checked here
//   with line numbers, and the declared element counts must fit in the bytes after the header.
// - GLB: a chunk length larger than the file makes it allocate that much (4 GB from a 564-byte
//   file). The binary container's header and chunk lengths are checked against the file size.
// - glTF/GLB JSON: its JSON parser read freed memory on some invalid JSON. The JSON (the .gltf
//   file, or the GLB's JSON chunk) must parse with nlohmann-json first; its error has the line.
#include "scene/scene_detail.hpp"

#include <glcollide/error.hpp>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace glcollide::detail {
namespace {

const std::map<std::string, std::uint64_t>& scalarSizes() {
    static const std::map<std::string, std::uint64_t> sizes = {
        {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},   {"ushort", 2},
        {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},   {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    return sizes;
}

std::string readAll(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open file");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t littleEndian32(const std::string& bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(bytes[at + i])} << (8 * i);
    return v;
}

void checkJson(const std::string& text, const std::string& where) {
    try {
        const auto json = nlohmann::json::parse(text);
        if (!json.is_object()) throw Error(where + ": the glTF JSON is not an object");
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(where + ": invalid glTF JSON: " + e.what());
    }
}

bool isIntegral(const std::string& type) { return type.find("float") == std::string::npos && type != "double"; }

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::uint64_t minBytes = 0;  ///< binary: bytes of one element with every list empty
    std::uint64_t properties = 0;
    std::size_t line = 0;
};

} // namespace

void checkPlyHeader(const std::filesystem::path& path) {
    const std::string file = path.string();
    const std::string text = readAll(path);
    const auto fail = [&](std::size_t line, const std::string& what) {
        throw Error(file + ":" + std::to_string(line) + ": " + what);
    };

    std::size_t pos = 0, lineNo = 0;
    bool ended = false, binary = false, haveFormat = false;
    std::vector<Element> elements;
    while (!ended) {
        if (pos >= text.size()) fail(lineNo, "PLY header has no end_header line");
        const std::size_t eol = text.find('\n', pos);
        std::string line = text.substr(pos, eol == std::string::npos ? std::string::npos : eol - pos);
        pos = eol == std::string::npos ? text.size() : eol + 1;
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream tokens(line);
        std::string keyword;
        tokens >> keyword;
        if (lineNo == 1) {
            if (line != "ply") fail(1, "not a PLY file: the first line must be 'ply'");
            continue;
        }
        std::vector<std::string> args{std::istream_iterator<std::string>(tokens), std::istream_iterator<std::string>()};
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            if (haveFormat || lineNo != 2) fail(lineNo, "'format' must be the second header line, once");
            if (args.size() != 2 || args[1] != "1.0" ||
                (args[0] != "ascii" && args[0] != "binary_little_endian" && args[0] != "binary_big_endian"))
                fail(lineNo, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            binary = args[0] != "ascii";
            haveFormat = true;
        } else if (!haveFormat) {
            fail(lineNo, "expected the 'format' line after 'ply'");
        } else if (keyword == "element") {
            if (args.size() != 2 || args[1].empty() || args[1].size() > 12 ||
                args[1].find_first_not_of("0123456789") != std::string::npos)
                fail(lineNo, "expected 'element <name> <count>' with a decimal count below 10^12");
            elements.push_back({args[0], std::stoull(args[1]), 0, 0, lineNo});
        } else if (keyword == "property") {
            if (elements.empty()) fail(lineNo, "'property' before any 'element'");
            Element& e = elements.back();
            const auto& sizes = scalarSizes();
            if (!args.empty() && args[0] == "list") {
                if (args.size() != 4 || !sizes.count(args[1]) || !sizes.count(args[2]) || !isIntegral(args[1]))
                    fail(lineNo, "expected 'property list <integer type> <type> <name>'");
                e.minBytes += sizes.at(args[1]);
            } else {
                if (args.size() != 2 || !sizes.count(args[0]))
                    fail(lineNo, "expected 'property <type> <name>' with a PLY scalar type (char uchar short "
                                 "ushort int uint float double, or int8 ... float64)");
                e.minBytes += sizes.at(args[0]);
            }
            ++e.properties;
        } else if (keyword == "end_header") {
            if (!args.empty()) fail(lineNo, "unexpected text after 'end_header'");
            ended = true;
        } else {
            fail(lineNo, "unknown PLY header keyword '" + keyword + "'");
        }
    }

    // Every element must fit in what follows the header: a binary element takes at least its
    // fixed bytes, an ASCII value at least one character and a separator.
    // (The last ASCII value may end the file without a separator: one byte of slack.)
    const std::uint64_t remaining = text.size() - pos;
    const std::uint64_t budget = binary ? remaining : remaining + 1;
    std::uint64_t needed = 0;
    for (const Element& e : elements) {
        const std::uint64_t each = binary ? e.minBytes : 2 * e.properties;
        if (each != 0 && e.count > (budget - needed) / each)
            fail(e.line, "element '" + e.name + "' declares " + std::to_string(e.count) + " entries, more than the " +
                             std::to_string(remaining) + " bytes after the header can hold");
        needed += e.count * each;
    }
}

void checkGlbContainer(const std::filesystem::path& path) {
    const std::string file = path.string();
    const std::string bytes = readAll(path);
    const auto fail = [&](std::size_t offset, const std::string& what) {
        throw Error(file + ": byte " + std::to_string(offset) + ": " + what);
    };
    constexpr std::uint32_t kMagic = 0x46546C67; // "glTF"
    constexpr std::uint32_t kJson = 0x4E4F534A, kBin = 0x004E4942;
    if (bytes.size() < 12) fail(0, "a GLB file starts with a 12-byte header; the file has " + std::to_string(bytes.size()) + " bytes");
    if (littleEndian32(bytes, 0) != kMagic) fail(0, "not a GLB file (the magic is not 'glTF')");
    if (littleEndian32(bytes, 4) != 2) fail(4, "GLB version " + std::to_string(littleEndian32(bytes, 4)) + " (expected 2: glTF 2.0)");
    if (littleEndian32(bytes, 8) != bytes.size())
        fail(8, "the header's length " + std::to_string(littleEndian32(bytes, 8)) + " differs from the file size " +
                    std::to_string(bytes.size()));
    std::size_t at = 12;
    for (int chunk = 0; at < bytes.size(); ++chunk) {
        if (bytes.size() - at < 8) fail(at, "truncated chunk header");
        const std::uint32_t length = littleEndian32(bytes, at), type = littleEndian32(bytes, at + 4);
        if (chunk == 0 && type != kJson) fail(at + 4, "the first chunk must be JSON");
        if (chunk > 0 && type == kJson) fail(at + 4, "a second JSON chunk");
        if (length > bytes.size() - at - 8)
            fail(at, std::string(type == kJson ? "JSON" : type == kBin ? "BIN" : "a") + " chunk of " +
                         std::to_string(length) + " bytes runs past the end of the file (" +
                         std::to_string(bytes.size() - at - 8) + " bytes left)");
        if (chunk == 0) checkJson(bytes.substr(at + 8, length), file + ": JSON chunk");
        at += 8 + std::size_t{length};
    }
    if (at == 12) fail(12, "no JSON chunk");
}

void checkGltfJson(const std::filesystem::path& path) { checkJson(readAll(path), path.string()); }

} // namespace glcollide::detail
