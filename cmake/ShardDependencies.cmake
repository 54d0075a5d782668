# All dependencies come from Debian 12 packages (see .ci/install-deps).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
find_package(HDF5 REQUIRED COMPONENTS C)
find_package(Boost 1.74 REQUIRED COMPONENTS graph)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(NLopt REQUIRED)
# SIMD lanes of the laws (header-only). Debian 12's xsimd target also names xtl, an optional
# library the package does not depend on (-lxtl fails to link): only its headers are taken.
find_package(xsimd REQUIRED)
if(NOT TARGET shard_xsimd)
  add_library(shard_xsimd INTERFACE)
  add_library(shard::xsimd ALIAS shard_xsimd)
  get_target_property(SHARD_XSIMD_INCLUDE xsimd INTERFACE_INCLUDE_DIRECTORIES)
  target_include_directories(shard_xsimd SYSTEM INTERFACE ${SHARD_XSIMD_INCLUDE})
endif()
if(SHARD_BUILD_TESTS)
  find_package(doctest REQUIRED)
endif()
# OpenVDB's find module ships in the multiarch library folder on Debian.
foreach(dir IN ITEMS /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/aarch64-linux-gnu/cmake/OpenVDB
                     /usr/lib/cmake/OpenVDB /usr/local/lib/cmake/OpenVDB)
  if(EXISTS "${dir}/FindOpenVDB.cmake")
    list(APPEND CMAKE_MODULE_PATH "${dir}")
  endif()
endforeach()
