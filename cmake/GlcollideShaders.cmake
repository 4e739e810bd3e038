# Embeds every shaders/passes/*.comp and shaders/bench/*.comp (with its #includes expanded and
# #line markers) into a generated C++ file compiled into `target`, and validates every variant of
# every shader (each combination of its declared features, tools/shader_embed.cpp) with
# glslangValidator when it is installed, so a GLSL error fails the build before any GPU.

find_program(GLSLANG_VALIDATOR glslangValidator)

function(glcollide_embed_shaders target shader_root)
  if(NOT TARGET glcollide_shader_embed)
    add_executable(glcollide_shader_embed ${PROJECT_SOURCE_DIR}/tools/shader_embed.cpp)
  endif()
  file(GLOB_RECURSE _all CONFIGURE_DEPENDS ${shader_root}/*.glsl ${shader_root}/*.comp)
  file(GLOB _passes CONFIGURE_DEPENDS RELATIVE ${shader_root} ${shader_root}/passes/*.comp ${shader_root}/bench/*.comp)
  list(SORT _passes)
  set(_out_cpp ${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp)
  set(_out_dir ${CMAKE_CURRENT_BINARY_DIR}/expanded_shaders)
  set(_commands COMMAND glcollide_shader_embed ${_out_cpp} ${_out_dir} ${shader_root} ${_passes})
  if(GLCOLLIDE_VALIDATE_GLSL AND GLSLANG_VALIDATOR)
    list(APPEND _commands COMMAND ${CMAKE_COMMAND} -DVALIDATOR=${GLSLANG_VALIDATOR} -DDIR=${_out_dir}
         -P ${PROJECT_SOURCE_DIR}/cmake/validate_shaders.cmake)
  elseif(GLCOLLIDE_VALIDATE_GLSL)
    message(STATUS "glslangValidator not found: shaders are checked only by the GL tests")
  endif()
  add_custom_command(OUTPUT ${_out_cpp} ${_commands}
    DEPENDS glcollide_shader_embed ${_all}
    COMMENT "Embedding and validating shaders" VERBATIM)
  target_sources(${target} PRIVATE ${_out_cpp})
endfunction()
