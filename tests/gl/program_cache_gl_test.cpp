// The program binary cache on this device (src/gl/program_cache.hpp, used by
// gl::ComputeProgram): a second build of a program is loaded from the cache and computes the same
// results; a damaged, foreign or rejected entry falls back to compiling and is rewritten; `off`
// and an unusable folder mean compiling every time, never an error; an Engine's setup statistics
// count its own programs only.
//
// Each test points GLCOLLIDE_CACHE_DIR at a fresh folder of its own, so no test depends on what
// another (or an earlier run) left in a cache.

#include "gl/handles.hpp"
#include "gl/program.hpp"
#include "gl/program_cache.hpp"
#include "gl/setup_stats_sink.hpp"
#include "scoped_cache_dir.hpp"
#include "support/two_tet_boxes_scene.hpp"

#include <glcollide/engine.hpp>
#include <glcollide/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

namespace glcollide {
namespace {

namespace fs = std::filesystem;

using test::FreshCacheDir;
using test::ScopedEnv;

const std::string kSource = R"(#version 430
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Out { uint values[]; };
uniform uint u_add;
uniform uint u_count;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < u_count) values[i] = i * 3u + u_add;
}
)";
constexpr std::uint32_t kCount = 200;

// Builds the probe program with a sink open, so the test sees whether it was a cache hit.
struct Built {
    gl::ComputeProgram program;
    SetupStats stats;
};
Built buildProbe() {
    Built b;
    const gl::SetupStatsScope sink(&b.stats);
    b.program = gl::ComputeProgram::fromSource("cache_probe", kSource);
    return b;
}

// Dispatches the program and checks every value it wrote.
void expectComputes(const gl::ComputeProgram& program) {
    const std::vector<std::uint32_t> zeros(kCount, 0u);
    const gl::Buffer out("cacheProbe", kCount * sizeof(std::uint32_t), zeros.data());
    out.bindStorage(0);
    program.use();
    program.set("u_add", 7u);
    program.set("u_count", kCount);
    program.dispatch1D(kCount, 64);
    std::vector<std::uint32_t> values(kCount);
    out.download(0, kCount * sizeof(std::uint32_t), values.data());
    for (std::uint32_t i = 0; i < kCount; ++i) ASSERT_EQ(values[i], i * 3u + 7u) << i;
}

