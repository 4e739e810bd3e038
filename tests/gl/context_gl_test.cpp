// HeadlessContext and GlInfo on the binary's context (llvmpipe in CI), plus the "no EGL" path in a
// child process. Context handling is tested on whatever device the environment uses; the few tests
// that need Mesa itself say so with GLCOLLIDE_REQUIRE_MESA (support/require_mesa.hpp).

#include "glcollide/error.hpp"
#include "glcollide/gl_info.hpp"
#include "glcollide/headless_context.hpp"
#include "support/gl_test_environment.hpp"
#include "support/require_mesa.hpp"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern char** environ;

namespace glcollide {
namespace {

using test::glTestContext;
using test::glTestContextOptions;

bool isPowerOfTwo(int v) {
    return v > 0 && (v & (v - 1)) == 0;
}

// After a test made another context current (or none), the environment's context must be back.
void restoreTestContext() {
    glTestContext().makeCurrent();
    ASSERT_NE(glGetString(GL_VERSION), nullptr);
}

TEST(HeadlessContext, EnvironmentContextIsGl43CoreDebug) {
    const GlInfo& info = glTestContext().glInfo();
    std::printf("device: %s\nEGL: %s %s\nGL: %s | %s | %s | GLSL %s\n",
                glTestContext().deviceDescription().c_str(), glTestContext().eglVendor().c_str(),
                glTestContext().eglVersion().c_str(), info.vendor.c_str(), info.renderer.c_str(),
                info.version.c_str(), info.glslVersion.c_str());
    EXPECT_TRUE(info.major > 4 || (info.major == 4 && info.minor >= 3)) << info.version;
    EXPECT_TRUE(info.coreProfile);
    EXPECT_TRUE(info.debugContext);
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_NE(profile & GL_CONTEXT_CORE_PROFILE_BIT, 0);
    EXPECT_FALSE(info.renderer.empty());
    EXPECT_FALSE(glTestContext().eglVersion().empty());
    EXPECT_FALSE(glTestContext().deviceDescription().empty());
    // queryGlInfo on the already-current context agrees with what creation recorded.
    const GlInfo again = queryGlInfo();
    EXPECT_EQ(again.renderer, info.renderer);
    EXPECT_EQ(again.major, info.major);
    EXPECT_NO_THROW(requireGl43());
}

TEST(HeadlessContext, ComputeLimitsAreSane) {
    const ComputeLimits& l = glTestContext().glInfo().limits;
    // GL 4.3 minimums (spec table 23.x): 1024 invocations, 8 storage blocks, 65535 groups, 32 KiB shared.
    EXPECT_GE(l.maxWorkGroupInvocations, 1024);
    EXPECT_GE(l.maxComputeShaderStorageBlocks, 8);
    EXPECT_GE(l.maxShaderStorageBufferBindings, 8);
    EXPECT_GE(l.maxShaderStorageBlockBytes, std::int64_t{1} << 24);
    EXPECT_GE(l.maxSharedMemoryBytes, 32768);
    for (int axis = 0; axis < 3; ++axis) EXPECT_GE(l.maxWorkGroupCount[axis], 65535) << axis;
    EXPECT_GE(l.maxWorkGroupSize[0], 1024);
    EXPECT_GE(l.maxWorkGroupSize[2], 64);
    EXPECT_TRUE(isPowerOfTwo(l.shaderStorageBufferOffsetAlignment)) << l.shaderStorageBufferOffsetAlignment;
    // GL_TIMESTAMP queries are core since GL 3.3 and the engine's per-pass GPU timing reads them:
    // a counter of 0 bits (no timer) must fail here rather than time every pass as 0 ms. At most 64:
    // results are GLuint64. (llvmpipe and the NVIDIA driver report 64.)
    EXPECT_GT(l.timestampBits, 0);
    EXPECT_LE(l.timestampBits, 64);
}

TEST(HeadlessContext, RendererSoftwareFlagMatchesName) {
    const GlInfo& info = glTestContext().glInfo();
    const bool named = info.renderer.find("llvmpipe") != std::string::npos ||
                       info.renderer.find("softpipe") != std::string::npos;
    if (named) {
        EXPECT_TRUE(info.isSoftware);
    }
}

TEST(HeadlessContext, ListDevicesReportsSoftwareFlag) {
    const std::vector<EglDeviceInfo> devices = HeadlessContext::listDevices();
    for (const EglDeviceInfo& d : devices) {
        std::printf("%s | extensions: %s\n", d.description().c_str(), d.extensions.c_str());
        EXPECT_EQ(d.software, d.extensions.find("EGL_MESA_device_software") != std::string::npos);
        EXPECT_EQ(d.description().rfind("EGL device " + std::to_string(d.index), 0), 0u);
    }
    for (std::size_t i = 0; i < devices.size(); ++i) EXPECT_EQ(devices[i].index, static_cast<int>(i));
    if (glTestContext().eglVendor().find("Mesa") != std::string::npos) {
        // Mesa always lists its software device (platform.md §1.2).
        ASSERT_GE(devices.size(), 1u);
        bool anySoftware = false;
        for (const EglDeviceInfo& d : devices) anySoftware = anySoftware || d.software;
        EXPECT_TRUE(anySoftware);
    }
}

TEST(HeadlessContext, SecondContextCoexists) {
    {
        // The environment's options pick the environment's device again (a GPU, or llvmpipe).
        HeadlessContext second(glTestContextOptions());
        EXPECT_EQ(second.deviceDescription(), glTestContext().deviceDescription());
        EXPECT_EQ(second.glInfo().renderer, glTestContext().glInfo().renderer);
        EXPECT_GE(second.glInfo().major, 4);
        EXPECT_NE(glGetString(GL_VERSION), nullptr);
        // Moving keeps one owner of the EGL objects.
        HeadlessContext moved(std::move(second));
        moved.makeCurrent();
        EXPECT_FALSE(moved.deviceDescription().empty());
        std::printf("second context: %s | %s\n", moved.deviceDescription().c_str(),
                    moved.glInfo().renderer.c_str());
    }
    // Destroying the current second context leaves nothing current on this thread.
    EXPECT_EQ(eglGetCurrentContext(), EGL_NO_CONTEXT);
    restoreTestContext();
    EXPECT_EQ(queryGlInfo().renderer, glTestContext().glInfo().renderer);
}

TEST(HeadlessContext, DestroyingANonCurrentContextKeepsTheCurrentOne) {
    auto second = std::make_unique<HeadlessContext>(glTestContextOptions());
    restoreTestContext();
    const EGLContext envContext = eglGetCurrentContext();
    second.reset();
    EXPECT_EQ(eglGetCurrentContext(), envContext);
    EXPECT_NE(glGetString(GL_VERSION), nullptr);
}

// The software device's EGLDisplay as a host would open it (nullptr without one).
EGLDisplay softwareDeviceDisplay() {
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
        !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base"))
        return EGL_NO_DISPLAY;
    for (const EglDeviceInfo& d : HeadlessContext::listDevices()) {
        if (!d.software) continue;
        std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(d.index) + 1);
        EGLint count = 0;
        if (!eglQueryDevicesEXT(static_cast<EGLint>(handles.size()), handles.data(), &count) ||
            count <= d.index)
            return EGL_NO_DISPLAY;
        return eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, handles[static_cast<std::size_t>(d.index)],
                                        nullptr);
    }
    return EGL_NO_DISPLAY;
}

