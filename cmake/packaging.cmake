# A Debian package of what the build installs (the plugins into the host's plugin folder,
# gsresample into bin, the .mlx scripts and the sample bunny into share/meshlab-gaussphere),
# for the MeshLab it was built against:
#   cpack -G DEB   (in the build folder; scripts/package.sh builds every target's package)
# The package depends on the exact version of the distribution's `meshlab` package found at
# configure time (plugins are built against one MeshLab's headers and ABI), and on the shared
# libraries its files link (dpkg-shlibdeps; libmeshlab-common.so belongs to meshlab). Its file
# name carries the distribution's codename: meshlab-gaussphere_VERSION-1~CODENAME_amd64.deb.
# Include it after project(); it reads PROJECT_VERSION (and MESHLAB_HOST_VERSION when set).
set(GAUSSPHERE_MESHLAB_PACKAGE_VERSION "" CACHE STRING
    "Version of the Debian meshlab package the plugins are built for (empty: dpkg-query's answer)")
if(NOT GAUSSPHERE_MESHLAB_PACKAGE_VERSION)
  execute_process(COMMAND dpkg-query -W -f=\${Version} meshlab
                  OUTPUT_VARIABLE GAUSSPHERE_MESHLAB_PACKAGE_VERSION ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
endif()
# Built against another MeshLab than the distribution's (MeshLab 2025.07 from source beside
# trixie's 2022.02): no package, since none of the distribution's would fit.
if(DEFINED MESHLAB_HOST_VERSION AND NOT GAUSSPHERE_MESHLAB_PACKAGE_VERSION MATCHES "^${MESHLAB_HOST_VERSION}")
  message(STATUS "no .deb: the plugins are for MeshLab ${MESHLAB_HOST_VERSION}, the meshlab package is '${GAUSSPHERE_MESHLAB_PACKAGE_VERSION}'")
  return()
endif()
set(codename unknown)
if(EXISTS /etc/os-release)
  file(STRINGS /etc/os-release codename_line REGEX "^VERSION_CODENAME=")
  string(REGEX REPLACE "^VERSION_CODENAME=\"?([^\"]*)\"?$" "\\1" codename "${codename_line}")
endif()

install(DIRECTORY ${GAUSSPHERE_SOURCE_DIR}/sample_data/ DESTINATION share/meshlab-gaussphere/scripts
        FILES_MATCHING PATTERN "*.mlx")
install(FILES ${GAUSSPHERE_SOURCE_DIR}/sample_data/bunny.ply DESTINATION share/meshlab-gaussphere)
install(FILES ${GAUSSPHERE_SOURCE_DIR}/README.md ${GAUSSPHERE_SOURCE_DIR}/docs/surfel_format.md
        DESTINATION share/doc/meshlab-gaussphere)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME meshlab-gaussphere)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_CONTACT "Gaussian sphere resampling for MeshLab <gaussphere@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "MeshLab plugins: feature-sensitive resampling of point sets into elliptical surfels")
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "Gaussian sphere feature-sensitive resampling (filter), the .surfel format (IO), the surfel\n error measure (filter) and Ellipse Splatting (render mode) for MeshLab ${GAUSSPHERE_MESHLAB_PACKAGE_VERSION},\n and gsresample, the resampler on the command line.")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_RELEASE "1~${codename}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libmeshlab-common.so has no SONAME and lives in MeshLab's private folder: meshlab provides it.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS /usr/lib/x86_64-linux-gnu/meshlab)
if(GAUSSPHERE_MESHLAB_PACKAGE_VERSION)
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "meshlab (= ${GAUSSPHERE_MESHLAB_PACKAGE_VERSION})")
else()
  message(WARNING "no meshlab package installed: the .deb will not name the MeshLab it needs")
endif()
include(CPack)