std::string readAll(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeAll(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string probeKey() {
    return gl::programCacheKey(gl::currentDriverIdentity(), kSource);
}

// The driver must offer a binary format for the cache to do anything. Mesa offers one only while
// its own shader cache is enabled (MESA_SHADER_CACHE_DISABLE unset), as it is by default; that is
// a property of the device, so a device without one fails the hit tests loudly rather than
// skipping them.
TEST(ProgramCacheGl, DriverOffersABinaryFormat) {
    EXPECT_FALSE(gl::programBinaryFormats().empty())
        << "GL_NUM_PROGRAM_BINARY_FORMATS is 0 here (Mesa: is MESA_SHADER_CACHE_DISABLE set?)";
}

TEST(ProgramCacheGl, SecondBuildIsAHitAndComputesTheSame) {
    const FreshCacheDir dir;
    const Built first = buildProbe();
    EXPECT_EQ(first.stats.cacheMisses, 1u);
    EXPECT_EQ(first.stats.cacheHits, 0u);
    EXPECT_EQ(first.stats.cacheFolder, dir.path().string());
    EXPECT_EQ(first.stats.cacheNote, "");
    ASSERT_EQ(dir.files().size(), 1u) << "one entry, no temporary file left behind";
    EXPECT_EQ(dir.files()[0].extension(), ".bin");
    EXPECT_TRUE(gl::decodeCacheEntry(readAll(dir.files()[0]), probeKey()).has_value());
    expectComputes(first.program);

    const Built second = buildProbe();
    EXPECT_EQ(second.stats.cacheHits, 1u);
    EXPECT_EQ(second.stats.cacheMisses, 0u);
    ASSERT_EQ(second.stats.programs.size(), 1u);
    EXPECT_TRUE(second.stats.programs[0].cacheHit);
    EXPECT_EQ(second.stats.programs[0].shader, "cache_probe");
    EXPECT_EQ(second.stats.programs[0].sourceHash, gl::fnv1a64(kSource));
    expectComputes(second.program);
}

// Every kind of damage: the build compiles (a miss, no error), the program works, and the entry
// is rewritten so that the next build is a hit.
struct Damage {
    const char* name;
    std::string (*apply)(const std::string& good);
};
// gtest (and ctest's test list) print the parameter by name, not as bytes holding a pointer.
[[maybe_unused]] void PrintTo(const Damage& d, std::ostream* os) {
    *os << d.name;
}

std::string truncateHalf(const std::string& good) {
    return good.substr(0, good.size() / 2);
}
std::string emptyFile(const std::string&) {
    return {};
}
std::string badMagic(const std::string& good) {
    return "XXXXXXXX" + good.substr(8);
}
std::string garbage(const std::string& good) {
    return std::string(good.size(), '\x5a');
}
// The same file name (the key's hash) holding another program's key: a hash collision.
std::string otherKey(const std::string& good) {
    gl::CacheEntry e = *gl::decodeCacheEntry(good, probeKey());
    e.key = gl::programCacheKey(gl::currentDriverIdentity(), kSource + "// another program\n");
    return gl::encodeCacheEntry(e);
}
// An intact file whose binary the driver rejects (e.g. written by another driver build): our
// checksum is right, the driver's own check fails, GL_LINK_STATUS is false.
std::string rejectedByDriver(const std::string& good) {
    gl::CacheEntry e = *gl::decodeCacheEntry(good, probeKey());
    for (std::size_t i = e.binary.size() / 2; i < e.binary.size(); ++i)
        e.binary[i] = static_cast<char>(e.binary[i] ^ 0x55);
    return gl::encodeCacheEntry(e);
}
// A binary format this context does not list (stale entry from another driver).
std::string unknownFormat(const std::string& good) {
    gl::CacheEntry e = *gl::decodeCacheEntry(good, probeKey());
    e.binaryFormat = 0x7fff0001u;
    return gl::encodeCacheEntry(e);
}

class ProgramCacheDamageGl : public ::testing::TestWithParam<Damage> {};

TEST_P(ProgramCacheDamageGl, FallsBackToCompilingAndRewritesTheEntry) {
    const FreshCacheDir dir;
    (void)buildProbe();
    ASSERT_EQ(dir.files().size(), 1u);
    const fs::path entry = dir.files()[0];
    const std::string good = readAll(entry);
    writeAll(entry, GetParam().apply(good));

    const Built rebuilt = buildProbe();
    EXPECT_EQ(rebuilt.stats.cacheMisses, 1u);
    EXPECT_EQ(rebuilt.stats.cacheHits, 0u);
    expectComputes(rebuilt.program);
    ASSERT_EQ(dir.files().size(), 1u);
    EXPECT_TRUE(gl::decodeCacheEntry(readAll(entry), probeKey()).has_value()) << "entry rewritten";

    const Built again = buildProbe();
    EXPECT_EQ(again.stats.cacheHits, 1u);
    expectComputes(again.program);
}

INSTANTIATE_TEST_SUITE_P(Damages, ProgramCacheDamageGl,
                         ::testing::Values(Damage{"truncated", truncateHalf}, Damage{"empty", emptyFile},
                                           Damage{"bad_magic", badMagic}, Damage{"garbage", garbage},
                                           Damage{"other_key", otherKey},
                                           Damage{"rejected_by_driver", rejectedByDriver},
                                           Damage{"unknown_format", unknownFormat}),
                         [](const ::testing::TestParamInfo<Damage>& i) { return std::string(i.param.name); });

TEST(ProgramCacheGl, OffCompilesEveryTimeAndWritesNothing) {
    const FreshCacheDir dir;
    const ScopedEnv off("GLCOLLIDE_CACHE_DIR", "off");
    for (int i = 0; i < 2; ++i) {
        const Built b = buildProbe();
        EXPECT_EQ(b.stats.cacheMisses, 1u);
        EXPECT_EQ(b.stats.cacheHits, 0u);
        EXPECT_EQ(b.stats.cacheFolder, "");
        EXPECT_EQ(b.stats.cacheNote, "GLCOLLIDE_CACHE_DIR=off");
        expectComputes(b.program);
    }
    EXPECT_TRUE(dir.files().empty());
}

TEST(ProgramCacheGl, AFolderThatCannotBeCreatedIsNoError) {
    const FreshCacheDir dir;
    // A folder below a regular file cannot be created, whoever runs the test (root included).
    writeAll(dir.path() / "file", "x");
    const ScopedEnv blocked("GLCOLLIDE_CACHE_DIR", (dir.path() / "file" / "cache").string());
    for (int i = 0; i < 2; ++i) {
        const Built b = buildProbe();
        EXPECT_EQ(b.stats.cacheMisses, 1u);
        EXPECT_NE(b.stats.cacheNote.find("cannot create"), std::string::npos) << b.stats.cacheNote;
        expectComputes(b.program);
    }
}

TEST(ProgramCacheGl, NoSinkRecordsNothingAndStillCaches) {
    const FreshCacheDir dir;
    ASSERT_EQ(gl::activeSetupStats(), nullptr);
    const gl::ComputeProgram program = gl::ComputeProgram::fromSource("cache_probe", kSource);
    EXPECT_EQ(dir.files().size(), 1u);
    expectComputes(program);
}

TEST(ProgramCacheGl, EngineSetupStatsCountItsOwnProgramsOnly) {
    const FreshCacheDir dir;
    const Scene scene = test::twoOverlappingTetBoxes("robust");
    const Engine cold(scene);
    const SetupStats coldStats = cold.setupStats();
    ASSERT_FALSE(coldStats.programs.empty());
    EXPECT_EQ(coldStats.cacheHits, 0u);
    EXPECT_EQ(coldStats.cacheMisses, coldStats.programs.size());
    EXPECT_EQ(coldStats.cacheFolder, dir.path().string());
    double sum = 0.0;
    for (const ProgramSetup& p : coldStats.programs) sum += p.milliseconds;
    EXPECT_DOUBLE_EQ(coldStats.compileLinkMilliseconds, sum);
    bool robustTriTri = false, defines = false;
    for (const ProgramSetup& p : coldStats.programs) {
        robustTriTri |= p.shader == "tri_tri_filtered";
        defines |= p.shader == "node_update" &&
                   std::find(p.defines.begin(), p.defines.end(), "GLC_FORCES") != p.defines.end();
    }
    EXPECT_TRUE(robustTriTri && defines) << "the per-program list names shaders and defines";

    const Engine warm(scene);
    EXPECT_EQ(warm.setupStats().cacheHits, coldStats.programs.size());
    EXPECT_EQ(warm.setupStats().cacheMisses, 0u);
    // The first engine's numbers are its own: building the second did not add to them.
    EXPECT_EQ(cold.setupStats().programs.size(), coldStats.programs.size());
    EXPECT_EQ(cold.setupStats().cacheMisses, coldStats.cacheMisses);
    EXPECT_EQ(gl::activeSetupStats(), nullptr) << "the engine closed its sink";
}

} // namespace
} // namespace glcollide