bool displayInitialised(EGLDisplay display) {
    const bool initialised = eglQueryString(display, EGL_VERSION) != nullptr;
    eglGetError();
    return initialised;
}

TEST(HeadlessContext, TerminatesOnlyDisplaysItInitialised) {
    // The software device is a display that a host can open itself and that the environment's
    // context usually does not use (Mesa's surfaceless platform does), so both halves below run.
    GLCOLLIDE_REQUIRE_MESA("open its software device's EGL display as a host would");
    const EGLDisplay display = softwareDeviceDisplay();
    ASSERT_NE(display, EGL_NO_DISPLAY)
        << "Mesa lists a software device, but its EGL display cannot be opened";
    // When the environment's context lives on the same display, it is not ours to terminate.
    const bool sharedWithEnvironment = displayInitialised(display);
    HeadlessContextOptions options;
    options.device = "software";

    // Ours: terminated with the last HeadlessContext using it.
    std::make_unique<HeadlessContext>(options).reset();
    EXPECT_EQ(displayInitialised(display), sharedWithEnvironment);

    // A host's: initialised before us, so it must survive our context.
    if (!sharedWithEnvironment) {
        EGLint major = 0, minor = 0;
        ASSERT_TRUE(eglInitialize(display, &major, &minor));
        std::make_unique<HeadlessContext>(options).reset();
        EXPECT_TRUE(displayInitialised(display));
        eglTerminate(display);
    }
    restoreTestContext();
}

