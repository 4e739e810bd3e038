#pragma once
// The program binary cache: linked programs saved with glGetProgramBinary and restored with
// glProgramBinary, so a process does not pay the driver's compile + link again (minutes on some
// drivers whose own disk cache is not in use). Entries are keyed by the driver (GL vendor,
// renderer, version string) and the complete expanded source. Every failure (no folder, no
// permission, a corrupt, stale or foreign file, a driver that rejects the binary or offers no
// binary format) falls back to compiling; nothing here throws.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide::gl {

/// Where the cache lives (docs/integration.md, "Program cache").
struct CacheLocation {
    bool enabled = false;
    std::filesystem::path folder; ///< empty when disabled
    std::string reason;           ///< when disabled: why
};

/// The resolution order, from the variables' values (nullptr or "" = unset):
/// GLCOLLIDE_CACHE_DIR ("off" disables the cache), else $XDG_CACHE_HOME/glcollide, else
/// $HOME/.cache/glcollide, else disabled.
CacheLocation resolveCacheLocation(const char* glcollideCacheDir, const char* xdgCacheHome, const char* home);
/// resolveCacheLocation() with this process's environment.
CacheLocation cacheLocationFromEnvironment();

/// 64-bit FNV-1a (Fowler, Noll, Vo): names entry files and checks their payload.
std::uint64_t fnv1a64(std::string_view bytes);

/// What identifies a driver's program binary: GL_VENDOR, GL_RENDERER, GL_VERSION.
struct DriverIdentity {
    std::string vendor, renderer, version;
};
/// From the current context.
DriverIdentity currentDriverIdentity();

/// The full key text of a program: a format tag, the driver identity and the source. Stored in
/// the entry and compared on load, so a colliding file-name hash never loads a wrong program.
std::string programCacheKey(const DriverIdentity& driver, std::string_view source);

/// One entry file: "GLCPBIN1", the binary format, the lengths, the payload's FNV-1a, the key text
/// and the binary. Pure encoding, no GL.
struct CacheEntry {
    std::uint32_t binaryFormat = 0;
    std::string key;
    std::string binary;
};
std::string encodeCacheEntry(const CacheEntry& entry);
/// nullopt for anything but an intact entry of exactly this key (bad magic, truncated, trailing
/// bytes, payload checksum mismatch, other key).
std::optional<CacheEntry> decodeCacheEntry(std::string_view bytes, std::string_view expectedKey);

/// Writes `bytes` to a uniquely named temporary file (pid + 64 random bits) in the target's folder
/// and renames it over `target`: a reader, in any process, sees the old file or the new one,
/// never a mixture. False (and no file left behind) when either step fails.
bool writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

/// The binary formats the current context accepts (empty: the driver offers none, no cache).
std::vector<std::int32_t> programBinaryFormats();

class ProgramCache {
  public:
    explicit ProgramCache(CacheLocation location);

    /// The folder is set, could be created, and the driver offers a binary format.
    [[nodiscard]] bool usable() const { return m_usable; }
    [[nodiscard]] const CacheLocation& location() const { return m_location; }
    /// The first reason the cache could not be used or written (empty when all went well).
    [[nodiscard]] const std::string& note() const { return m_note; }

    /// The entry file of a program: "<label>-<fnv1a64(key) in hex>.bin", the label reduced to
    /// [A-Za-z0-9_-] for a readable folder.
    [[nodiscard]] std::filesystem::path entryPath(std::string_view label, std::string_view key) const;

    /// Restores the entry into `program` (a fresh glCreateProgram name). True when the program is
    /// now linked; false (a miss) when there is no intact entry or the driver rejected it.
    bool load(std::uint32_t program, std::string_view label, const std::string& key);
    /// Saves a linked program that was linked with GL_PROGRAM_BINARY_RETRIEVABLE_HINT: written to
    /// a unique temporary file in the folder, then renamed over the entry, so concurrent
    /// processes never see a half-written file.
    void store(std::uint32_t program, std::string_view label, const std::string& key);

  private:
    void noteOnce(std::string text);

    CacheLocation m_location;
    std::vector<std::int32_t> m_formats;
    bool m_usable = false;
    std::string m_note;
};

} // namespace glcollide::gl
