# GAUSSPHERE_SANITIZE and GAUSSPHERE_FUZZ: every target of the build compiled and linked with
# AddressSanitizer and UndefinedBehaviorSanitizer (float-to-int overflow included where the
# compiler has it), every report fatal. GAUSSPHERE_FUZZ (clang only) also instruments the code
# for libFuzzer and adds the fuzz targets of tests/fuzz.
# Debian's MeshLab is not sanitized and cannot load sanitized plugins: both need
# GAUSSPHERE_BUILD_PLUGINS=OFF.
if(NOT GAUSSPHERE_SANITIZE AND NOT GAUSSPHERE_FUZZ)
  return()
endif()
if(GAUSSPHERE_BUILD_PLUGINS)
  message(FATAL_ERROR "GAUSSPHERE_SANITIZE and GAUSSPHERE_FUZZ need -DGAUSSPHERE_BUILD_PLUGINS=OFF: "
                      "Debian's MeshLab cannot load sanitized plugins")
endif()
if(GAUSSPHERE_FUZZ AND NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "GAUSSPHERE_FUZZ needs clang (libFuzzer): -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14")
endif()

set(gaussphere_sanitizers address,undefined)
include(CheckCXXCompilerFlag)
set(CMAKE_REQUIRED_LINK_OPTIONS -fsanitize=float-cast-overflow)
check_cxx_compiler_flag(-fsanitize=float-cast-overflow GAUSSPHERE_HAVE_FLOAT_CAST_OVERFLOW)
unset(CMAKE_REQUIRED_LINK_OPTIONS)
if(GAUSSPHERE_HAVE_FLOAT_CAST_OVERFLOW)
  string(APPEND gaussphere_sanitizers ",float-cast-overflow")
endif()

add_compile_options(-fsanitize=${gaussphere_sanitizers} -fno-sanitize-recover=all -fno-omit-frame-pointer)
add_link_options(-fsanitize=${gaussphere_sanitizers} -fno-sanitize-recover=all)
if(GAUSSPHERE_FUZZ)
  # Coverage instrumentation everywhere; only the fuzz targets link libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
message(STATUS "Sanitizers: ${gaussphere_sanitizers}")
