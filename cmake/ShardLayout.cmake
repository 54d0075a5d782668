# Where a build and an install put Shard's files, and how the running code finds them again
# (kernel/include/shard/install_layout.hpp). Every install destination is a GNUInstallDirs path
# relative to the prefix, so an installed tree can be moved as a whole: the programs find the
# libraries through a relative RPATH, the library finds the plugins and the data relative to itself.
include(GNUInstallDirs)
foreach(pair BINDIR:bin LIBDIR:lib DATADIR:share INCLUDEDIR:include)
  string(REPLACE ":" ";" pair "${pair}")
  list(GET pair 0 dir)
  list(GET pair 1 example)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    message(FATAL_ERROR "CMAKE_INSTALL_${dir}=${CMAKE_INSTALL_${dir}} is absolute: give it relative to "
                        "CMAKE_INSTALL_PREFIX (e.g. -DCMAKE_INSTALL_${dir}=${example}), so that the installed "
                        "Shard finds its plugins wherever the prefix is moved")
  endif()
endforeach()

# Every plugin module lands in one folder of the build tree, which the build tree's host searches.
set(SHARD_BUILD_PLUGIN_DIR "${CMAKE_BINARY_DIR}/plugins")
set(SHARD_INSTALL_PLUGIN_DIR "${CMAKE_INSTALL_LIBDIR}/shard/plugins")
set(SHARD_INSTALL_DATA_DIR "${CMAKE_INSTALL_DATADIR}/shard")    # templates/ and scenes/
set(SHARD_INSTALL_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/Shard")

# Installed programs and libraries find libshard_kernel and each other in <prefix>/<libdir>.
file(RELATIVE_PATH shard_bin_to_lib "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${CMAKE_INSTALL_LIBDIR}")
file(RELATIVE_PATH shard_lib_to_prefix "/prefix/${CMAKE_INSTALL_LIBDIR}" "/prefix")
set(CMAKE_INSTALL_RPATH "$ORIGIN/${shard_bin_to_lib};$ORIGIN")

# For install_layout.cpp alone (and the fuzzer that compiles it): SHARD_BUILD_IMAGE_DIR, where the
# binary holding that code is built, is added by each user.
set(SHARD_LAYOUT_DEFINITIONS
  "SHARD_BUILD_PLUGIN_DIR=\"${SHARD_BUILD_PLUGIN_DIR}\""
  "SHARD_SOURCE_DIR=\"${PROJECT_SOURCE_DIR}\""
  "SHARD_LIBDIR_TO_PREFIX=\"${shard_lib_to_prefix}\""
  "SHARD_PLUGIN_SUBDIR=\"${SHARD_INSTALL_PLUGIN_DIR}\""
  "SHARD_DATA_SUBDIR=\"${SHARD_INSTALL_DATA_DIR}\"")
