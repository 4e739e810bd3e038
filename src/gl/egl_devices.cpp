#include "gl/egl_devices.hpp"

#include "glcollide/error.hpp"

#include <epoxy/egl.h>

#include <algorithm>
#include <charconv>
#include <sstream>

// In libegl-dev 1.6's eglext.h but not in epoxy 1.5.10's generated header (platform.md §1.1).
#ifndef EGL_DRM_RENDER_NODE_FILE_EXT
#define EGL_DRM_RENDER_NODE_FILE_EXT 0x3377
#endif

namespace glcollide {

namespace {

constexpr const char* kAcceptedForms =
    "accepted: \"auto\", \"software\", a device index such as \"0\", or \"cuda:<n>\" such as \"cuda:0\"";

bool hasWord(std::string_view list, std::string_view word) {
    std::size_t pos = 0;
    while ((pos = list.find(word, pos)) != std::string_view::npos) {
        const bool startOk = pos == 0 || list[pos - 1] == ' ';
        const std::size_t end = pos + word.size();
        const bool endOk = end == list.size() || list[end] == ' ';
        if (startOk && endOk) return true;
        pos = end;
    }
    return false;
}

// Strict decimal: digits only, no sign or spaces, must fit an int.
bool parseNonNegative(std::string_view text, int& out) {
    if (text.empty() || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return false;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), out);
    return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

} // namespace

DeviceSelector DeviceSelector::parse(std::string_view text) {
    if (text == "auto") return {Kind::Auto, -1};
    if (text == "software") return {Kind::Software, -1};
    int number = -1;
    if (parseNonNegative(text, number)) return {Kind::Index, number};
    constexpr std::string_view kCuda = "cuda:";
    if (text.substr(0, kCuda.size()) == kCuda && parseNonNegative(text.substr(kCuda.size()), number))
        return {Kind::Cuda, number};
    throw Error("invalid EGL device selector \"" + std::string(text) + "\"; " + kAcceptedForms);
}

std::string DeviceSelector::toString() const {
    switch (kind) {
    case Kind::Auto:
        return "auto";
    case Kind::Software:
        return "software";
    case Kind::Index:
        return std::to_string(number);
    case Kind::Cuda:
        return "cuda:" + std::to_string(number);
    }
    return "auto";
}

std::string EglDeviceInfo::description() const {
    std::vector<std::string> parts;
    for (const char* ext : {"EGL_MESA_device_software", "EGL_NV_device_cuda", "EGL_EXT_device_drm"})
        if (hasWord(extensions, ext)) parts.emplace_back(ext);
    if (!queryable) parts.emplace_back("not queryable");
    if (software) parts.emplace_back("software");
    if (!drmRenderNode.empty())
        parts.push_back(drmRenderNode);
    else if (!drmDeviceFile.empty())
        parts.push_back(drmDeviceFile);
    if (cudaDevice >= 0) parts.push_back("cuda:" + std::to_string(cudaDevice));
    std::string text = "EGL device " + std::to_string(index);
    if (!parts.empty()) {
        text += " (";
        for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? ", " : "") + parts[i];
        text += ")";
    }
    return text;
}

