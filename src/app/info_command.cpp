#include "app/commands.hpp"
#include "app/self_check_report.hpp"

#include "engine/robust_self_check.hpp"
#include "gl/program_cache.hpp"

#include <glcollide/gl_info.hpp>
#include <glcollide/headless_context.hpp>

#include <nlohmann/json.hpp>

#include <iostream>

namespace glcollide::app {

int infoCommand(const InfoOptions& options) {
    const std::vector<EglDeviceInfo> devices = HeadlessContext::listDevices();
    HeadlessContext context({options.device});
    const GlInfo& gl = context.glInfo();
    const ComputeLimits& l = gl.limits;
    nlohmann::json j = {
        {"egl_devices", nlohmann::json::array()},
        {"chosen_device", context.deviceDescription()},
        {"egl_vendor", context.eglVendor()},
        {"egl_version", context.eglVersion()},
        {"gl_vendor", gl.vendor},
        {"gl_renderer", gl.renderer},
        {"gl_version", gl.version},
        {"glsl_version", gl.glslVersion},
        {"software_renderer", gl.isSoftware},
        {"compute_limits",
         {{"max_work_group_count", {l.maxWorkGroupCount[0], l.maxWorkGroupCount[1], l.maxWorkGroupCount[2]}},
          {"max_work_group_size", {l.maxWorkGroupSize[0], l.maxWorkGroupSize[1], l.maxWorkGroupSize[2]}},
          {"max_work_group_invocations", l.maxWorkGroupInvocations},
          {"max_shared_memory_bytes", l.maxSharedMemoryBytes},
          {"max_shader_storage_block_bytes", l.maxShaderStorageBlockBytes},
          {"max_shader_storage_buffer_bindings", l.maxShaderStorageBufferBindings},
          {"max_compute_shader_storage_blocks", l.maxComputeShaderStorageBlocks},
          {"shader_storage_buffer_offset_alignment", l.shaderStorageBufferOffsetAlignment},
          {"timestamp_bits", l.timestampBits}}}};
    for (const EglDeviceInfo& d : devices) j["egl_devices"].push_back(d.description());
    // The program binary cache (docs/cli.md, docs/integration.md): where it is, and whether this
    // driver can fill it (no binary format: every program is compiled, every time).
    const gl::CacheLocation cache = gl::cacheLocationFromEnvironment();
    const std::size_t binaryFormats = gl::programBinaryFormats().size();
    j["program_cache"] = {
        {"folder", cache.enabled ? nlohmann::json(cache.folder.string()) : nlohmann::json(nullptr)},
        {"off_reason", cache.enabled ? nlohmann::json(nullptr) : nlohmann::json(cache.reason)},
        {"binary_formats", binaryFormats}};
    // The robust self-check on this device: run now, or the remembered pass. info reports a
    // failure rather than failing (it is what a user runs to find out).
    const SelfCheckMode mode = engine::effectiveSelfCheckMode(SelfCheckMode::Error);
    SelfCheckReport selfCheck =
        engine::runRobustSelfCheck(mode == SelfCheckMode::Error ? SelfCheckMode::Warn : mode);
    selfCheck.mode = mode; // report the mode in force, not the one info ran it in
    j["robust_self_check"] = selfCheckJson(selfCheck);
    if (options.json) {
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    std::cout << "EGL devices:\n";
    for (const EglDeviceInfo& d : devices) std::cout << "  " << d.description() << "\n";
    if (devices.empty()) std::cout << "  (no device enumeration)\n";
    std::cout << "chosen: " << context.deviceDescription() << "\n"
              << "EGL: " << context.eglVersion() << " (" << context.eglVendor() << ")\n"
              << "GL vendor: " << gl.vendor << "\nGL renderer: " << gl.renderer
              << "\nGL version: " << gl.version << "\nGLSL version: " << gl.glslVersion << "\n"
              << "compute limits:\n";
    for (const auto& [key, value] : j["compute_limits"].items())
        std::cout << "  " << key << ": " << value.dump() << "\n";
    std::cout << "program cache: ";
    if (cache.enabled)
        std::cout << cache.folder.string() << " (the driver offers " << binaryFormats
                  << " program binary format" << (binaryFormats == 1 ? "" : "s")
                  << (binaryFormats == 0 ? ": nothing is cached" : "") << ")\n";
    else
        std::cout << "off (" << cache.reason << ")\n";
    std::cout << "robust self-check: " << selfCheckLine(selfCheck) << "\n";
    return 0;
}

} // namespace glcollide::app
