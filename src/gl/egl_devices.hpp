#pragma once
// EGL device enumeration and the (pure) device-selection plan behind HeadlessContext.
// Kept free of EGL/epoxy headers so the plan can be unit-tested without a GL stack.

#include "glcollide/headless_context.hpp"

#include <span>
#include <string>
#include <vector>

namespace glcollide::egl {

/// Client (display-independent) EGL capabilities. Every extension function is gated on these,
/// because libepoxy aborts the process when a function has no provider (platform.md §1.6).
struct ClientCaps {
    bool libraryLoaded = false;     // libEGL could be loaded at all
    std::string extensions;         // eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS)
    bool platformBase = false;      // EGL_EXT_platform_base
    bool platformDevice = false;    // EGL_EXT_platform_device
    bool deviceEnumeration = false; // EGL_EXT_device_enumeration or EGL_EXT_device_base
    bool deviceQuery = false;       // EGL_EXT_device_query or EGL_EXT_device_base
    bool surfacelessMesa = false;   // EGL_MESA_platform_surfaceless

    bool canOpenDevices() const { return platformBase && platformDevice && deviceEnumeration; }
    bool canOpenSurfaceless() const { return platformBase && surfacelessMesa; }
};

/// Reads the client extensions; libraryLoaded is false (and the rest empty) without libEGL.
ClientCaps queryClientCaps();

/// An enumerated device and its opaque EGLDeviceEXT handle.
struct Device {
    EglDeviceInfo info;
    void* handle = nullptr;
};

/// Enumerates devices (empty when the client extensions are missing or enumeration fails).
std::vector<Device> enumerateDevices(const ClientCaps& caps);

/// One thing to try when creating a context.
struct Candidate {
    enum class Kind { Device, Surfaceless };
    Kind kind = Kind::Surfaceless;
    int deviceIndex = -1; // index into the device list for Kind::Device
    friend bool operator==(const Candidate&, const Candidate&) = default;
};

/// What is available to the planner.
struct PlanInputs {
    std::span<const EglDeviceInfo> devices;
    bool canOpenDevices = false;     // ClientCaps::canOpenDevices()
    bool canOpenSurfaceless = false; // ClientCaps::canOpenSurfaceless()
    bool requireGpu = false;
};

/// The ordered list of candidates for `selector` (platform.md §1.8): for auto, non-software devices
/// in enumeration order, then Mesa surfaceless, then software devices (dropped with requireGpu).
/// Explicit selectors never fall back: an index or CUDA ordinal that is absent throws Error listing
/// the devices found. Throws Error when nothing at all can be tried.
std::vector<Candidate> planCandidates(const DeviceSelector& selector, const PlanInputs& inputs);

/// Human-readable name of a candidate, for logs and errors.
std::string candidateName(const Candidate& candidate, std::span<const EglDeviceInfo> devices);

/// "devices found: EGL device 0 (...); EGL device 1 (...)" or "no EGL devices found".
std::string describeDevices(std::span<const EglDeviceInfo> devices);

/// How to get a working EGL + GL 4.3 stack; appended to "no EGL" errors.
inline constexpr const char* kInstallHint =
    "On Debian/Ubuntu: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri (Mesa >= 20 llvmpipe "
    "gives GL 4.5 in software). On NVIDIA: a driver with EGL support; in containers set "
    "NVIDIA_DRIVER_CAPABILITIES to include 'graphics', and if libglvnd finds no vendor, point "
    "__EGL_VENDOR_LIBRARY_FILENAMES at the vendor JSON (e.g. "
    "/usr/share/glvnd/egl_vendor.d/10_nvidia.json or 50_mesa.json).";

} // namespace glcollide::egl