TEST(HeadlessContext, MoveAssignmentReleasesTheOldContext) {
    HeadlessContext a(glTestContextOptions());
    HeadlessContext b(glTestContextOptions());
    a = std::move(b); // destroys a's context; b's (current) survives in a
    EXPECT_NE(eglGetCurrentContext(), EGL_NO_CONTEXT);
    a.makeCurrent();
    EXPECT_NE(glGetString(GL_VERSION), nullptr);
    restoreTestContext();
}

TEST(HeadlessContext, PbufferFallbackGivesGl43) {
    HeadlessContextOptions options;
    options.forcePbuffer = true;
    {
        HeadlessContext pbuffer(options);
        EXPECT_FALSE(pbuffer.surfaceless());
        EXPECT_TRUE(pbuffer.glInfo().coreProfile);
        EXPECT_TRUE(pbuffer.glInfo().major > 4 ||
                    (pbuffer.glInfo().major == 4 && pbuffer.glInfo().minor >= 3));
    }
    restoreTestContext();
}

TEST(HeadlessContext, MissingDeviceIndexIsAnErrorListingDevices) {
    HeadlessContextOptions options;
    options.device = "99";
    try {
        HeadlessContext missing(options);
        FAIL() << "device 99 should not exist";
    } catch (const Error& e) {
        const std::string message = e.what();
        std::printf("message: %s\n", message.c_str());
        EXPECT_NE(message.find("99"), std::string::npos) << message;
        const std::vector<EglDeviceInfo> devices = HeadlessContext::listDevices();
        if (devices.empty()) {
            EXPECT_NE(message.find("no EGL devices"), std::string::npos) << message;
        }
        for (const EglDeviceInfo& d : devices)
            EXPECT_NE(message.find(d.description()), std::string::npos) << message;
    }
    // Nothing was touched: the environment's context is still current.
    EXPECT_NE(glGetString(GL_VERSION), nullptr);
}

TEST(HeadlessContext, RequireGpuOnSoftwareFailsAndKeepsTheCurrentContext) {
    if (!glTestContext().glInfo().isSoftware) GTEST_SKIP() << "a GPU is present";
    const EGLContext envContext = eglGetCurrentContext();
    HeadlessContextOptions options;
    options.device = "auto";
    options.requireGpu = true;
    try {
        HeadlessContext gpu(options);
        ADD_FAILURE() << "requireGpu succeeded on " << gpu.glInfo().renderer;
    } catch (const Error& e) {
        const std::string message = e.what();
        std::printf("message: %s\n", message.c_str());
        EXPECT_TRUE(message.find("GPU") != std::string::npos) << message;
    }
    // The failed attempt made its own context current and released it; ours is back.
    EXPECT_EQ(eglGetCurrentContext(), envContext);
    EXPECT_NE(glGetString(GL_VERSION), nullptr);
}

TEST(HeadlessContext, MissingCudaOrdinalIsAnError) {
    HeadlessContextOptions options;
    options.device = "cuda:4096";
    EXPECT_THROW(HeadlessContext missing(options), Error);
    EXPECT_NE(glGetString(GL_VERSION), nullptr);
}

