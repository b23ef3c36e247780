# Embeds the shader stages of shaders/ into C++ (cmake -P, run at build time):
#   cmake -DSHADER_DIR=<shaders> -DTEMPLATE=<splat_shaders.cpp.in> -DOUTPUT_CPP=<file.cpp>
#         -DEXPANDED_DIR=<dir> -P embed_shaders.cmake
# A stage is a file <name>.vert.glsl or <name>.frag.glsl; it becomes the function
# <name>Vertex() or <name>Fragment() of splat_shaders.h. A line starting `#include "<file>.glsl"`
# in a stage is replaced by that file (which includes nothing itself), between #line directives:
# source string 0 is the stage, 1, 2, ... its includes in order, so a compiler's "S:L" names
# line L of the file that source string S stands for (ShaderSource::sourceStrings lists them).
# The expanded stages are also written to EXPANDED_DIR/<name>.vert|frag for glslangValidator.
cmake_minimum_required(VERSION 3.16)

foreach(var SHADER_DIR TEMPLATE OUTPUT_CPP EXPANDED_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "embed_shaders.cmake: ${var} is not set")
  endif()
endforeach()

# Number of newline characters in `text`.
function(count_lines text out)
  string(REGEX MATCHALL "\n" newlines "${text}")
  list(LENGTH newlines n)
  set(${out} ${n} PARENT_SCOPE)
endfunction()

file(GLOB stages RELATIVE "${SHADER_DIR}" "${SHADER_DIR}/*.vert.glsl" "${SHADER_DIR}/*.frag.glsl")
list(SORT stages)
file(MAKE_DIRECTORY "${EXPANDED_DIR}")
set(SHADER_DEFINITIONS "")
foreach(stage ${stages})
  string(REGEX MATCH "^([A-Za-z0-9_]+)\\.(vert|frag)\\.glsl$" ok "${stage}")
  if(NOT ok)
    message(FATAL_ERROR "${SHADER_DIR}/${stage}: a stage is named <identifier>.vert.glsl or <identifier>.frag.glsl")
  endif()
  set(name ${CMAKE_MATCH_1})
  set(kind ${CMAKE_MATCH_2})
  if(kind STREQUAL "vert")
    set(function "${name}Vertex")
  else()
    set(function "${name}Fragment")
  endif()

  file(READ "${SHADER_DIR}/${stage}" rest)
  set(expanded "")
  set(sourceStrings "0: ${stage}")
  set(stringNumber 0)
  set(line 1) # line of the stage file at which `rest` starts
  while(TRUE)
    # A directive starts a line: with a newline put in front, "\n#include" found at `at` means
    # the directive starts at `at` in `rest`.
    string(FIND "\n${rest}" "\n#include \"" at)
    if(at EQUAL -1)
      break()
    endif()
    string(SUBSTRING "${rest}" 0 ${at} before)
    string(SUBSTRING "${rest}" ${at} -1 rest)
    string(FIND "${rest}" "\n" end)
    if(end EQUAL -1)
      string(LENGTH "${rest}" end)
    endif()
    string(SUBSTRING "${rest}" 0 ${end} directive)
    math(EXPR afterDirective "${end} + 1")
    string(SUBSTRING "${rest}" ${afterDirective} -1 rest)
    count_lines("${before}" beforeLines)
    math(EXPR line "${line} + ${beforeLines}")
    if(NOT directive MATCHES "^#include \"([A-Za-z0-9_]+\\.glsl)\"[ \t]*$")
      message(FATAL_ERROR "${SHADER_DIR}/${stage}:${line}: expected #include \"<file>.glsl\" at the start of a line")
    endif()
    set(included ${CMAKE_MATCH_1})
    file(READ "${SHADER_DIR}/${included}" content)
    if(content MATCHES "#include")
      message(FATAL_ERROR "${SHADER_DIR}/${included}: an included file includes nothing itself")
    endif()
    if(NOT content MATCHES "\n$")
      string(APPEND content "\n")
    endif()
    math(EXPR stringNumber "${stringNumber} + 1")
    math(EXPR line "${line} + 1")
    string(APPEND expanded "${before}#line 1 ${stringNumber}\n${content}#line ${line} 0\n")
    string(APPEND sourceStrings ", ${stringNumber}: ${included}")
  endwhile()
  string(APPEND expanded "${rest}")

  if(expanded MATCHES "\\)glsl\"")
    message(FATAL_ERROR "${SHADER_DIR}/${stage}: contains )glsl\", the end of the raw string it is embedded in")
  endif()
  file(WRITE "${EXPANDED_DIR}/${name}.${kind}.tmp" "${expanded}")
  configure_file("${EXPANDED_DIR}/${name}.${kind}.tmp" "${EXPANDED_DIR}/${name}.${kind}" COPYONLY)
  file(REMOVE "${EXPANDED_DIR}/${name}.${kind}.tmp")
  string(APPEND SHADER_DEFINITIONS
         "ShaderSource ${function}()\n{\n    return {R\"glsl(${expanded})glsl\",\n            \"${sourceStrings}\"};\n}\n\n")
endforeach()

configure_file("${TEMPLATE}" "${OUTPUT_CPP}" @ONLY)
