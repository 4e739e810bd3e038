// The pure parts of the robust self-check (src/engine/robust_self_check.hpp): the built-in case
// set, the mode's spelling, the printed coordinates, which must name every float exactly, and the
// verdict on answers, fed here by simulated devices: the shader library compiled as C++ (the code
// of both kernel sets) as it runs here, on a device that flushes denormal inputs before
// floatBitsToUint reads them, and under a compiler that distributes the filter's products of
// differences into raw coordinates. The soundness argument excludes the last two
// (docs/narrow-phase.md); the self-check must refuse such devices. The check itself runs on the
// device in tests/gl/robust_self_check_gl_test.cpp.

#include "cpu/shader_library.hpp"
#include "engine/robust_self_check.hpp"

#include <glcollide/error.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <limits>
#include <string>

namespace glcollide::engine {
namespace {

TEST(RobustSelfCheckCases, HardCasesThenSeededFamilies) {
    const std::vector<SelfCheckCase>& cases = builtinSelfCheckCases();
    const std::size_t hard = cpu::hardTriTriCases().size();
    EXPECT_GE(hard, 300u);
    ASSERT_EQ(cases.size(), hard + 3 * kSelfCheckSamplePerFamily);
    for (const char* name :
         {"coplanar, one float step off the hypotenuse", "far away, crossing", "far away, above",
          "far away, touching", "far away exact, apex on the face", "denormal triangle pierced"}) {
        bool found = false;
        for (std::size_t i = 0; i < hard; ++i) found |= cases[i].name.rfind(name, 0) == 0;
        EXPECT_TRUE(found) << name;
    }
    EXPECT_EQ(cases[hard].name, "random ulp #0 (seed " + std::to_string(kSelfCheckSeed) + ")");
    EXPECT_EQ(cases.back().name.rfind("random degenerate #", 0), 0u) << cases.back().name;
    EXPECT_EQ(&cases, &builtinSelfCheckCases()) << "built once";
}

TEST(RobustSelfCheckMode, ParsesTheThreeWordsOnly) {
    EXPECT_EQ(parseSelfCheckMode("error", "x"), SelfCheckMode::Error);
    EXPECT_EQ(parseSelfCheckMode("warn", "x"), SelfCheckMode::Warn);
    EXPECT_EQ(parseSelfCheckMode("off", "x"), SelfCheckMode::Off);
    try {
        (void)parseSelfCheckMode("Warn", "GLCOLLIDE_SELF_CHECK");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "GLCOLLIDE_SELF_CHECK: expected error, warn or off, got 'Warn'");
    }
}

// 9 significant digits identify every binary32 value (IEEE 754-2008, 5.12.2), so each printed
// coordinate must read back as the same float, denormals and extremes included.
TEST(RobustSelfCheckFormat, CoordinatesReadBackExactly) {
    cpu::FloatTriPair pair{};
    const float values[] = {0.0f,
                            -0.0f,
                            1.0f / 3.0f,
                            std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::min(),
                            1e-7f,
                            std::nextafter(1.0f, 2.0f),
                            123456.789f};
    for (std::size_t i = 0; i < pair.size(); ++i) pair[i] = values[i % std::size(values)];
    const std::string text = formatTriPair(pair);
    std::size_t at = 0;
    for (std::size_t i = 0; i < pair.size(); ++i) {
        at = text.find_first_of("-0123456789", text.find(i % 3 == 0 ? '(' : ',', at) + 1);
        char* end = nullptr;
        const float back = std::strtof(text.c_str() + at, &end);
        EXPECT_EQ(std::memcmp(&back, &pair[i], sizeof back), 0) << i << ": " << text;
        at = static_cast<std::size_t>(end - text.c_str());
    }
    EXPECT_EQ(text.rfind("a0 (", 0), 0u);
    EXPECT_NE(text.find(" b2 ("), std::string::npos);
}

// A simulated device: the shader library compiled as C++ (both kernel sets run its code: the
// filtered pass, then the exact pass on what it leaves undecided), fed the pair as `read` maps it.
template <typename Read> SelfCheckAnswers libraryAnswers(const char* kernels, Read read) {
    SelfCheckAnswers answers{kernels, {}};
    for (const SelfCheckCase& c : builtinSelfCheckCases()) {
        const cpu::FloatTriPair p = read(c.pair);
        auto v = [&](int k) {
            const auto i = static_cast<std::size_t>(3 * k);
            return glm::vec3(p[i], p[i + 1], p[i + 2]);
        };
        answers.intersect.push_back(shader::robustTrianglesIntersect(v(0), v(1), v(2), v(3), v(4), v(5)) ? 1
                                                                                                         : 0);
    }
    return answers;
}

cpu::FloatTriPair asGiven(const cpu::FloatTriPair& p) {
    return p;
}

// GLSL lets an implementation flush denormal inputs to zero (sign kept); floatBitsToUint then
// reads the zero, and the exact pass decides the flushed pair.
cpu::FloatTriPair denormalsFlushed(const cpu::FloatTriPair& p) {
    cpu::FloatTriPair out = p;
    for (float& f : out) {
        const std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
        if ((bits & 0x7f800000u) == 0) f = std::bit_cast<float>(bits & 0x80000000u);
    }
    return out;
}

std::size_t wrongAmong(const SelfCheckAnswers& answers, const std::string& namePrefix) {
    std::size_t wrong = 0;
    const std::vector<SelfCheckCase>& cases = builtinSelfCheckCases();
    for (std::size_t i = 0; i < cases.size(); ++i)
        if (cases[i].name.rfind(namePrefix, 0) == 0)
            wrong += (answers.intersect[i] != 0) != cpu::exactPairIntersects(cases[i].pair) ? 1 : 0;
    return wrong;
}

TEST(RobustSelfCheckVerdict, TheLibraryAsCompiledHerePasses) {
    SelfCheckReport report;
    judgeSelfCheckAnswers({libraryAnswers("library", asGiven)}, {}, report);
    EXPECT_EQ(report.cases, builtinSelfCheckCases().size());
    EXPECT_EQ(report.wrong, 0u) << report.firstWrong;
}

TEST(RobustSelfCheckVerdict, NamesTheKernelsThatAnsweredWrong) {
    SelfCheckAnswers right = libraryAnswers("right kernels", asGiven), wrong = right;
    wrong.kernels = "wrong kernels";
    wrong.intersect[7] ^= 1;
    SelfCheckReport report;
    judgeSelfCheckAnswers({right, wrong}, {}, report);
    EXPECT_EQ(report.wrong, 1u);
    EXPECT_EQ(report.firstWrong.rfind("case 7 \"", 0), 0u) << report.firstWrong;
    EXPECT_NE(report.firstWrong.find("from the wrong kernels"), std::string::npos) << report.firstWrong;
    EXPECT_EQ(report.firstWrong.find("right kernels"), std::string::npos) << report.firstWrong;
}

// Docs (narrow-phase.md, "On-device self-check"): a device that flushes denormal inputs decides
// the flushed pair, which differs from the given one; the self-check's denormal cases expose it.
TEST(RobustSelfCheckVerdict, ADeviceThatFlushesDenormalInputsIsRefused) {
    const SelfCheckAnswers flushed = libraryAnswers("flushing device", denormalsFlushed);
    SelfCheckReport report;
    judgeSelfCheckAnswers({flushed}, {}, report);
    EXPECT_GT(report.wrong, 0u) << "the self-check would accept a device that flushes denormal inputs";
    EXPECT_NE(report.firstWrong.find("denormal"), std::string::npos) << report.firstWrong;
    std::printf("[ verdict  ] denormal inputs flushed: %u of %u cases wrong; first: %s\n", report.wrong,
                report.cases, report.firstWrong.c_str());
}

// The argument also excludes a compiler that expands the filter's products of coordinate
// differences into raw coordinates ((b - a) * y into b * y - a * y): for small triangles far from
// the origin the float determinant is then mostly rounding error of products of large
// coordinates, while the permanent (abs() keeps it in differences) stays small, so the filter
// certifies signs at random. The self-check's far-from-origin cases must expose it.
float tripleProduct(glm::vec3 x, glm::vec3 y, glm::vec3 z) {
    return x.x * (y.y * z.z - y.z * z.y) + x.y * (y.z * z.x - y.x * z.z) + x.z * (y.x * z.y - y.y * z.x);
}
glm::vec3 distributedEstimate(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    glm::vec3 e = shader::glcOrient3dEstimate(a, b, c, d);
    // det[b-a, c-a, d-a] = [b,c,d] - [a,c,d] - [b,a,d] - [b,c,a] (multilinearity; terms with two
    // a's vanish): 24 products of raw coordinates.
    e.x = tripleProduct(b, c, d) - tripleProduct(a, c, d) - tripleProduct(b, a, d) - tripleProduct(b, c, a);
    return e;
}

TEST(RobustSelfCheckVerdict, ACompilerThatDistributesIntoRawCoordinatesIsRefused) {
    shader::orient3dEstimateOverride = &distributedEstimate;
    const SelfCheckAnswers distributed = libraryAnswers("distributing compiler", asGiven);
    shader::orient3dEstimateOverride = nullptr;
    SelfCheckReport report;
    judgeSelfCheckAnswers({distributed}, {}, report);
    EXPECT_GT(report.wrong, 0u) << "the self-check would accept a distributing compiler";
    const std::size_t far = wrongAmong(distributed, "far away");
    EXPECT_GT(far, 0u) << "the far-from-origin cases must expose it";
    std::printf("[ verdict  ] products distributed into raw coordinates: %u of %u cases wrong (%zu of them "
                "\"far away\"); first: %s\n",
                report.wrong, report.cases, far, report.firstWrong.c_str());
}

} // namespace
} // namespace glcollide::engine
