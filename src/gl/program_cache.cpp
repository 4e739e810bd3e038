#include "gl/program_cache.hpp"

#include <epoxy/gl.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <system_error>

namespace glcollide::gl {
namespace {

constexpr std::string_view kMagic = "GLCPBIN1"; // bump the digit when the layout changes
// magic, format (u32), reserved (u32), key length, binary length, binary FNV-1a (u64 each).
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8;
// Program binaries are kilobytes to a few megabytes; a larger file is not ours (read nothing).
constexpr std::uintmax_t kMaxBinaryBytes = 256u << 20;

bool isSet(const char* value) {
    return value != nullptr && value[0] != '\0';
}

void putU32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}
void putU64(std::string& out, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}
std::uint64_t getLE(std::string_view bytes, std::size_t at, int count) {
    std::uint64_t v = 0;
    for (int i = count - 1; i >= 0; --i)
        v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
    return v;
}

std::string glString(GLenum name) {
    const auto* text = reinterpret_cast<const char*>(glGetString(name));
    return text ? std::string(text) : std::string();
}

std::string hex64(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

// A name no other process or thread picks: pid plus 64 random bits.
std::string uniqueSuffix() {
    std::random_device rd;
    const std::uint64_t r = (std::uint64_t{rd()} << 32) ^ rd();
    return std::to_string(::getpid()) + "." + hex64(r);
}

std::optional<std::string> readFile(const std::filesystem::path& path, std::uintmax_t maxBytes) {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec || size > maxBytes) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return std::nullopt;
    return bytes;
}

} // namespace

CacheLocation resolveCacheLocation(const char* glcollideCacheDir, const char* xdgCacheHome,
                                   const char* home) {
    CacheLocation loc;
    if (isSet(glcollideCacheDir)) {
        if (std::string_view(glcollideCacheDir) == "off") {
            loc.reason = "GLCOLLIDE_CACHE_DIR=off";
            return loc;
        }
        loc.folder = glcollideCacheDir;
    } else if (isSet(xdgCacheHome)) {
        loc.folder = std::filesystem::path(xdgCacheHome) / "glcollide";
    } else if (isSet(home)) {
        loc.folder = std::filesystem::path(home) / ".cache" / "glcollide";
    } else {
        loc.reason = "neither GLCOLLIDE_CACHE_DIR, XDG_CACHE_HOME nor HOME is set";
        return loc;
    }
    loc.enabled = true;
    return loc;
}

CacheLocation cacheLocationFromEnvironment() {
    return resolveCacheLocation(std::getenv("GLCOLLIDE_CACHE_DIR"), std::getenv("XDG_CACHE_HOME"),
                                std::getenv("HOME"));
}

std::uint64_t fnv1a64(std::string_view bytes) {
    std::uint64_t h = 0xcbf29ce484222325ull; // FNV-1a 64-bit offset basis
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 0x100000001b3ull; // FNV 64-bit prime
    }
    return h;
}

DriverIdentity currentDriverIdentity() {
    return {glString(GL_VENDOR), glString(GL_RENDERER), glString(GL_VERSION)};
}

std::string programCacheKey(const DriverIdentity& driver, std::string_view source) {
    std::string key = "glcollide program cache 1\nvendor: " + driver.vendor +
                      "\nrenderer: " + driver.renderer + "\nversion: " + driver.version + "\nsource:\n";
    key += source;
    return key;
}

std::string encodeCacheEntry(const CacheEntry& entry) {
    std::string out(kMagic);
    putU32(out, entry.binaryFormat);
    putU32(out, 0);
    putU64(out, entry.key.size());
    putU64(out, entry.binary.size());
    putU64(out, fnv1a64(entry.binary));
    out += entry.key;
    out += entry.binary;
    return out;
}

std::optional<CacheEntry> decodeCacheEntry(std::string_view bytes, std::string_view expectedKey) {
    if (bytes.size() < kHeaderBytes || bytes.substr(0, kMagic.size()) != kMagic) return std::nullopt;
    const std::uint64_t keyLength = getLE(bytes, 16, 8);
    const std::uint64_t binaryLength = getLE(bytes, 24, 8);
    // Compared one at a time, so no sum can overflow.
    if (keyLength != expectedKey.size() || binaryLength > bytes.size() ||
        bytes.size() - kHeaderBytes != keyLength + binaryLength)
        return std::nullopt;
    if (bytes.substr(kHeaderBytes, keyLength) != expectedKey) return std::nullopt;
    CacheEntry entry;
    entry.binaryFormat = static_cast<std::uint32_t>(getLE(bytes, 8, 4));
    entry.key = expectedKey;
    entry.binary = std::string(bytes.substr(kHeaderBytes + keyLength));
    if (fnv1a64(entry.binary) != getLE(bytes, 32, 8)) return std::nullopt;
    return entry;
}

