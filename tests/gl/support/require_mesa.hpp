#pragma once
// The one way a GL test says that it needs Mesa (its EGL software device, llvmpipe, or a Mesa-only
// switch such as MESA_GL_VERSION_OVERRIDE). Everything else runs on whatever device the
// environment's context uses (an NVIDIA GPU has no Mesa at all).
//
// Without Mesa's software device such a test is skipped, with a message naming what is missing
// and what the test needs Mesa for. CI has Mesa, so .ci/run sets GLCOLLIDE_REQUIRE_MESA=1, which
// turns the skip into a failure: a broken Mesa setup cannot pass as a row of skips there.

#include <gtest/gtest.h>

#include <string>

namespace glcollide::test {

/// "1" turns GLCOLLIDE_REQUIRE_MESA's skip into a failure.
inline constexpr const char* kRequireMesaEnvVar = "GLCOLLIDE_REQUIRE_MESA";

/// Empty when an EGL device advertises EGL_MESA_device_software (Mesa's llvmpipe); otherwise what
/// is missing, in words.
std::string missingMesa();

/// True when the environment variable GLCOLLIDE_REQUIRE_MESA is "1".
bool mesaRequired();

/// The skip or failure message: what is missing, and why the test needs Mesa.
std::string mesaMissingMessage(const std::string& missing, const std::string& why);

} // namespace glcollide::test

/// In a test body: returns from the test (skipped, or failed under GLCOLLIDE_REQUIRE_MESA=1) when
/// Mesa's software device is absent. `why` completes "this test needs Mesa to ...".
/// A macro because GTEST_SKIP() and FAIL() return from the function they are written in.
#define GLCOLLIDE_REQUIRE_MESA(why)                                                                          \
    do {                                                                                                     \
        if (const std::string glcollideMissing_ = ::glcollide::test::missingMesa();                          \
            !glcollideMissing_.empty()) {                                                                    \
            const std::string glcollideMessage_ =                                                            \
                ::glcollide::test::mesaMissingMessage(glcollideMissing_, why);                               \
            if (::glcollide::test::mesaRequired()) FAIL() << glcollideMessage_;                              \
            GTEST_SKIP() << glcollideMessage_;                                                               \
        }                                                                                                    \
    } while (false)
