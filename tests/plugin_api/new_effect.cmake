# `shard new-plugin --effect` as a user runs it (docs/how-to/write-a-plugin.md, "A bond effect"):
#   1. the installed shard writes the effect, its registration, a scaffold test and a CMakeLists.txt;
#   2. they build against the installed prefix only (warnings as errors) and the scaffold test passes;
#   3. the installed shard lists the effect and beam_bond's [bond] table gains its parameter, with
#      its neutral value;
#   4. composed onto beam_bond in the tiny bending scene it is exact at its neutral value (named in
#      `effects`, the peak load is beam_bond's to every printed digit) and lowers the peak load when on.
# Run: cmake -DSHARD_BUILD_DIR=<build> -DSHARD_SOURCE_DIR=<source> -DWORK_DIR=<scratch> -P new_effect.cmake
include("${CMAKE_CURRENT_LIST_DIR}/install_prefix.cmake")

set(name oot_damage)
set(src "${WORK_DIR}/${name}")
run("${shard}" new-plugin --effect ${name} --dir "${src}")
foreach(file ${name}.hpp ${name}.cpp test_${name}.cpp CMakeLists.txt)
  if(NOT EXISTS "${src}/${file}")
    message(FATAL_ERROR "new-plugin --effect did not write ${file}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S "${src}" -B "${src}/build" -G Ninja "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_FLAGS=${strict_flags}")
run(${CMAKE_COMMAND} --build "${src}/build")
get_filename_component(cmake_bin "${CMAKE_COMMAND}" DIRECTORY)
run("${cmake_bin}/ctest" --test-dir "${src}/build" --output-on-failure -V)
if(NOT run_output MATCHES "${name}: all checks passed")
  message(FATAL_ERROR "the scaffold test did not pass:\n${run_output}")
endif()
message(STATUS "${name}: generated, built against the installed API, scaffold test passed")

set(plugins "${src}/build/plugins")
run("${shard}" --plugin-dir "${plugins}" plugins)
if(NOT run_output MATCHES "bond_effect/${name} 0.1.0  \\(${plugins}/shard_${name}.so\\)")
  message(FATAL_ERROR "${name} not listed by shard plugins:\n${run_output}")
endif()
string(REGEX MATCH "\nbond/beam_bond [^\n]*\n(    [^\n]*\n|  [^\n]*\n)*" beam "${run_output}")
if(NOT beam MATCHES "${name}_damage_per_strain [^\n]*neutral 0")
  message(FATAL_ERROR "beam_bond's schema does not list ${name}_damage_per_strain with its neutral value:\n${beam}")
endif()

set(tiny "${SHARD_SOURCE_DIR}/scenes/measurements/tiny_bending.toml")
function(peak_load out label)
  run("${shard}" --plugin-dir "${plugins}" run "${tiny}" --out "${WORK_DIR}/${label}" --threads 1 ${ARGN})
  string(REGEX MATCH "peak load [^\n]*" line "${run_log}")
  if(line STREQUAL "")
    message(FATAL_ERROR "${label}: no peak load reported:\n${run_log}")
  endif()
  set(${out} "${line}" PARENT_SCOPE)
endfunction()
peak_load(plain plain)
peak_load(neutral neutral --set bond.effects=${name})
if(NOT neutral STREQUAL plain)
  message(FATAL_ERROR "${name} at its neutral value is not beam_bond: '${plain}' vs '${neutral}'")
endif()
peak_load(damaged damaged --set bond.${name}_damage_per_strain=100)
string(REGEX MATCH "peak load ([0-9.e+-]+)" _ "${plain}")
set(intact "${CMAKE_MATCH_1}")
string(REGEX MATCH "peak load ([0-9.e+-]+)" _ "${damaged}")
set(weakened "${CMAKE_MATCH_1}")
if(NOT weakened LESS intact)
  message(FATAL_ERROR "${name}_damage_per_strain = 100 did not lower the peak load: ${weakened} N against ${intact} N")
endif()
message(STATUS "${name} on beam_bond: neutral = beam_bond (${plain}); damage_per_strain 100: ${weakened} N")
file(REMOVE_RECURSE "${WORK_DIR}")
