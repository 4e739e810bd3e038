#pragma once
// The GL test binary's one context (a gtest Environment) and its GL-error bookkeeping.
// main() lives in gl_test_environment.cpp.

#include "glcollide/headless_context.hpp"

#include <cstddef>

namespace glcollide::test {

/// The options the binary's context is created with: a debug context on the device that
/// GLCOLLIDE_EGL_DEVICE names, else "auto". Tests of context handling create their extra contexts
/// with these, so they run on whatever device the environment provides.
HeadlessContextOptions glTestContextOptions();

/// The binary's HeadlessContext, created with glTestContextOptions().
/// Tests that make another context current must call glTestContext().makeCurrent() afterwards.
HeadlessContext& glTestContext();

/// While alive, GL_DEBUG_TYPE_ERROR messages are counted instead of failing the current test.
/// For tests that provoke a GL error on purpose.
class ExpectGlErrors {
  public:
    ExpectGlErrors();
    ~ExpectGlErrors();
    ExpectGlErrors(const ExpectGlErrors&) = delete;
    ExpectGlErrors& operator=(const ExpectGlErrors&) = delete;
    /// Error messages received since construction.
    std::size_t count() const;

  private:
    std::size_t m_start = 0;
};

/// Environment variable that turns the binary into a child process without the Environment
/// (used to run the "no EGL" checks with a broken EGL setup).
inline constexpr const char* kChildEnvVar = "GLCOLLIDE_GL_TEST_CHILD";

} // namespace glcollide::test
