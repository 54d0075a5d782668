# `shard check SCENE` validates a scene without running it: a good scene reports its plugins and
# the time step `shard run` takes (the same line), writes nothing; a bad one exits non-zero with
# the loader's file:line:column error naming the key, a missing file or an unknown plugin.
# Run: cmake -DSHARD=<shard> -DSOURCE_DIR=<source> -DWORK_DIR=<scratch> -P check_scene.cmake
set(required_vars SHARD SOURCE_DIR WORK_DIR)
include(${CMAKE_CURRENT_LIST_DIR}/command_line.cmake)

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/cwd")
set(scene "${SOURCE_DIR}/scenes/four_point_bending.toml")
set(short --set simulation.duration=0.003)

# A good scene: valid, its plugins named, the time step reported, nothing written.
execute_process(COMMAND "${SHARD}" check "${scene}" ${short} WORKING_DIRECTORY "${WORK_DIR}/cwd"
                RESULT_VARIABLE rc OUTPUT_VARIABLE checked ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "shard check of ${scene} failed (${rc}):\n${checked}\n${err}")
endif()
expect_match("check" "${checked}" "bond beam_bond [^\n]*shard_beam_bond\\.so")
expect_match("check" "${checked}" "generator stl_fill")
expect_match("check" "${checked}" "1 bodies, [1-9][0-9]* particles, [1-9][0-9]* bonds; 4 walls")
file(GLOB written "${WORK_DIR}/cwd/*")
if(written)
  message(FATAL_ERROR "shard check wrote files: ${written}")
endif()
# The same time-step lines as the run of the same scene.
run("${SHARD}" run "${scene}" ${short} --out "${WORK_DIR}/run" --threads 1)
string(REGEX MATCHALL "time step [^\n]*" run_lines "${run_log}")
string(REGEX MATCHALL "time step [^\n]*" check_lines "${checked}")
if(NOT run_lines OR NOT run_lines STREQUAL check_lines)
  message(FATAL_ERROR "time step: shard run says\n${run_lines}\nshard check says\n${check_lines}")
endif()
message(STATUS "check reports what the run takes: ${check_lines}")

# A misspelt key: the error names the file, the key's line and the closest valid key.
file(READ "${scene}" text)
string(REPLACE "youngs_modulus" "youngs_modulos" text "${text}")
file(WRITE "${WORK_DIR}/misspelt.toml" "${text}")
file(STRINGS "${WORK_DIR}/misspelt.toml" lines)
set(line_number 0)
foreach(line IN LISTS lines)
  math(EXPR line_number "${line_number} + 1")
  if(line MATCHES "^youngs_modulos")
    break()
  endif()
endforeach()
run_failing("${SHARD}" check "${WORK_DIR}/misspelt.toml")
expect_match("misspelt key" "${run_log}" "misspelt\\.toml:${line_number}:[0-9]+: [^\n]*'youngs_modulos'[^\n]*youngs_modulus")

# A geometry file that is not there: named in the error.
file(COPY "${SOURCE_DIR}/scenes/four_point_bending.toml" DESTINATION "${WORK_DIR}/no_geometry")
run_failing("${SHARD}" check "${WORK_DIR}/no_geometry/four_point_bending.toml")
expect_match("missing geometry" "${run_log}" "beam_180x30x35\\.stl")

# An unknown plugin: the loader's suggestion.
run_failing("${SHARD}" check "${scene}" --set bond.plugin=beam_bnd)
expect_match("unknown plugin" "${run_log}" "unknown bond plugin 'beam_bnd' \\(did you mean 'beam_bond'\\?\\)")
file(REMOVE_RECURSE "${WORK_DIR}")
