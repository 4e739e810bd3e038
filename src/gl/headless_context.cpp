#include "glcollide/headless_context.hpp"

#include "gl/egl_devices.hpp"
#include "glcollide/error.hpp"

#include <epoxy/egl.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <optional>

namespace glcollide {

namespace {

std::string eglErrorName(EGLint code) {
    switch (code) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CURRENT_SURFACE:
        return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_SURFACE:
        return "EGL_BAD_SURFACE";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    case EGL_BAD_NATIVE_PIXMAP:
        return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
        return "EGL_BAD_NATIVE_WINDOW";
    case EGL_CONTEXT_LOST:
        return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT:
        return "EGL_BAD_DEVICE_EXT";
    default:
        return "EGL error 0x" + [&] {
            char buf[16];
            std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>(code));
            return std::string(buf);
        }();
    }
}

std::string lastEglError() {
    return eglErrorName(eglGetError());
}

// eglCreateContext's EGL_BAD_MATCH usually means the driver's GL is older than the 4.3 we ask for.
std::string contextCreationError() {
    const EGLint code = eglGetError();
    return eglErrorName(code) +
           (code == EGL_BAD_MATCH ? " (the driver offers no OpenGL 4.3 core context)" : "");
}

// EGL displays are process-wide singletons per (platform, native display) and eglTerminate is not
// reference-counted, so two HeadlessContexts on the same display must not terminate it under each
// other. This registry counts only displays *we* initialised; a display someone else (a host)
// had already initialised is never terminated by us.
struct DisplayRegistry {
    std::mutex mutex;
    std::map<EGLDisplay, int> references;
};
DisplayRegistry& displayRegistry() {
    static DisplayRegistry registry;
    return registry;
}

// Initialises `display`; returns whether we own a reference (and so must release it), or an error.
struct Acquired {
    bool owned = false;
    std::string error;
};
Acquired acquireDisplay(EGLDisplay display) {
    DisplayRegistry& reg = displayRegistry();
    std::lock_guard lock(reg.mutex);
    EGLint major = 0, minor = 0;
    if (auto it = reg.references.find(display); it != reg.references.end()) {
        ++it->second;
        return {true, {}};
    }
    // EGL_VERSION is only readable on an initialised display: a non-NULL answer means someone
    // else initialised it and owns its termination.
    const bool foreign = eglQueryString(display, EGL_VERSION) != nullptr;
    if (!foreign) eglGetError(); // drop the expected EGL_NOT_INITIALIZED
    if (!eglInitialize(display, &major, &minor)) return {false, "eglInitialize failed: " + lastEglError()};
    if (foreign) return {false, {}};
    reg.references[display] = 1;
    return {true, {}};
}
void releaseDisplay(EGLDisplay display) {
    DisplayRegistry& reg = displayRegistry();
    std::lock_guard lock(reg.mutex);
    auto it = reg.references.find(display);
    if (it == reg.references.end()) return;
    if (--it->second == 0) {
        eglTerminate(display);
        reg.references.erase(it);
    }
}

bool displayHas(EGLDisplay display, const char* extension) {
    return epoxy_has_egl_extension(display, extension);
}

} // namespace

