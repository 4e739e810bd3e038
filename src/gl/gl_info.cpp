#include "glcollide/gl_info.hpp"

#include "glcollide/error.hpp"

#include "core/gpu_layout.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <cctype>

namespace glcollide {

namespace {

constexpr const char* kHowToGet43 =
    "glcollide needs desktop OpenGL 4.3 (compute shaders). Get it from Mesa >= 20 llvmpipe "
    "(Debian/Ubuntu: apt-get install libegl-mesa0 libgl1-mesa-dri) or an NVIDIA driver.";

std::string glString(GLenum name) {
    const auto* text = reinterpret_cast<const char*>(glGetString(name));
    return text ? std::string(text) : std::string();
}

bool namesSoftwareRasterizer(std::string renderer) {
    std::transform(renderer.begin(), renderer.end(), renderer.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* word : {"llvmpipe", "softpipe", "swrast"})
        if (renderer.find(word) != std::string::npos) return true;
    return false;
}

// Throws unless a desktop GL >= 4.3 context is current; returns its GL_VERSION string.
std::string checkCurrentContext() {
    // glGetString is GL 1.0 and resolves without a context; it returns NULL when none is current.
    const std::string version = glString(GL_VERSION);
    if (version.empty())
        throw Error("no OpenGL context is current on this thread (glGetString(GL_VERSION) returned "
                    "NULL); make a GL 4.3 context current first, or use glcollide::HeadlessContext");
    if (!epoxy_is_desktop_gl())
        throw Error("the current context is OpenGL ES (\"" + version + "\"), not desktop OpenGL. " +
                    kHowToGet43);
    const int packed = epoxy_gl_version();
    if (packed < 43)
        throw Error("the current context is OpenGL " + std::to_string(packed / 10) + "." +
                    std::to_string(packed % 10) + " (\"" + version + "\", renderer \"" +
                    glString(GL_RENDERER) + "\"); " + kHowToGet43);
    return version;
}

int getInt(GLenum name) {
    GLint value = 0;
    glGetIntegerv(name, &value);
    return value;
}

} // namespace

GlInfo queryGlInfo() {
    GlInfo info;
    info.version = checkCurrentContext();
    info.vendor = glString(GL_VENDOR);
    info.renderer = glString(GL_RENDERER);
    info.glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
    info.major = getInt(GL_MAJOR_VERSION);
    info.minor = getInt(GL_MINOR_VERSION);
    info.coreProfile = (getInt(GL_CONTEXT_PROFILE_MASK) & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    info.debugContext = (getInt(GL_CONTEXT_FLAGS) & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
    info.isSoftware = namesSoftwareRasterizer(info.renderer);

    ComputeLimits& l = info.limits;
    for (GLuint axis = 0; axis < 3; ++axis) {
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, axis, &l.maxWorkGroupCount[axis]);
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_SIZE, axis, &l.maxWorkGroupSize[axis]);
    }
    l.maxWorkGroupInvocations = getInt(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    l.maxSharedMemoryBytes = getInt(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
    GLint64 blockBytes = 0;
    // 64-bit query: the block size limit can exceed 2 GiB on GPUs.
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &blockBytes);
    l.maxShaderStorageBlockBytes = blockBytes;
    l.maxShaderStorageBufferBindings = getInt(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
    l.maxComputeShaderStorageBlocks = getInt(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS);
    l.shaderStorageBufferOffsetAlignment = getInt(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT);
    GLint bits = 0;
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
    l.timestampBits = bits;
    return info;
}

void requireGl43() {
    checkCurrentContext();
    // GL 4.3 promises only 8 storage bindings; the engine's buffers sit at fixed points up to
    // GLC_BINDING_COUNT-1 (layout.glsl), so a device with fewer cannot run it.
    const int bindings = getInt(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
    if (bindings < GLC_BINDING_COUNT)
        throw Error("the device offers " + std::to_string(bindings) +
                    " shader storage buffer bindings (GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, renderer \"" +
                    glString(GL_RENDERER) + "\"); glcollide binds buffers at 0 .. " +
                    std::to_string(GLC_BINDING_COUNT - 1));
}

} // namespace glcollide