namespace egl {

ClientCaps queryClientCaps() {
    ClientCaps caps;
    // Without libEGL every epoxy EGL call would abort; epoxy_has_egl() only tries to dlopen it.
    if (!epoxy_has_egl()) return caps;
    caps.libraryLoaded = true;
    // NULL when EGL_EXT_client_extensions is missing (EGL_BAD_DISPLAY): then nothing below exists.
    const char* ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (ext == nullptr) {
        eglGetError(); // clear the error so it does not surface in a later check
        return caps;
    }
    caps.extensions = ext;
    caps.platformBase = hasWord(caps.extensions, "EGL_EXT_platform_base");
    caps.platformDevice = hasWord(caps.extensions, "EGL_EXT_platform_device");
    // NVIDIA exposes only the older EGL_EXT_device_base, which bundles enumeration and query.
    const bool deviceBase = hasWord(caps.extensions, "EGL_EXT_device_base");
    caps.deviceEnumeration = deviceBase || hasWord(caps.extensions, "EGL_EXT_device_enumeration");
    caps.deviceQuery = deviceBase || hasWord(caps.extensions, "EGL_EXT_device_query");
    caps.surfacelessMesa = hasWord(caps.extensions, "EGL_MESA_platform_surfaceless");
    // Cross-check with epoxy's own view: it is what decides whether a call aborts.
    caps.platformBase = caps.platformBase && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base");
    caps.deviceEnumeration =
        caps.deviceEnumeration && (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base") ||
                                   epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration"));
    caps.deviceQuery = caps.deviceQuery && (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base") ||
                                            epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_query"));
    return caps;
}

std::vector<Device> enumerateDevices(const ClientCaps& caps) {
    std::vector<Device> result;
    if (!caps.libraryLoaded || !caps.deviceEnumeration) return result;
    EGLint count = 0;
    if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) {
        // NVIDIA's vendor without an NVIDIA GPU reports EGL_BAD_ALLOC here (platform.md §1.6).
        eglGetError();
        return result;
    }
    std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(count));
    if (!eglQueryDevicesEXT(count, handles.data(), &count)) {
        eglGetError();
        return result;
    }
    handles.resize(static_cast<std::size_t>(std::max(count, 0)));
    for (std::size_t i = 0; i < handles.size(); ++i) {
        Device device;
        device.handle = handles[i];
        device.info.index = static_cast<int>(i);
        if (caps.deviceQuery) {
            // Query the string first: on some NVIDIA drivers eglQueryDeviceAttribEXT crashed for
            // devices the cgroup cannot access, while the string query fails cleanly
            // (Magnum's nv-egl-crashy-query-device-attrib workaround).
            const char* ext = eglQueryDeviceStringEXT(handles[i], EGL_EXTENSIONS);
            if (ext == nullptr) {
                eglGetError();
                device.info.queryable = false;
            } else {
                device.info.extensions = ext;
                device.info.software = hasWord(device.info.extensions, "EGL_MESA_device_software");
                if (hasWord(device.info.extensions, "EGL_EXT_device_drm")) {
                    if (const char* file = eglQueryDeviceStringEXT(handles[i], EGL_DRM_DEVICE_FILE_EXT))
                        device.info.drmDeviceFile = file;
                    else
                        eglGetError();
                }
                if (hasWord(device.info.extensions, "EGL_EXT_device_drm_render_node")) {
                    if (const char* node = eglQueryDeviceStringEXT(handles[i], EGL_DRM_RENDER_NODE_FILE_EXT))
                        device.info.drmRenderNode = node;
                    else
                        eglGetError();
                }
                if (hasWord(device.info.extensions, "EGL_NV_device_cuda")) {
                    EGLAttrib cuda = -1;
                    if (eglQueryDeviceAttribEXT(handles[i], EGL_CUDA_DEVICE_NV, &cuda))
                        device.info.cudaDevice = static_cast<int>(cuda);
                    else
                        eglGetError();
                }
            }
        } else {
            device.info.queryable = false;
        }
        result.push_back(std::move(device));
    }
    return result;
}

std::string describeDevices(std::span<const EglDeviceInfo> devices) {
    if (devices.empty()) return "no EGL devices found";
    std::string text = "devices found: ";
    for (std::size_t i = 0; i < devices.size(); ++i) text += (i ? "; " : "") + devices[i].description();
    return text;
}

std::string candidateName(const Candidate& candidate, std::span<const EglDeviceInfo> devices) {
    if (candidate.kind == Candidate::Kind::Surfaceless) return "Mesa surfaceless platform";
    for (const EglDeviceInfo& d : devices)
        if (d.index == candidate.deviceIndex) return d.description();
    return "EGL device " + std::to_string(candidate.deviceIndex);
}

std::vector<Candidate> planCandidates(const DeviceSelector& selector, const PlanInputs& in) {
    using Kind = DeviceSelector::Kind;
    std::vector<Candidate> plan;
    const auto addDevice = [&](const EglDeviceInfo& d) {
        plan.push_back({Candidate::Kind::Device, d.index});
    };
    const auto explicitNeedsDevices = [&](const std::string& what) {
        if (!in.canOpenDevices)
            throw Error("EGL device " + what +
                        " requested, but EGL cannot open devices (needs the client "
                        "extensions EGL_EXT_platform_base, EGL_EXT_platform_device and "
                        "EGL_EXT_device_enumeration or EGL_EXT_device_base); " +
                        describeDevices(in.devices));
    };

    switch (selector.kind) {
    case Kind::Auto:
        if (in.canOpenDevices)
            for (const EglDeviceInfo& d : in.devices)
                if (d.queryable && !d.software) addDevice(d);
        if (in.canOpenSurfaceless) plan.push_back({Candidate::Kind::Surfaceless, -1});
        if (in.canOpenDevices && !in.requireGpu)
            for (const EglDeviceInfo& d : in.devices)
                if (d.queryable && d.software) addDevice(d);
        if (plan.empty())
            throw Error(std::string("no usable EGL device or platform: ") + describeDevices(in.devices) +
                        (in.requireGpu ? " (a GPU was required)" : "") +
                        ", and Mesa's surfaceless platform "
                        "(EGL_MESA_platform_surfaceless) is " +
                        (in.canOpenSurfaceless ? "available" : "missing"));
        break;
    case Kind::Software:
        if (in.requireGpu) throw Error("EGL device \"software\" requested together with requireGpu");
        if (in.canOpenDevices)
            for (const EglDeviceInfo& d : in.devices)
                if (d.software) addDevice(d);
        // Without a software device (no enumeration, or a non-Mesa vendor), Mesa's surfaceless
        // platform is the next best thing; the renderer is checked after creation.
        if (plan.empty() && in.canOpenSurfaceless) plan.push_back({Candidate::Kind::Surfaceless, -1});
        if (plan.empty())
            throw Error("EGL device \"software\" requested, but there is no EGL_MESA_device_software device "
                        "and no Mesa surfaceless platform; " +
                        describeDevices(in.devices));
        break;
    case Kind::Index: {
        explicitNeedsDevices(selector.toString());
        const auto it = std::find_if(in.devices.begin(), in.devices.end(),
                                     [&](const EglDeviceInfo& d) { return d.index == selector.number; });
        if (it == in.devices.end())
            throw Error("EGL device " + selector.toString() + " requested, but it does not exist; " +
                        describeDevices(in.devices));
        addDevice(*it);
        break;
    }
    case Kind::Cuda: {
        explicitNeedsDevices(selector.toString());
        const auto it = std::find_if(in.devices.begin(), in.devices.end(),
                                     [&](const EglDeviceInfo& d) { return d.cudaDevice == selector.number; });
        if (it == in.devices.end())
            throw Error("EGL device " + selector.toString() +
                        " requested, but no device reports that "
                        "EGL_CUDA_DEVICE_NV ordinal (ordinals follow CUDA_VISIBLE_DEVICES); " +
                        describeDevices(in.devices));
        addDevice(*it);
        break;
    }
    }
    return plan;
}

} // namespace egl
} // namespace glcollide
