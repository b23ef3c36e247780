# Plants an undeclared identifier at a known line of an included shader file and of a stage,
# embeds the shaders as the build does (embed_shaders.cmake) and checks that glslangValidator
# names those lines with the right source string numbers (opaque.frag.glsl: 0 the stage, 3
# lighting.glsl).
foreach(var GLSLANG_VALIDATOR SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "glsl_line_numbers.cmake: ${var} is not set")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")
file(COPY "${SOURCE_DIR}/shaders/" DESTINATION "${WORK_DIR}/shaders")

# Replaces the first `from` in file with `to`; returns the line it was on.
function(plant file from to lineOut)
  file(READ "${file}" text)
  string(FIND "${text}" "${from}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${file}: no '${from}' to plant an error in")
  endif()
  string(SUBSTRING "${text}" 0 ${at} before)
  string(REGEX MATCHALL "\n" newlines "${before}")
  list(LENGTH newlines n)
  math(EXPR line "${n} + 1")
  string(REPLACE "${from}" "${to}" text "${text}")
  file(WRITE "${file}" "${text}")
  set(${lineOut} ${line} PARENT_SCOPE)
endfunction()

function(check_error planted expected)
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -DSHADER_DIR=${WORK_DIR}/shaders -DTEMPLATE=${SOURCE_DIR}/splat_shaders.cpp.in
            -DOUTPUT_CPP=${WORK_DIR}/splat_shaders.cpp -DEXPANDED_DIR=${WORK_DIR}/expanded
            -P "${SOURCE_DIR}/embed_shaders.cmake"
    RESULT_VARIABLE embedded)
  if(NOT embedded EQUAL 0)
    message(FATAL_ERROR "embed_shaders.cmake failed")
  endif()
  execute_process(COMMAND "${GLSLANG_VALIDATOR}" -S frag "${WORK_DIR}/expanded/opaque.frag"
                  RESULT_VARIABLE validated OUTPUT_VARIABLE log ERROR_VARIABLE log)
  if(validated EQUAL 0)
    message(FATAL_ERROR "the planted ${planted} was not reported")
  endif()
  if(NOT log MATCHES "ERROR: ${expected}: '${planted}'")
    message(FATAL_ERROR "expected an error at ${expected} for ${planted}, got:\n${log}")
  endif()
  message(STATUS "${planted} reported at ${expected}")
endfunction()

plant("${WORK_DIR}/shaders/lighting.glsl" "float diffuse = max(" "float diffuse = plantedInInclude + max(" line)
check_error(plantedInInclude "3:${line}")
file(COPY "${SOURCE_DIR}/shaders/lighting.glsl" DESTINATION "${WORK_DIR}/shaders")
plant("${WORK_DIR}/shaders/opaque.frag.glsl" "gl_FragDepth = depth;" "gl_FragDepth = plantedInStage;" line)
check_error(plantedInStage "0:${line}")
