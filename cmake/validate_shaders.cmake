# Runs glslangValidator on every expanded shader variant tools/shader_embed.cpp wrote to DIR
# (cmake -DVALIDATOR=... -DDIR=... -P validate_shaders.cmake); the first invalid one fails the build.
file(GLOB _variants ${DIR}/*.comp)
list(LENGTH _variants _count)
if(_count EQUAL 0)
  message(FATAL_ERROR "validate_shaders: no shader variants in ${DIR}")
endif()
foreach(_v ${_variants})
  execute_process(COMMAND ${VALIDATOR} -S comp ${_v} RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "glslangValidator rejected ${_v}:\n${_out}${_err}")
  endif()
endforeach()
message(STATUS "glslangValidator: ${_count} shader variants valid")
