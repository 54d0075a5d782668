# Shared by the installed-API scripts: run(), and a fresh install of the build into ${prefix}.
foreach(var SHARD_BUILD_DIR SHARD_SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "-D${var}= is required")
  endif()
endforeach()

# Runs a command, failing the test with its output; run_output / run_log: its stdout / stderr
# (a run's report, peak load and time steps, goes to stderr).
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
  set(run_log "${err}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} --install "${SHARD_BUILD_DIR}" --prefix "${prefix}")
set(shard "${prefix}/bin/shard")
# What a plugin author compiles with: every warning an error.
set(strict_flags "-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror")
