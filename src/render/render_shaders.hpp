#pragma once
// The renderer's vertex and fragment shaders (shaders/render/), embedded at build time by
// cmake/embed_graphics_shaders.cmake.

#include <string_view>

namespace glcollide::render {

/// Source of shaders/render/<file> (e.g. "surface.frag"); nullptr when there is no such shader.
const char* embeddedShaderSource(std::string_view file);

} // namespace glcollide::render
