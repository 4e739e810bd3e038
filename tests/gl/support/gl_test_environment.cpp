#include "support/gl_test_environment.hpp"

#include "gl/debug_output.hpp"
#include "glcollide/error.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace glcollide::test {

namespace {

// Shared between the debug callback (which may run on a driver thread if a test turns
// synchronous output off) and the listener.
struct ErrorLog {
    std::mutex mutex;
    std::vector<std::string> pending; // errors not yet reported
    std::size_t total = 0;            // all errors ever received
    int expectScopes = 0;             // live ExpectGlErrors
};
ErrorLog& errorLog() {
    static ErrorLog log;
    return log;
}

std::unique_ptr<HeadlessContext> g_context;
std::string g_contextError; // why g_context could not be created

class GlTestEnvironment final : public ::testing::Environment {
  public:
    void SetUp() override {
        try {
            g_context = std::make_unique<HeadlessContext>(glTestContextOptions());
        } catch (const Error& e) {
            // CI runs these tests on llvmpipe: a missing context must be red, not skipped. A failure
            // here would make gtest print every test as SKIPPED (and ctest's skip regex would
            // hide it), so the listener fails each test instead.
            g_contextError = e.what();
            std::fprintf(stderr, "cannot create the GL test context: %s\n", e.what());
            return;
        }
        const GlInfo& info = g_context->glInfo();
        std::printf("[ GL context ] %s | EGL %s (%s) | %s | %s%s%s\n", g_context->deviceDescription().c_str(),
                    g_context->eglVersion().c_str(), g_context->eglVendor().c_str(), info.renderer.c_str(),
                    info.version.c_str(), info.debugContext ? " | debug" : "",
                    g_context->surfaceless() ? " | surfaceless" : " | pbuffer");
        m_debug.emplace(
            [](const gl::DebugMessage& message) {
                // Compile/link errors reach the debug log as errors too, but they are reported
                // (with file and line) by the program code, and tests provoke them on purpose.
                if (message.type != GL_DEBUG_TYPE_ERROR || message.source == GL_DEBUG_SOURCE_SHADER_COMPILER)
                    return;
                ErrorLog& log = errorLog();
                std::lock_guard lock(log.mutex);
                ++log.total;
                if (log.expectScopes == 0)
                    log.pending.push_back("GL error (id " + std::to_string(message.id) +
                                          "): " + std::string(message.text));
            },
            gl::DebugOutputScope::kEnableOutput | gl::DebugOutputScope::kSynchronous);
    }

    void TearDown() override {
        if (g_context) g_context->makeCurrent();
        m_debug.reset();
        g_context.reset();
    }

  private:
    std::optional<gl::DebugOutputScope> m_debug;
};

// Fails the test during which a GL error message arrived. OnTestEnd runs before the default
// printer's (end events go to listeners in reverse order), so the failure is shown with the test.
class GlErrorListener final : public ::testing::EmptyTestEventListener {
    void OnTestStart(const ::testing::TestInfo&) override {
        takePending();
        // A fatal failure before the test object runs keeps its body (and its GL calls) from running.
        if (!g_context && !g_contextError.empty()) FAIL() << "no GL test context: " << g_contextError;
    }
    void OnTestEnd(const ::testing::TestInfo&) override {
        for (const std::string& message : takePending()) ADD_FAILURE() << message;
    }
    static std::vector<std::string> takePending() {
        ErrorLog& log = errorLog();
        std::lock_guard lock(log.mutex);
        return std::exchange(log.pending, {});
    }
};

} // namespace

HeadlessContextOptions glTestContextOptions() {
    HeadlessContextOptions options;
    options.debug = true; // device left empty: GLCOLLIDE_EGL_DEVICE or auto, resolved by HeadlessContext
    return options;
}

HeadlessContext& glTestContext() {
    if (!g_context) throw std::logic_error("glTestContext(): the GL test environment has no context");
    return *g_context;
}

ExpectGlErrors::ExpectGlErrors() {
    ErrorLog& log = errorLog();
    std::lock_guard lock(log.mutex);
    ++log.expectScopes;
    m_start = log.total;
}

ExpectGlErrors::~ExpectGlErrors() {
    ErrorLog& log = errorLog();
    std::lock_guard lock(log.mutex);
    --log.expectScopes;
}

std::size_t ExpectGlErrors::count() const {
    ErrorLog& log = errorLog();
    std::lock_guard lock(log.mutex);
    return log.total - m_start;
}

} // namespace glcollide::test

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    // A child run (see context_gl_test.cpp) tests context creation itself, so it gets no Environment.
    if (std::getenv(glcollide::test::kChildEnvVar) == nullptr) {
        ::testing::AddGlobalTestEnvironment(new glcollide::test::GlTestEnvironment);
        ::testing::UnitTest::GetInstance()->listeners().Append(new glcollide::test::GlErrorListener);
    }
    return RUN_ALL_TESTS();
}
