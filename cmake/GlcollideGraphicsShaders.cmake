# Embeds the renderer's vertex and fragment shaders (shaders/render/*.vert, *.frag) into a generated
# C++ file compiled into `target`, and validates each one with glslangValidator (stage from the file
# extension) when it is installed. These shaders are self-contained (no #include), so unlike the
# compute passes (GlcollideShaders.cmake, tools/shader_embed.cpp) they need no expansion.
#
# The generated file defines `const char* glcollide::render::embeddedShaderSource(std::string_view
# stem)` (nullptr for an unknown stem), declared in src/render/render_shaders.hpp.

find_program(GLSLANG_VALIDATOR glslangValidator)

function(glcollide_embed_graphics_shaders target shader_dir)
  file(GLOB _shaders CONFIGURE_DEPENDS ${shader_dir}/*.vert ${shader_dir}/*.frag)
  list(SORT _shaders)
  set(_out_cpp ${CMAKE_CURRENT_BINARY_DIR}/${target}_graphics_shaders.cpp)
  # '|' rather than ';' between files: a list separator would be split by the build tool's shell.
  string(REPLACE ";" "|" _joined "${_shaders}")
  set(_commands COMMAND ${CMAKE_COMMAND} -DOUT=${_out_cpp} -DSHADERS=${_joined}
                        -P ${PROJECT_SOURCE_DIR}/cmake/embed_graphics_shaders.cmake)
  if(GLCOLLIDE_VALIDATE_GLSL AND GLSLANG_VALIDATOR)
    foreach(_s ${_shaders})
      list(APPEND _commands COMMAND ${GLSLANG_VALIDATOR} ${_s})
    endforeach()
  endif()
  add_custom_command(OUTPUT ${_out_cpp} ${_commands}
    DEPENDS ${_shaders} ${PROJECT_SOURCE_DIR}/cmake/embed_graphics_shaders.cmake
    COMMENT "Embedding and validating the graphics shaders of ${target}" VERBATIM)
  target_sources(${target} PRIVATE ${_out_cpp})
endfunction()
