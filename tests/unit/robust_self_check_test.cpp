// The pure parts of the robust self-check (src/engine/robust_self_check.hpp): the built-in case
// set, the mode's spelling, and the printed coordinates, which must name every float exactly. The
// check itself runs on the device in tests/gl/robust_self_check_gl_test.cpp.

#include "engine/robust_self_check.hpp"

#include <glcollide/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
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

} // namespace
} // namespace glcollide::engine
