#pragma once
/// \file A GL 4.3 core context without a window or display server, created through EGL
/// (a GPU through the EGL device platform, or Mesa's llvmpipe).

#include "glcollide/gl_info.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace glcollide {

/// One EGL device as enumerated by EGL_EXT_device_enumeration / EGL_EXT_device_base.
struct EglDeviceInfo {
    int index = -1;            ///< position in eglQueryDevicesEXT's list (what "<index>" selects)
    std::string extensions;    ///< device extension string (empty when it could not be queried)
    bool software = false;     ///< advertises EGL_MESA_device_software
    std::string drmDeviceFile; ///< EGL_DRM_DEVICE_FILE_EXT, e.g. "/dev/dri/card0"; empty if none
    std::string drmRenderNode; ///< EGL_DRM_RENDER_NODE_FILE_EXT, e.g. "/dev/dri/renderD128"; empty if none
    int cudaDevice = -1;       ///< EGL_CUDA_DEVICE_NV ordinal; -1 when not an NVIDIA CUDA device
    bool queryable = true;     ///< false when eglQueryDeviceStringEXT failed (device is skipped by "auto")

    /// One line for logs, e.g. "EGL device 0 (EGL_MESA_device_software, software)".
    std::string description() const;
};

/// Which device to use: "auto" | "software" | "<index>" | "cuda:<n>".
struct DeviceSelector {
    enum class Kind { Auto, Software, Index, Cuda };
    Kind kind = Kind::Auto;
    int number = -1; ///< device index (Kind::Index) or CUDA ordinal (Kind::Cuda); -1 otherwise

    /// Parses the text form. Throws glcollide::Error naming the text and the accepted forms when
    /// it is not one of them (indices and ordinals are decimal, >= 0, without sign).
    static DeviceSelector parse(std::string_view text);
    /// The text form, parse(toString()) == *this.
    std::string toString() const;

    friend bool operator==(const DeviceSelector&, const DeviceSelector&) = default;
};

struct HeadlessContextOptions {
    std::string device;        ///< empty: the env variable GLCOLLIDE_EGL_DEVICE if set, else "auto"
    bool debug = false;        ///< request a debug context (EGL_CONTEXT_OPENGL_DEBUG)
    bool requireGpu = false;   ///< fail if the chosen renderer is a software rasteriser
    bool forcePbuffer = false; ///< skip the surfaceless path and use a 1x1 pbuffer (tests the fallback)
};

/// An EGL display + GL 4.3 core context owned by this object. Move-only.
/// Construction makes the context current on the calling thread.
class HeadlessContext {
  public:
    /// Chooses a device (see DeviceSelector; "auto" tries GPU devices in enumeration order, then
    /// Mesa's surfaceless platform, then the software device), creates a 4.3 core context and makes
    /// it current. Throws glcollide::Error saying what was tried and why each attempt failed.
    explicit HeadlessContext(const HeadlessContextOptions& options = {});
    /// Releases the context if current on this thread, destroys it, terminates the display only if
    /// this object initialised it and no other HeadlessContext uses it, and releases EGL thread
    /// state when no context remains current on this thread.
    ~HeadlessContext();
    HeadlessContext(HeadlessContext&&) noexcept;
    HeadlessContext& operator=(HeadlessContext&&) noexcept;
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

    /// Makes this context current on the calling thread. Throws glcollide::Error on failure.
    void makeCurrent();

    /// Strings and limits read right after creation.
    const GlInfo& glInfo() const;
    /// EGL_VENDOR of the display, e.g. "Mesa Project".
    const std::string& eglVendor() const;
    /// EGL_VERSION of the display, e.g. "1.5".
    const std::string& eglVersion() const;
    /// What was chosen, e.g. "EGL device 0 (EGL_MESA_device_software, software)" or
    /// "Mesa surfaceless platform".
    const std::string& deviceDescription() const;
    /// True when current without a surface (EGL_KHR_surfaceless_context); false with a 1x1 pbuffer.
    bool surfaceless() const;

    /// The EGL devices visible to this process; empty (not a crash) when EGL or its device
    /// extensions are missing.
    static std::vector<EglDeviceInfo> listDevices();

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace glcollide
