# All dependencies come from Debian 12 packages (see .ci/install-deps).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
# Every JSON document is written and read through libshard_io (io/include/shard/io/json.hpp).
find_package(nlohmann_json 3.10 REQUIRED)
# HDF5 is named explicitly, whatever Debian's hdf5.pc alternative points at (installing
# libhdf5-openmpi-dev switches it): the serial build takes the serial library through h5cc, the
# MPI build the OpenMPI one through h5pcc.openmpi.
if(SHARD_WITH_MPI)
  find_package(MPI REQUIRED COMPONENTS C CXX)
  set(HDF5_PREFER_PARALLEL TRUE)
  if(EXISTS /usr/bin/h5pcc.openmpi)
    set(HDF5_C_COMPILER_EXECUTABLE /usr/bin/h5pcc.openmpi CACHE FILEPATH "HDF5 compiler wrapper (parallel, OpenMPI)")
  endif()
elseif(EXISTS /usr/bin/h5cc)
  set(HDF5_C_COMPILER_EXECUTABLE /usr/bin/h5cc CACHE FILEPATH "HDF5 compiler wrapper (serial)")
endif()
find_package(HDF5 REQUIRED COMPONENTS C)
if(SHARD_WITH_MPI AND NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR "SHARD_WITH_MPI needs parallel HDF5 (libhdf5-openmpi-dev); found ${HDF5_C_LIBRARIES}")
elseif(SHARD_WITH_MPI)
  set_property(TARGET hdf5::hdf5 APPEND PROPERTY INTERFACE_LINK_LIBRARIES MPI::MPI_C)  # its hdf5.h includes mpi.h
elseif(NOT SHARD_WITH_MPI AND HDF5_IS_PARALLEL)
  message(FATAL_ERROR "the serial build found parallel HDF5 (${HDF5_C_LIBRARIES}): set HDF5_C_COMPILER_EXECUTABLE=/usr/bin/h5cc")
endif()
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
