// The program binary cache's pure parts (src/gl/program_cache.hpp): where the folder is, the
// FNV-1a hash that names entries, and the entry encoding that must reject every damaged or
// foreign file. The GL half (store, load, fallback) is tests/gl/program_cache_gl_test.cpp.

#include "gl/program_cache.hpp"

#include <gtest/gtest.h>

#include <string>

namespace glcollide::gl {
namespace {

TEST(ProgramCacheLocation, GlcollideCacheDirComesFirst) {
    const CacheLocation loc = resolveCacheLocation("/a/b", "/xdg", "/home/u");
    EXPECT_TRUE(loc.enabled);
    EXPECT_EQ(loc.folder, std::filesystem::path("/a/b"));
}

TEST(ProgramCacheLocation, OffDisablesTheCache) {
    const CacheLocation loc = resolveCacheLocation("off", "/xdg", "/home/u");
    EXPECT_FALSE(loc.enabled);
    EXPECT_TRUE(loc.folder.empty());
    EXPECT_EQ(loc.reason, "GLCOLLIDE_CACHE_DIR=off");
}

TEST(ProgramCacheLocation, ThenXdgCacheHome) {
    for (const char* unset : {static_cast<const char*>(nullptr), ""}) {
        const CacheLocation loc = resolveCacheLocation(unset, "/xdg", "/home/u");
        EXPECT_TRUE(loc.enabled);
        EXPECT_EQ(loc.folder, std::filesystem::path("/xdg/glcollide"));
    }
}

TEST(ProgramCacheLocation, ThenHomeDotCache) {
    // An empty XDG_CACHE_HOME counts as unset (XDG Base Directory specification).
    const CacheLocation loc = resolveCacheLocation(nullptr, "", "/home/u");
    EXPECT_TRUE(loc.enabled);
    EXPECT_EQ(loc.folder, std::filesystem::path("/home/u/.cache/glcollide"));
}

TEST(ProgramCacheLocation, NothingSetMeansNoCache) {
    const CacheLocation loc = resolveCacheLocation(nullptr, nullptr, "");
    EXPECT_FALSE(loc.enabled);
    EXPECT_FALSE(loc.reason.empty());
}

// Reference values of 64-bit FNV-1a (the published test vectors of Fowler/Noll/Vo).
TEST(ProgramCacheHash, Fnv1a64MatchesReferenceVectors) {
    EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);
    EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
    EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
}

TEST(ProgramCacheKey, NamesDriverAndSource) {
    const std::string key = programCacheKey({"V", "R", "4.6 X"}, "#version 430\nvoid main(){}\n");
    EXPECT_NE(key.find("vendor: V\n"), std::string::npos);
    EXPECT_NE(key.find("renderer: R\n"), std::string::npos);
    EXPECT_NE(key.find("version: 4.6 X\n"), std::string::npos);
    EXPECT_NE(key.find("#version 430\nvoid main(){}\n"), std::string::npos);
    EXPECT_NE(key, programCacheKey({"V", "R", "4.6 Y"}, "#version 430\nvoid main(){}\n"));
}

class ProgramCacheEntry : public ::testing::Test {
  protected:
    CacheEntry entry{0x8740u, "the key", std::string("\x01\x02\x00\xff binary", 11)};
    std::string bytes = encodeCacheEntry(entry);
};

TEST_F(ProgramCacheEntry, RoundTrips) {
    const std::optional<CacheEntry> back = decodeCacheEntry(bytes, "the key");
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->binaryFormat, entry.binaryFormat);
    EXPECT_EQ(back->key, entry.key);
    EXPECT_EQ(back->binary, entry.binary);
}

TEST_F(ProgramCacheEntry, RejectsAnotherKey) {
    EXPECT_FALSE(decodeCacheEntry(bytes, "the kez").has_value());  // same length
    EXPECT_FALSE(decodeCacheEntry(bytes, "the key2").has_value()); // other length
}

TEST_F(ProgramCacheEntry, RejectsEveryTruncation) {
    for (std::size_t n = 0; n < bytes.size(); ++n)
        EXPECT_FALSE(decodeCacheEntry(std::string_view(bytes).substr(0, n), "the key").has_value()) << n;
}

TEST_F(ProgramCacheEntry, RejectsTrailingBytes) {
    EXPECT_FALSE(decodeCacheEntry(bytes + "x", "the key").has_value());
}

TEST_F(ProgramCacheEntry, RejectsBadMagic) {
    bytes[0] = 'X';
    EXPECT_FALSE(decodeCacheEntry(bytes, "the key").has_value());
}

TEST_F(ProgramCacheEntry, RejectsAnyFlippedPayloadByte) {
    for (std::size_t i = bytes.size() - entry.binary.size(); i < bytes.size(); ++i) {
        std::string damaged = bytes;
        damaged[i] = static_cast<char>(damaged[i] ^ 0x10);
        EXPECT_FALSE(decodeCacheEntry(damaged, "the key").has_value()) << i;
    }
}

TEST_F(ProgramCacheEntry, RejectsHugeLengthsWithoutOverflow) {
    // Lengths near 2^64 must not wrap around into a plausible size.
    for (std::size_t at : {std::size_t{16}, std::size_t{24}}) {
        std::string damaged = bytes;
        for (std::size_t i = 0; i < 8; ++i) damaged[at + i] = static_cast<char>(0xff);
        EXPECT_FALSE(decodeCacheEntry(damaged, "the key").has_value()) << at;
    }
}

} // namespace
} // namespace glcollide::gl