struct HeadlessContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE; // 1x1 pbuffer, only when surfaceless is unavailable
    bool ownsDisplay = false;
    GlInfo glInfo;
    std::string eglVendor;
    std::string eglVersion;
    std::string description;

    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl() { destroy(); }

    void destroyContextAndSurface() {
        if (context != EGL_NO_CONTEXT) {
            // A context destroyed while current is only marked for deletion ("zombie", Magnum):
            // release it first, but only if it is ours that is current, not some other context.
            if (eglGetCurrentContext() == context) {
                eglBindAPI(EGL_OPENGL_API); // eglMakeCurrent(NO_CONTEXT) releases the bound API's context
                eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            }
            eglDestroyContext(display, context);
            context = EGL_NO_CONTEXT;
        }
        if (surface != EGL_NO_SURFACE) {
            eglDestroySurface(display, surface);
            surface = EGL_NO_SURFACE;
        }
    }

    void destroy() {
        if (display == EGL_NO_DISPLAY) return;
        destroyContextAndSurface();
        if (ownsDisplay) releaseDisplay(display);
        display = EGL_NO_DISPLAY;
        ownsDisplay = false;
        // eglReleaseThread would also release whatever other context is current on this thread.
        if (eglGetCurrentContext() == EGL_NO_CONTEXT) eglReleaseThread();
    }

    // Creates a 4.3 core context on the initialised `display` and makes it current. Returns an
    // error description on failure (and leaves nothing behind).
    std::optional<std::string> createContext(const HeadlessContextOptions& options) {
        if (!eglBindAPI(EGL_OPENGL_API))
            return "eglBindAPI(EGL_OPENGL_API) failed (" + lastEglError() +
                   "): no desktop OpenGL on this display";

        EGLint eglMajor = 0, eglMinor = 0;
        eglInitialize(display, &eglMajor, &eglMinor); // already initialised: just reads the version
        const bool egl15 = eglMajor > 1 || (eglMajor == 1 && eglMinor >= 5);
        const bool createContextKhr = displayHas(display, "EGL_KHR_create_context");
        std::vector<EGLint> attribs;
        if (egl15 || createContextKhr) {
            // Binary drivers give exactly the version asked for (Magnum), so ask for 4.3 core.
            attribs = {EGL_CONTEXT_MAJOR_VERSION_KHR,       4,
                       EGL_CONTEXT_MINOR_VERSION_KHR,       3,
                       EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR};
            if (options.debug) {
                if (egl15)
                    attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
                else
                    attribs.insert(attribs.end(), {EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR});
            }
        }
        attribs.push_back(EGL_NONE);

        std::string failures;
        const bool noConfig = displayHas(display, "EGL_KHR_no_config_context") ||
                              displayHas(display, "EGL_MESA_configless_context");
        const bool surfacelessExt = displayHas(display, "EGL_KHR_surfaceless_context");
        if (options.forcePbuffer) {
            failures = "surfaceless skipped (forcePbuffer); ";
        } else if (!noConfig || !surfacelessExt) {
            failures = std::string("surfaceless path unavailable (") +
                       (noConfig ? "" : "no EGL_KHR_no_config_context ") +
                       (surfacelessExt ? "" : "no EGL_KHR_surfaceless_context") + "); ";
        } else {
            context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs.data());
            if (context == EGL_NO_CONTEXT) {
                failures =
                    "eglCreateContext(EGL_NO_CONFIG_KHR, GL 4.3 core) failed: " + contextCreationError() +
                    "; ";
            } else if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
                // Advertising surfaceless does not guarantee it works (google/filament#8145):
                // EGL_BAD_MATCH here means "use a pbuffer".
                failures = "surfaceless eglMakeCurrent failed: " + lastEglError() + "; ";
                destroyContextAndSurface();
            } else if (auto error = verifyGl(options)) {
                return error;
            } else {
                return std::nullopt;
            }
        }

        // Fallback: a config with a 1x1 pbuffer. All rendering still goes to our own FBOs.
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                        EGL_PBUFFER_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        if (!eglChooseConfig(display, configAttribs, &config, 1, &configCount) || configCount < 1)
            return failures + "no EGL config with EGL_OPENGL_BIT and EGL_PBUFFER_BIT (" + lastEglError() +
                   ")";
        context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
        if (context == EGL_NO_CONTEXT)
            return failures +
                   "eglCreateContext(pbuffer config, GL 4.3 core) failed: " + contextCreationError();
        const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        surface = eglCreatePbufferSurface(display, config, pbufferAttribs);
        if (surface == EGL_NO_SURFACE) {
            std::string error = failures + "eglCreatePbufferSurface(1x1) failed: " + lastEglError();
            destroyContextAndSurface();
            return error;
        }
        if (!eglMakeCurrent(display, surface, surface, context)) {
            std::string error = failures + "eglMakeCurrent(pbuffer) failed: " + lastEglError();
            destroyContextAndSurface();
            return error;
        }
        return verifyGl(options);
    }

    // The context is current: check what the driver really gave us.
    std::optional<std::string> verifyGl(const HeadlessContextOptions& options) {
        try {
            glInfo = queryGlInfo();
        } catch (const Error& e) {
            destroyContextAndSurface();
            return std::string(e.what());
        }
        if (!glInfo.coreProfile) {
            std::string error = "context is not a core profile (GL_VERSION \"" + glInfo.version + "\")";
            destroyContextAndSurface();
            return error;
        }
        if (options.requireGpu && glInfo.isSoftware) {
            std::string error =
                "renderer \"" + glInfo.renderer + "\" is a software rasteriser, but a GPU was required";
            destroyContextAndSurface();
            return error;
        }
        return std::nullopt;
    }
};

