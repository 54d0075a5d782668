# Warnings, portable optimisation and the sanitizer build, applied to every Shard target via
# the interface library shard_flags.
add_library(shard_flags INTERFACE)
target_compile_options(shard_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion
  $<$<CONFIG:Release,RelWithDebInfo>:-O3 -march=x86-64-v2 -fno-math-errno>)
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
