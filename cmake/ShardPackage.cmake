# `cpack -G DEB` in a build folder: a Debian package of what `cmake --install` installs (the
# `shard` command, its libraries and plugins, the plugin API, templates and example scenes), its
# library dependencies worked out by dpkg-shlibdeps (needs dpkg-dev and file: .ci/install-deps
# package). Installs with `apt-get install ./shard_<version>_<arch>.deb`; docs/how-to/install.md.
set(CPACK_PACKAGE_NAME shard)
set(CPACK_PACKAGE_VENDOR "Shard developers")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
  "Shard predicts if, where and how brittle, complex-shaped bodies break with the Discrete Element "
  "Method and a bonded particle model: spheres joined by elastic beams that break. Every model is a "
  "plugin loaded at run time.")
set(CPACK_RESOURCE_FILE_LICENSE "${PROJECT_SOURCE_DIR}/LICENSE")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # shard_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "Shard developers <dev@shard.invalid>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libshard_kernel and its siblings ship in the package itself: dpkg-shlibdeps finds them here.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS "${CMAKE_BINARY_DIR}/kernel;${CMAKE_BINARY_DIR}/analysis;${CMAKE_BINARY_DIR}/analysis/bending")
# Plots (bending, fragments, history) are drawn by gnuplot; a plugin author builds against the
# installed API with a compiler, CMake and Eigen.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "paraview, cmake, g++, libeigen3-dev")
include(CPack)
