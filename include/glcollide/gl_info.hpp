#pragma once
/// \file GL strings and compute limits of the current context (headless or a host's).

#include <cstdint>
#include <string>

namespace glcollide {

/// Compute-related limits, read from the driver at run time (never assumed).
struct ComputeLimits {
    int maxWorkGroupCount[3] = {0, 0, 0};        ///< GL_MAX_COMPUTE_WORK_GROUP_COUNT per axis
    int maxWorkGroupSize[3] = {0, 0, 0};         ///< GL_MAX_COMPUTE_WORK_GROUP_SIZE per axis
    int maxWorkGroupInvocations = 0;             ///< GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS
    int maxSharedMemoryBytes = 0;                ///< GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, bytes
    std::int64_t maxShaderStorageBlockBytes = 0; ///< GL_MAX_SHADER_STORAGE_BLOCK_SIZE, bytes per binding
    int maxShaderStorageBufferBindings = 0;      ///< GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS
    int maxComputeShaderStorageBlocks = 0;       ///< GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS
    int shaderStorageBufferOffsetAlignment = 0;  ///< GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, bytes
    int timestampBits = 0;                       ///< GL_QUERY_COUNTER_BITS of GL_TIMESTAMP (0: no timer)
};

/// What the current context is, as reported by the driver.
struct GlInfo {
    std::string vendor;        ///< GL_VENDOR
    std::string renderer;      ///< GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version;       ///< GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"
    std::string glslVersion;   ///< GL_SHADING_LANGUAGE_VERSION
    int major = 0;             ///< GL_MAJOR_VERSION
    int minor = 0;             ///< GL_MINOR_VERSION
    bool coreProfile = false;  ///< GL_CONTEXT_CORE_PROFILE_BIT set in GL_CONTEXT_PROFILE_MASK
    bool debugContext = false; ///< GL_CONTEXT_FLAG_DEBUG_BIT set in GL_CONTEXT_FLAGS
    bool isSoftware = false;   ///< GL_RENDERER names a software rasteriser (llvmpipe, softpipe, swrast)
    ComputeLimits limits;
};

/// Reads GL strings and limits from the context current on this thread.
/// Throws glcollide::Error if no context is current, if it is not desktop GL, or if its version is
/// below 4.3 (the message says which version was found and how to get 4.3).
GlInfo queryGlInfo();

/// Host mode: checks that a desktop GL >= 4.3 context is current on this thread and that GL calls
/// can be made through glcollide's loader. Throws glcollide::Error otherwise.
void requireGl43();

} // namespace glcollide
