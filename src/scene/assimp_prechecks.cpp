// Checks that run before assimp reads a file, where assimp 5.2 (Debian 12) misbehaves on malformed
// input instead of failing (found by the fuzz targets; the inputs are in fuzz/regressions/):
// (PLY is read by our own reader, src/scene/ply_reader.cpp, for the same reason.)
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
#include <string>

namespace glcollide::detail {
namespace {

std::string readAll(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open file");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t littleEndian32(const std::string& bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i)
        v |= std::uint32_t{static_cast<unsigned char>(bytes[at + i])} << (8 * i);
    return v;
}

void checkJson(const std::string& text, const std::string& where) {
    try {
        const auto json = nlohmann::json::parse(text);
        if (!json.is_object()) throw Error(where + ": the glTF JSON is not an object");
    } catch (const nlohmann::json::exception& e) { // parse errors, and numbers beyond double range
        throw Error(where + ": invalid glTF JSON: " + e.what());
    }
}

} // namespace

void checkGlbContainer(const std::filesystem::path& path) {
    const std::string file = path.string();
    const std::string bytes = readAll(path);
    const auto fail = [&](std::size_t offset, const std::string& what) {
        throw Error(file + ": byte " + std::to_string(offset) + ": " + what);
    };
    constexpr std::uint32_t kMagic = 0x46546C67; // "glTF"
    constexpr std::uint32_t kJson = 0x4E4F534A, kBin = 0x004E4942;
    if (bytes.size() < 12)
        fail(0, "a GLB file starts with a 12-byte header; the file has " + std::to_string(bytes.size()) +
                    " bytes");
    if (littleEndian32(bytes, 0) != kMagic) fail(0, "not a GLB file (the magic is not 'glTF')");
    if (littleEndian32(bytes, 4) != 2)
        fail(4, "GLB version " + std::to_string(littleEndian32(bytes, 4)) + " (expected 2: glTF 2.0)");
    if (littleEndian32(bytes, 8) != bytes.size())
        fail(8, "the header's length " + std::to_string(littleEndian32(bytes, 8)) +
                    " differs from the file size " + std::to_string(bytes.size()));
    std::size_t at = 12;
    for (int chunk = 0; at < bytes.size(); ++chunk) {
        if (bytes.size() - at < 8) fail(at, "truncated chunk header");
        const std::uint32_t length = littleEndian32(bytes, at), type = littleEndian32(bytes, at + 4);
        if (chunk == 0 && type != kJson) fail(at + 4, "the first chunk must be JSON");
        if (chunk > 0 && type == kJson) fail(at + 4, "a second JSON chunk");
        if (length > bytes.size() - at - 8)
            fail(at, std::string(type == kJson  ? "JSON"
                                 : type == kBin ? "BIN"
                                                : "a") +
                         " chunk of " + std::to_string(length) + " bytes runs past the end of the file (" +
                         std::to_string(bytes.size() - at - 8) + " bytes left)");
        if (chunk == 0) checkJson(bytes.substr(at + 8, length), file + ": JSON chunk");
        at += 8 + std::size_t{length};
    }
    if (at == 12) fail(12, "no JSON chunk");
}

void checkGltfJson(const std::filesystem::path& path) {
    checkJson(readAll(path), path.string());
}

} // namespace glcollide::detail
