#pragma once
/// \file What a benchmark result must name so it can be trusted and compared: the renderer and
/// driver, the EGL device, the CPU, the commit measured and the date.

#include <string>
#include <string_view>

namespace glcollide {
class HeadlessContext;
}

namespace glcollide::benchkit {

struct RunContext {
    std::string renderer, rendererSlug, glVersion, glVendor;
    bool softwareRenderer = false;
    std::string eglDevice, eglVendor, eglVersion;
    std::string cpuModel;
    std::string gitCommit; ///< HEAD of the source tree at run time ("-dirty" if modified)
    std::string buildType;
    std::string dateUtc; ///< ISO 8601
};

RunContext describeRun(const HeadlessContext& context);

/// "llvmpipe (LLVM 15.0.6, 256 bits)" -> "llvmpipe"; "NVIDIA H100 80GB HBM3/PCIe/SSE2" ->
/// "nvidia-h100": names result files (bench/results/<slug>...).
std::string rendererSlug(std::string_view renderer);

} // namespace glcollide::benchkit
