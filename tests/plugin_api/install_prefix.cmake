# Shared by the installed-API scripts: run(), and a fresh install of the build into ${prefix}.
set(required_vars SHARD_BUILD_DIR SHARD_SOURCE_DIR WORK_DIR)
include(${CMAKE_CURRENT_LIST_DIR}/../install/command_line.cmake)  # run(), expect_match()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} --install "${SHARD_BUILD_DIR}" --prefix "${prefix}")
set(shard "${prefix}/bin/shard")
# What a plugin author compiles with: every warning an error.
set(strict_flags "-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror")