TEST(HeadlessContext, InvalidSelectorFromEnvironmentNamesTheVariable) {
    const char* previous = std::getenv("GLCOLLIDE_EGL_DEVICE");
    const std::string saved = previous ? previous : "";
    ::setenv("GLCOLLIDE_EGL_DEVICE", "gpu", 1);
    try {
        HeadlessContext bad{};
        ADD_FAILURE() << "\"gpu\" is not a valid selector";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("GLCOLLIDE_EGL_DEVICE"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("\"gpu\""), std::string::npos) << e.what();
    }
    if (previous)
        ::setenv("GLCOLLIDE_EGL_DEVICE", saved.c_str(), 1);
    else
        ::unsetenv("GLCOLLIDE_EGL_DEVICE");
}

TEST(GlInfo, NoCurrentContextIsAnError) {
    eglBindAPI(EGL_OPENGL_API);
    ASSERT_TRUE(eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
    try {
        queryGlInfo();
        ADD_FAILURE() << "queryGlInfo without a context should throw";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no OpenGL context"), std::string::npos) << e.what();
    }
    EXPECT_THROW(requireGl43(), Error);
    restoreTestContext();
}

// ---- "no EGL": a child process with a vendor list that loads nothing --------------------------

struct ChildResult {
    bool exited = false;
    int exitCode = -1;
    int signal = 0;
    std::string output;
};

ChildResult runSelfAsChild(const std::string& filter, const std::vector<std::string>& extraEnv) {
    // Everything the child needs is built before fork(): after it only exec-safe calls are made.
    std::vector<std::string> args = {"/proc/self/exe", "--gtest_filter=" + filter,
                                     "--gtest_also_run_disabled_tests", "--gtest_color=no"};
    std::vector<std::string> env = extraEnv;
    env.push_back(std::string(test::kChildEnvVar) + "=1");
    for (char** e = environ; *e != nullptr; ++e) {
        const std::string entry = *e;
        // A sharded run's variables would make the child run its shard of the one-test filter,
        // often nothing (seen on the H200 run at bd8506c).
        if (entry.rfind("GTEST_SHARD_INDEX=", 0) == 0 || entry.rfind("GTEST_TOTAL_SHARDS=", 0) == 0 ||
            entry.rfind("GTEST_SHARD_STATUS_FILE=", 0) == 0)
            continue;
        bool overridden = false;
        for (const std::string& extra : env)
            overridden =
                overridden || entry.substr(0, entry.find('=') + 1) == extra.substr(0, extra.find('=') + 1);
        if (!overridden) env.push_back(entry);
    }
    std::vector<char*> argv, envp;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    for (std::string& e : env) envp.push_back(e.data());
    envp.push_back(nullptr);

    std::array<int, 2> pipeFds{};
    if (::pipe(pipeFds.data()) != 0) return {};
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(pipeFds[1], STDOUT_FILENO);
        ::dup2(pipeFds[1], STDERR_FILENO);
        ::close(pipeFds[0]);
        ::close(pipeFds[1]);
        ::execve(argv[0], argv.data(), envp.data());
        ::_exit(127);
    }
    ::close(pipeFds[1]);
    ChildResult result;
    char buffer[4096];
    ssize_t n = 0;
    while ((n = ::read(pipeFds[0], buffer, sizeof buffer)) > 0)
        result.output.append(buffer, static_cast<std::size_t>(n));
    ::close(pipeFds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    result.exited = WIFEXITED(status);
    result.exitCode = result.exited ? WEXITSTATUS(status) : -1;
    result.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    return result;
}

constexpr const char* kNoEglMarker = "GLCOLLIDE_CHILD_ERROR: ";

// Runs only in the child (kChildEnvVar set, no Environment). Fails on purpose when context
// creation throws, so the child's exit code is non-zero as a CLI's would be.
TEST(NoEglChild, DISABLED_CreateContext) {
    if (std::getenv(test::kChildEnvVar) == nullptr) GTEST_SKIP() << "runs only as a child process";
    const std::vector<EglDeviceInfo> devices = HeadlessContext::listDevices();
    std::printf("GLCOLLIDE_CHILD_DEVICES: %zu\n", devices.size());
    try {
        HeadlessContext context{};
        std::printf("GLCOLLIDE_CHILD_CREATED: %s\n", context.deviceDescription().c_str());
    } catch (const Error& e) {
        std::printf("%s%s\n", kNoEglMarker, e.what());
        std::fflush(stdout);
        FAIL() << "context creation failed (expected in the no-EGL child)";
    }
}

TEST(HeadlessContext, NoEglVendorGivesAClearErrorNotAnAbort) {
    const ChildResult child = runSelfAsChild("NoEglChild.DISABLED_CreateContext",
                                             {"__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json"});
    SCOPED_TRACE(child.output);
    ASSERT_TRUE(child.exited) << "child killed by signal " << child.signal << " (SIGABRT is " << SIGABRT
                              << ")";
    EXPECT_NE(child.exitCode, 0);
    EXPECT_NE(child.exitCode, 127) << "exec failed";
    EXPECT_NE(child.output.find("GLCOLLIDE_CHILD_DEVICES: 0"), std::string::npos);
    const std::size_t at = child.output.find(kNoEglMarker);
    ASSERT_NE(at, std::string::npos);
    const std::string message = child.output.substr(at, child.output.find('\n', at) - at);
    // Says what is missing and how to get it.
    EXPECT_NE(message.find("EGL"), std::string::npos) << message;
    EXPECT_NE(message.find("libegl-mesa0"), std::string::npos) << message;
    EXPECT_NE(message.find("__EGL_VENDOR_LIBRARY_FILENAMES"), std::string::npos) << message;
    EXPECT_EQ(child.output.find("No provider of"), std::string::npos)
        << "libepoxy aborted on a missing provider";
}

TEST(HeadlessContext, NoGl43GivesAClearErrorNamingTheVersionAndThePackages) {
    // Mesa capped at GL 4.2 stands in for a driver without compute shaders. Only Mesa reads the cap,
    // so the child is sent to Mesa's software device even where a GPU would come first.
    GLCOLLIDE_REQUIRE_MESA("cap its OpenGL version at 4.2 with MESA_GL_VERSION_OVERRIDE");
    const ChildResult child =
        runSelfAsChild("NoEglChild.DISABLED_CreateContext",
                       {"MESA_GL_VERSION_OVERRIDE=4.2", "GLCOLLIDE_EGL_DEVICE=software"});
    SCOPED_TRACE(child.output);
    ASSERT_TRUE(child.exited) << "child killed by signal " << child.signal;
    EXPECT_NE(child.exitCode, 0);
    const std::size_t at = child.output.find(kNoEglMarker);
    ASSERT_NE(at, std::string::npos);
    const std::string message = child.output.substr(at); // several lines: one per EGL display tried
    EXPECT_NE(message.find("cannot create an OpenGL 4.3 core context"), std::string::npos) << message;
    EXPECT_NE(message.find("the driver offers no OpenGL 4.3 core context"), std::string::npos) << message;
    EXPECT_NE(message.find("libgl1-mesa-dri"), std::string::npos) << "no install hint";
}

TEST(HeadlessContext, ChildWithWorkingEglCreatesAContext) {
    // The same child without the broken vendor list: proves the child harness itself works, so the
    // test above fails for the right reason.
    const ChildResult child = runSelfAsChild("NoEglChild.DISABLED_CreateContext", {});
    SCOPED_TRACE(child.output);
    ASSERT_TRUE(child.exited) << "signal " << child.signal;
    // Not the exit code: under LeakSanitizer, Mesa's own leaks make it non-zero.
    EXPECT_NE(child.output.find("[  PASSED  ] 1 test"), std::string::npos);
    EXPECT_NE(child.output.find("GLCOLLIDE_CHILD_CREATED: "), std::string::npos);
}

} // namespace
} // namespace glcollide
