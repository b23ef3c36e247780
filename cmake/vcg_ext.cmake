# vcg_ext: the algorithms of vcg_ext/ (header-only, templated on vcg mesh types, no Qt, no
# MeshLab) as an INTERFACE target, against the vcglib and Eigen of the MeshLab being built for:
#   gaussphere_add_vcg_ext(VCGLIB_DIR EIGEN_INCLUDE_DIR)
# and the two Qt-free libraries beside it that programs outside MeshLab need:
#   gaussphere_add_file_libraries(VCGLIB_DIR)   vcg_plylib (vcglib's PLY reader/writer) and
#                                               surfel_file (the .surfel format, io_surfel/surfel_file.*)
# Used by the top-level build (2020.09) and by cmake/host_plugins (2022.02, 2025.07).
find_package(OpenMP REQUIRED COMPONENTS CXX)
# Header-only kd-tree (Debian: libnanoflann-dev): point_grid.h's fallback for isolated points.
find_package(nanoflann REQUIRED)
get_filename_component(GAUSSPHERE_SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

function(gaussphere_add_vcg_ext vcglib_dir eigen_include_dir)
  add_library(vcg_ext INTERFACE)
  target_include_directories(vcg_ext INTERFACE ${GAUSSPHERE_SOURCE_DIR})
  target_include_directories(vcg_ext SYSTEM INTERFACE ${vcglib_dir} ${eigen_include_dir})
  target_link_libraries(vcg_ext INTERFACE OpenMP::OpenMP_CXX nanoflann::nanoflann)
endfunction()

function(gaussphere_add_file_libraries vcglib_dir)
  add_library(vcg_plylib STATIC ${vcglib_dir}/wrap/ply/plylib.cpp)
  target_include_directories(vcg_plylib SYSTEM PUBLIC ${vcglib_dir})
  add_library(surfel_file STATIC ${GAUSSPHERE_SOURCE_DIR}/io_surfel/surfel_file.cpp
              ${GAUSSPHERE_SOURCE_DIR}/io_surfel/file_replacement.cpp)
  target_include_directories(surfel_file PUBLIC ${GAUSSPHERE_SOURCE_DIR}/io_surfel)
endfunction()