std::vector<std::int32_t> programBinaryFormats() {
    GLint count = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &count);
    std::vector<std::int32_t> formats(static_cast<std::size_t>(std::max(count, 0)));
    if (!formats.empty()) glGetIntegerv(GL_PROGRAM_BINARY_FORMATS, formats.data());
    return formats;
}

ProgramCache::ProgramCache(CacheLocation location) : m_location(std::move(location)) {
    if (!m_location.enabled) {
        m_note = m_location.reason;
        return;
    }
    std::error_code ec;
    std::filesystem::create_directories(m_location.folder, ec);
    if (ec) {
        m_note = "cannot create " + m_location.folder.string() + ": " + ec.message();
        return;
    }
    m_formats = programBinaryFormats();
    if (m_formats.empty()) {
        m_note = "the driver offers no program binary format (GL_NUM_PROGRAM_BINARY_FORMATS is 0)";
        return;
    }
    m_usable = true;
}

void ProgramCache::noteOnce(std::string text) {
    if (m_note.empty()) m_note = std::move(text);
}

std::filesystem::path ProgramCache::entryPath(std::string_view label, std::string_view key) const {
    std::string stem;
    for (const char c : label) {
        const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                           c == '_' || c == '-';
        stem.push_back(plain ? c : '_');
    }
    if (stem.size() > 64) stem.resize(64);
    return m_location.folder / (stem + "-" + hex64(fnv1a64(key)) + ".bin");
}

bool ProgramCache::load(std::uint32_t program, std::string_view label, const std::string& key) {
    if (!m_usable) return false;
    const std::filesystem::path path = entryPath(label, key);
    const std::optional<std::string> bytes = readFile(path, kHeaderBytes + key.size() + kMaxBinaryBytes);
    if (!bytes) return false; // absent (the usual miss) or unreadable
    const std::optional<CacheEntry> entry = decodeCacheEntry(*bytes, key);
    if (!entry) return false; // corrupt, truncated or another key's file: rewritten after compiling
    // glProgramBinary with a format the context does not list is GL_INVALID_ENUM: check first.
    if (std::find(m_formats.begin(), m_formats.end(), static_cast<std::int32_t>(entry->binaryFormat)) ==
        m_formats.end())
        return false;
    glProgramBinary(program, entry->binaryFormat, entry->binary.data(),
                    static_cast<GLsizei>(entry->binary.size()));
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    return linked == GL_TRUE; // false: the driver rejected it (e.g. built by another driver build)
}

void ProgramCache::store(std::uint32_t program, std::string_view label, const std::string& key) {
    if (!m_usable) return;
    GLint length = 0;
    glGetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
    if (length <= 0) {
        noteOnce("the driver returned no program binary for " + std::string(label));
        return;
    }
    CacheEntry entry;
    entry.key = key;
    entry.binary.resize(static_cast<std::size_t>(length));
    GLsizei written = 0;
    GLenum format = 0;
    glGetProgramBinary(program, length, &written, &format, entry.binary.data());
    if (written <= 0) {
        noteOnce("the driver returned no program binary for " + std::string(label));
        return;
    }
    entry.binary.resize(static_cast<std::size_t>(written));
    entry.binaryFormat = format;

    const std::filesystem::path target = entryPath(label, key);
    if (!writeFileAtomically(target, encodeCacheEntry(entry)))
        noteOnce("cannot write " + target.string() + " (the cache is skipped)");
}

bool writeFileAtomically(const std::filesystem::path& target, std::string_view bytes) {
    std::filesystem::path temporary = target;
    temporary += ".tmp." + uniqueSuffix();
    bool ok = false;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (out) {
            out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
            out.close();
            ok = static_cast<bool>(out);
        }
    }
    std::error_code ec;
    if (ok) {
        // rename() replaces the target atomically within one file system, however many
        // processes write the same entry at once.
        std::filesystem::rename(temporary, target, ec);
        ok = !ec;
    }
    if (!ok) std::filesystem::remove(temporary, ec);
    return ok;
}

} // namespace glcollide::gl