HeadlessContext::HeadlessContext(const HeadlessContextOptions& options) : m_impl(std::make_unique<Impl>()) {
    std::string selectorText = options.device;
    std::string selectorOrigin = "HeadlessContextOptions::device";
    if (selectorText.empty()) {
        if (const char* env = std::getenv("GLCOLLIDE_EGL_DEVICE"); env != nullptr && *env != '\0') {
            selectorText = env;
            selectorOrigin = "environment variable GLCOLLIDE_EGL_DEVICE";
        } else {
            selectorText = "auto";
        }
    }
    DeviceSelector selector;
    try {
        selector = DeviceSelector::parse(selectorText);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + " (from " + selectorOrigin + ")");
    }

    const egl::ClientCaps caps = egl::queryClientCaps();
    if (!caps.libraryLoaded)
        throw Error(
            std::string("cannot create a headless OpenGL context: libEGL.so.1 could not be loaded. ") +
            egl::kInstallHint);
    if (!caps.platformBase)
        throw Error(
            std::string("cannot create a headless OpenGL context: EGL has no vendor implementation or "
                        "lacks EGL_EXT_platform_base (client extensions: \"") +
            caps.extensions + "\"; check __EGL_VENDOR_LIBRARY_FILENAMES / __EGL_VENDOR_LIBRARY_DIRS). " +
            egl::kInstallHint);

    // If every candidate fails, the caller's current context (a host's, or another
    // HeadlessContext) must still be current afterwards: failed attempts release it.
    eglBindAPI(EGL_OPENGL_API);
    const EGLDisplay previousDisplay = eglGetCurrentDisplay();
    const EGLContext previousContext = eglGetCurrentContext();
    const EGLSurface previousDraw = eglGetCurrentSurface(EGL_DRAW);
    const EGLSurface previousRead = eglGetCurrentSurface(EGL_READ);
    const auto restorePrevious = [&] {
        if (previousContext != EGL_NO_CONTEXT && eglGetCurrentContext() != previousContext) {
            eglBindAPI(EGL_OPENGL_API);
            eglMakeCurrent(previousDisplay, previousDraw, previousRead, previousContext);
        }
    };

    const std::vector<egl::Device> devices = egl::enumerateDevices(caps);
    std::vector<EglDeviceInfo> infos;
    for (const egl::Device& d : devices) infos.push_back(d.info);
    const std::vector<egl::Candidate> plan = egl::planCandidates(
        selector, {infos, caps.canOpenDevices(), caps.canOpenSurfaceless(), options.requireGpu});

    std::string attempts;
    for (const egl::Candidate& candidate : plan) {
        const std::string name = egl::candidateName(candidate, infos);
        EGLDisplay display = EGL_NO_DISPLAY;
        if (candidate.kind == egl::Candidate::Kind::Device)
            display = eglGetPlatformDisplayEXT(
                EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(candidate.deviceIndex)].handle,
                nullptr);
        else
            display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display == EGL_NO_DISPLAY) {
            // A normal answer from a vendor that cannot serve this platform: try the next one.
            attempts += "\n  " + name + ": no EGL display (" + lastEglError() + ")";
            continue;
        }
        const Acquired acquired = acquireDisplay(display);
        if (!acquired.error.empty()) {
            attempts += "\n  " + name + ": " + acquired.error;
            continue;
        }
        m_impl->display = display;
        m_impl->ownsDisplay = acquired.owned;
        if (auto error = m_impl->createContext(options)) {
            attempts += "\n  " + name + ": " + *error;
            m_impl->destroy();
            continue;
        }
        if (selector.kind == DeviceSelector::Kind::Software && !m_impl->glInfo.isSoftware) {
            // Mesa surfaceless picks a hardware driver when one exists.
            attempts += "\n  " + name + ": renderer \"" + m_impl->glInfo.renderer +
                        "\" is not software (set LIBGL_ALWAYS_SOFTWARE=1 to force llvmpipe)";
            m_impl->destroy();
            continue;
        }
        const char* vendor = eglQueryString(display, EGL_VENDOR);
        const char* version = eglQueryString(display, EGL_VERSION);
        m_impl->eglVendor = vendor ? vendor : "";
        m_impl->eglVersion = version ? version : "";
        m_impl->description = name;
        return;
    }
    restorePrevious();
    throw Error("cannot create an OpenGL 4.3 core context for EGL device selector \"" + selector.toString() +
                "\"; tried:" + attempts + "\n" + egl::describeDevices(infos) + ". " + egl::kInstallHint);
}

HeadlessContext::~HeadlessContext() = default;
HeadlessContext::HeadlessContext(HeadlessContext&&) noexcept = default;
HeadlessContext& HeadlessContext::operator=(HeadlessContext&&) noexcept = default;

void HeadlessContext::makeCurrent() {
    if (!m_impl) throw Error("HeadlessContext::makeCurrent on a moved-from context");
    eglBindAPI(EGL_OPENGL_API);
    if (!eglMakeCurrent(m_impl->display, m_impl->surface, m_impl->surface, m_impl->context))
        throw Error("eglMakeCurrent failed for " + m_impl->description + ": " + lastEglError());
}

const GlInfo& HeadlessContext::glInfo() const {
    return m_impl->glInfo;
}
const std::string& HeadlessContext::eglVendor() const {
    return m_impl->eglVendor;
}
const std::string& HeadlessContext::eglVersion() const {
    return m_impl->eglVersion;
}
const std::string& HeadlessContext::deviceDescription() const {
    return m_impl->description;
}
bool HeadlessContext::surfaceless() const {
    return m_impl->surface == EGL_NO_SURFACE;
}

std::vector<EglDeviceInfo> HeadlessContext::listDevices() {
    std::vector<EglDeviceInfo> infos;
    for (const egl::Device& d : egl::enumerateDevices(egl::queryClientCaps())) infos.push_back(d.info);
    return infos;
}

} // namespace glcollide
