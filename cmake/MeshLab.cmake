# Locates MeshLab 2020.09: headers from Debian's source package (unpacked by
# scripts/setup.sh into .deps/meshlab-src) and the installed libmeshlab-common.so.
# Provides: MESHLAB_VCGLIB_DIR, EIGEN3_INCLUDE_DIR, the imported target meshlab::common,
# meshlab_add_plugin(name SOURCES ...) and meshlab_add_stage_target().

set(MESHLAB_SOURCE_DIR "${CMAKE_SOURCE_DIR}/.deps/meshlab-src" CACHE PATH
    "MeshLab 2020.09 source tree (apt-get source meshlab; scripts/setup.sh does it)")
set(MESHLAB_LIB_DIR "/usr/lib/x86_64-linux-gnu/meshlab" CACHE PATH
    "Folder holding the installed libmeshlab-common.so")
set(MESHLAB_BIN_DIR "/usr/bin" CACHE PATH "Folder holding meshlab and meshlabserver")
set(MESHLAB_PLUGIN_INSTALL_DIR "lib/x86_64-linux-gnu/meshlab/plugins" CACHE PATH
    "Where cmake --install puts the plugins, under the prefix (/usr: Debian's MeshLab loads them there)")

if(NOT EXISTS "${MESHLAB_SOURCE_DIR}/vcglib/vcg/complex/complex.h")
  message(FATAL_ERROR "MeshLab source tree not found in ${MESHLAB_SOURCE_DIR}: run scripts/setup.sh")
endif()
set(MESHLAB_VCGLIB_DIR "${MESHLAB_SOURCE_DIR}/vcglib")

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
get_target_property(EIGEN3_INCLUDE_DIR Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
add_compile_definitions(MESHLAB_SCALAR=float)

if(GAUSSPHERE_BUILD_PLUGINS)
  set(CMAKE_AUTOMOC ON)
  set(CMAKE_AUTOUIC ON)
  set(CMAKE_AUTORCC ON)
  find_package(Qt5 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml XmlPatterns)
  find_package(OpenGL REQUIRED)
  find_package(GLEW REQUIRED)
  if(NOT EXISTS "${MESHLAB_LIB_DIR}/libmeshlab-common.so")
    message(FATAL_ERROR "libmeshlab-common.so not found in ${MESHLAB_LIB_DIR}: apt-get install meshlab (scripts/setup.sh)")
  endif()
  add_library(meshlab::common SHARED IMPORTED)
  set_target_properties(meshlab::common PROPERTIES
    IMPORTED_LOCATION "${MESHLAB_LIB_DIR}/libmeshlab-common.so"
    IMPORTED_NO_SONAME TRUE)
  target_include_directories(meshlab::common INTERFACE
    "${MESHLAB_SOURCE_DIR}/src" "${MESHLAB_SOURCE_DIR}/src/common" "${MESHLAB_VCGLIB_DIR}")
  target_link_libraries(meshlab::common INTERFACE
    Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml Qt5::XmlPatterns
    GLEW::GLEW OpenGL::GL Eigen3::Eigen)
endif()

set(MESHLAB_STAGE_DIR "${CMAKE_BINARY_DIR}/stage")
set(MESHLAB_STAGE_PLUGIN_DIR "${MESHLAB_STAGE_DIR}/lib/x86_64-linux-gnu/meshlab/plugins")
set_property(GLOBAL PROPERTY GAUSSPHERE_PLUGINS "")

# A MeshLab plugin: a MODULE library built into the staged prefix and installed
# beside Debian's plugins.
function(meshlab_add_plugin name)
  cmake_parse_arguments(P "" "" "SOURCES;LIBS" ${ARGN})
  add_library(${name} MODULE ${P_SOURCES})
  target_link_libraries(${name} PRIVATE meshlab::common vcg_ext ${P_LIBS})
  set_target_properties(${name} PROPERTIES
    LIBRARY_OUTPUT_DIRECTORY "${MESHLAB_STAGE_PLUGIN_DIR}")
  install(TARGETS ${name} LIBRARY DESTINATION "${MESHLAB_PLUGIN_INSTALL_DIR}")
  set_property(GLOBAL APPEND PROPERTY GAUSSPHERE_PLUGINS ${name})
endfunction()

# `stage`: a prefix whose bin/meshlab and bin/meshlabserver load Debian's plugins plus
# ours without touching /usr (the executables are copied: Debian's build resolves the
# plugin folder from the executable's real path).
function(meshlab_add_stage_target)
  get_property(plugins GLOBAL PROPERTY GAUSSPHERE_PLUGINS)
  add_custom_target(stage ALL
    COMMAND ${CMAKE_COMMAND} -DSTAGE=${MESHLAB_STAGE_DIR} -DLIB=${MESHLAB_LIB_DIR}
            -DBIN=${MESHLAB_BIN_DIR} -P ${CMAKE_SOURCE_DIR}/cmake/stage.cmake
    DEPENDS ${plugins}
    COMMENT "Staging MeshLab with the project's plugins in ${MESHLAB_STAGE_DIR}")
endfunction()
