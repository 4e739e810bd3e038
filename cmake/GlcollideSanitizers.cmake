# Sanitizer and fuzzing builds (scripts/test-sanitizers.sh, scripts/fuzz.sh).
#
# GLCOLLIDE_SANITIZE: a -fsanitize= list (e.g. "address,undefined") applied to every target of
# the build, tests and CLI included, so the GL tests run instrumented on llvmpipe. Undefined
# behaviour aborts (no recovery): a UBSan report fails the test that caused it.
#
# GLCOLLIDE_BUILD_FUZZERS (clang only): instruments the readers (scene, core) for coverage and
# builds the libFuzzer targets in fuzz/.
set(GLCOLLIDE_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined (empty: none)")
option(GLCOLLIDE_BUILD_FUZZERS "Build the libFuzzer targets in fuzz/ (needs clang)" OFF)

if(GLCOLLIDE_SANITIZE)
  add_compile_options(-fsanitize=${GLCOLLIDE_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${GLCOLLIDE_SANITIZE})
endif()

if(GLCOLLIDE_BUILD_FUZZERS AND NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "GLCOLLIDE_BUILD_FUZZERS needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
endif()

# Coverage instrumentation for the code the fuzzers exercise; call after the module exists.
function(glcollide_fuzz_instrument target)
  if(GLCOLLIDE_BUILD_FUZZERS)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()
