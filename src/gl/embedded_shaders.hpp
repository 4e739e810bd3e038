#pragma once
// The shaders embedded at build time by tools/shader_embed.cpp (see cmake/GlcollideShaders.cmake).

#include <cstddef>

namespace glcollide::gl::embedded {

struct EmbeddedShader {
    const char* name;         ///< stem of the .comp file, e.g. "node_force"
    const char* source;       ///< expanded source: #version first, then #line-marked text
    const char* const* files; ///< files[k] = path (relative to shaders/) of GLSL source-string k
    std::size_t fileCount;
    const char* features; ///< space-separated switches of its `// glcollide-features:` line
};

extern const EmbeddedShader kShaders[];
extern const std::size_t kShaderCount;

} // namespace glcollide::gl::embedded
