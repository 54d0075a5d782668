# Warnings, portable optimisation and the sanitizer build, applied to every Shard target via
# the interface library shard_flags.

# The instruction set the whole build may assume (-march=SHARD_ARCH). x86-64-v2 (SSE4.2, POPCNT;
# every x86-64 processor since about 2009) on x86-64, the compiler's own default elsewhere; `native`
# for this machine only; empty for the compiler's default everywhere, as a distribution package
# wants. AVX2 and AVX-512 code paths are chosen at run time whatever this says.
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  set(shard_default_arch "x86-64-v2")
else()
  set(shard_default_arch "")
endif()
set(SHARD_ARCH "${shard_default_arch}" CACHE STRING
    "-march for optimised builds: x86-64-v2 (x86-64 default), x86-64, native, ..., or empty for the compiler default")
if(SHARD_ARCH STREQUAL "")
  set(shard_arch_flag "")
else()
  set(shard_arch_flag "-march=${SHARD_ARCH}")
  include(CheckCXXCompilerFlag)
  check_cxx_compiler_flag("${shard_arch_flag}" SHARD_ARCH_SUPPORTED_${SHARD_ARCH})
  if(NOT SHARD_ARCH_SUPPORTED_${SHARD_ARCH})
    message(FATAL_ERROR "SHARD_ARCH=${SHARD_ARCH}: ${CMAKE_CXX_COMPILER_ID} refuses ${shard_arch_flag} on "
                        "${CMAKE_SYSTEM_PROCESSOR}; use one of its -march values (x86-64, x86-64-v2, x86-64-v3, "
                        "native, armv8-a, ...) or -DSHARD_ARCH= for the compiler's default")
  endif()
endif()

add_library(shard_flags INTERFACE)
target_compile_options(shard_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion
  $<$<CONFIG:Release,RelWithDebInfo>:-O3 ${shard_arch_flag} -fno-math-errno>)
if(SHARD_WERROR)
  target_compile_options(shard_flags INTERFACE -Werror)
endif()
if(SHARD_SANITIZE)
  target_compile_options(shard_flags INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                               -fno-sanitize-recover=all)
  target_link_options(shard_flags INTERFACE -fsanitize=address,undefined)
endif()
find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_CXX_COMPILER_LAUNCHER "${CCACHE_PROGRAM}")
endif()
