# Out-of-tree MeshLab plugins against an installed MeshLab 2022.02 or 2025.07 (the plugin API
# of 2021.05 and later). include() it from a CMake project, with:
#   MESHLAB_SOURCE_DIR      the host's source tree, holding ML_VERSION, src/common, src/vcglib
#                           (2022.02: trixie's source package; 2025.07: the published tarball)
#   MESHLAB_COMMON_LIBRARY  the host's libmeshlab-common.so
# It defines the imported target meshlab_host_common (what meshlab-common's PUBLIC usage
# requirements are in src/common/CMakeLists.txt: MESHLAB_VERSION and MESHLAB_SCALAR, include
# dir src/, vcglib, Qt5 Core/OpenGL/Widgets/Xml/Network, GLEW, Eigen) and
#   meshlab_host_add_plugin(TARGET SOURCES...)   a MODULE library linking it, with AUTOMOC,
#                                                installed into MESHLAB_PLUGIN_INSTALL_DIR.
# MESHLAB_VERSION is ML_VERSION's text: the plugin loader refuses a plugin whose version
# string differs from its own in the first 6 characters (src/common/plugins/plugin_manager.cpp,
# checkPlugin), and one built with the other scalar (float unless the host was built with
# MESHLAB_BUILD_WITH_DOUBLE_SCALAR).
set(MESHLAB_SOURCE_DIR "" CACHE PATH "MeshLab source tree of the host (ML_VERSION, src/common, src/vcglib)")
set(MESHLAB_COMMON_LIBRARY "" CACHE FILEPATH "the host's libmeshlab-common.so")
set(MESHLAB_SCALAR float CACHE STRING "the host's scalar type (float or double)")
option(MESHLAB_HOST_NO_UNDEFINED "link plugins with -Wl,--no-undefined (OFF for plugins using symbols of the meshlab executable, such as GLArea's)" ON)
foreach(f ML_VERSION src/common/plugins/interfaces/filter_plugin.h src/vcglib/vcg/complex/complex.h)
  if(NOT EXISTS "${MESHLAB_SOURCE_DIR}/${f}")
    message(FATAL_ERROR "MESHLAB_SOURCE_DIR: no ${f} in '${MESHLAB_SOURCE_DIR}'")
  endif()
endforeach()
if(NOT EXISTS "${MESHLAB_COMMON_LIBRARY}")
  message(FATAL_ERROR "MESHLAB_COMMON_LIBRARY: '${MESHLAB_COMMON_LIBRARY}' does not exist")
endif()
file(READ "${MESHLAB_SOURCE_DIR}/ML_VERSION" MESHLAB_HOST_VERSION)
string(STRIP "${MESHLAB_HOST_VERSION}" MESHLAB_HOST_VERSION)

set(CMAKE_CXX_STANDARD 14)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_POSITION_INDEPENDENT_CODE ON)
set(OpenGL_GL_PREFERENCE GLVND)
find_package(Qt5 5.15 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml Network)
find_package(OpenGL REQUIRED)
find_package(GLEW REQUIRED)
find_package(Eigen3 REQUIRED NO_MODULE)

add_library(meshlab_host_common SHARED IMPORTED)
set_target_properties(meshlab_host_common PROPERTIES
  IMPORTED_LOCATION "${MESHLAB_COMMON_LIBRARY}"
  IMPORTED_NO_SONAME TRUE  # built without a SONAME
  INTERFACE_COMPILE_DEFINITIONS "MESHLAB_VERSION=${MESHLAB_HOST_VERSION};MESHLAB_SCALAR=${MESHLAB_SCALAR}"
  INTERFACE_INCLUDE_DIRECTORIES "${MESHLAB_SOURCE_DIR}/src;${MESHLAB_SOURCE_DIR}/src/vcglib"
  INTERFACE_LINK_LIBRARIES "Qt5::Core;Qt5::Gui;Qt5::Widgets;Qt5::OpenGL;Qt5::Xml;Qt5::Network;GLEW::GLEW;OpenGL::GL;OpenGL::GLU;Eigen3::Eigen")
message(STATUS "MeshLab host ${MESHLAB_HOST_VERSION} (${MESHLAB_SCALAR}): ${MESHLAB_COMMON_LIBRARY}")

set(MESHLAB_PLUGIN_INSTALL_DIR "lib/x86_64-linux-gnu/meshlab/plugins" CACHE PATH
    "where cmake --install puts the plugins, under the prefix (Debian's layout; MeshLab's own: lib/meshlab/plugins)")

function(meshlab_host_add_plugin target)
  add_library(${target} MODULE ${ARGN})
  install(TARGETS ${target} LIBRARY DESTINATION "${MESHLAB_PLUGIN_INSTALL_DIR}")
  set_target_properties(${target} PROPERTIES AUTOMOC ON)
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${target} PRIVATE meshlab_host_common)
  if(MESHLAB_HOST_NO_UNDEFINED)
    # an undefined symbol shows at link time, not when MeshLab loads the plugin
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
endfunction()
