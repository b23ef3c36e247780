# The splatting GL code, free of MeshLab and Qt: the static library ellipse_splat_renderer,
# shared by the render plugin of every host, the offscreen tool (tools/splat_render) and the
# rendering tests. Included by render_ellipsesplat/CMakeLists.txt (MeshLab 2020.09's build) and
# render_ellipsesplat/meshlab2021/CMakeLists.txt (cmake/host_plugins); needs the targets
# vcg_ext, GLEW::GLEW, OpenGL::GL and Eigen3::Eigen.
#
# The shader stages (shaders/*.vert.glsl, *.frag.glsl) become C++ at build time, and their
# expanded text goes to ${SPLAT_EXPANDED_SHADER_DIR} for the glslangValidator tests.
set(splat_dir ${CMAKE_CURRENT_LIST_DIR})
file(GLOB SPLAT_SHADER_FILES CONFIGURE_DEPENDS ${splat_dir}/shaders/*.glsl)
set(SPLAT_EXPANDED_SHADER_DIR ${CMAKE_CURRENT_BINARY_DIR}/shaders CACHE INTERNAL "expanded shader stages")
set(generated_shaders ${CMAKE_CURRENT_BINARY_DIR}/splat_shaders.cpp)
add_custom_command(
  OUTPUT ${generated_shaders}
  COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${splat_dir}/shaders
          -DTEMPLATE=${splat_dir}/splat_shaders.cpp.in -DOUTPUT_CPP=${generated_shaders}
          -DEXPANDED_DIR=${SPLAT_EXPANDED_SHADER_DIR} -P ${splat_dir}/embed_shaders.cmake
  DEPENDS ${SPLAT_SHADER_FILES} ${splat_dir}/splat_shaders.cpp.in ${splat_dir}/embed_shaders.cmake
  COMMENT "Embedding the splat shaders"
  VERBATIM)

add_library(ellipse_splat_renderer STATIC
  ${splat_dir}/ellipse_splat_renderer.cpp ${splat_dir}/gl_program.cpp ${splat_dir}/splat_frames.cpp
  ${generated_shaders})
target_include_directories(ellipse_splat_renderer PUBLIC ${splat_dir})
target_link_libraries(ellipse_splat_renderer PUBLIC GLEW::GLEW OpenGL::GL PRIVATE vcg_ext Eigen3::Eigen)
# Qt-free: no autogen target (it would also run the shader embedding a second time, in parallel).
set_target_properties(ellipse_splat_renderer PROPERTIES POSITION_INDEPENDENT_CODE ON AUTOMOC OFF AUTOUIC OFF AUTORCC OFF)
