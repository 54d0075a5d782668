# Out-of-tree plugin workflow, as a user runs it (docs/how-to/write-a-plugin.md):
#   1. cmake --install the Shard build into a fresh prefix;
#   2. the installed `shard new-plugin KIND NAME` writes a template, for each kind;
#   3. each template is configured (find_package(Shard)) and built against the prefix only,
#      with warnings as errors;
#   4. the installed `shard --plugin-dir <build>/plugins plugins` loads and lists it, and the
#      installed plugin folder holds the shipped plugins.
# Run: cmake -DSHARD_BUILD_DIR=<build> -DWORK_DIR=<scratch> -P out_of_tree_plugin.cmake
set(required_vars SHARD_BUILD_DIR SHARD_SOURCE_DIR WORK_DIR)
include(${CMAKE_CURRENT_LIST_DIR}/../install/command_line.cmake)  # run(), expect_match()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} --install "${SHARD_BUILD_DIR}" --prefix "${prefix}")

set(shard "${prefix}/bin/shard")
foreach(path bin/shard lib/libshard_kernel.so include/shard/plugin.hpp lib/cmake/Shard/ShardConfig.cmake
             lib/cmake/Shard/ShardTargets.cmake lib/cmake/Shard/ShardPlugin.cmake
             lib/shard/plugins/shard_beam_bond.so lib/shard/plugins/shard_hertz_mindlin.so
             share/shard/templates/contact.cpp.in)
  if(NOT EXISTS "${prefix}/${path}")
    message(FATAL_ERROR "install is missing ${path}")
  endif()
endforeach()

# The installed command runs from the prefix (its RPATH finds libshard_kernel there) and lists
# the installed plugins when pointed at them.
run("${shard}" --plugin-dir "${prefix}/lib/shard/plugins" plugins)
if(NOT run_output MATCHES "bond/beam_bond [^\n]*\\(${prefix}/lib/shard/plugins/shard_beam_bond.so\\)")
  message(FATAL_ERROR "installed beam_bond not listed from the prefix:\n${run_output}")
endif()

set(strict_flags "-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror")
foreach(kind contact bond generator)
  set(name "oot_${kind}")
  set(src "${WORK_DIR}/${name}")
  run("${shard}" new-plugin ${kind} ${name} --dir "${src}")
  # Only the prefix is given: the package must bring the headers, Eigen and shard_add_plugin().
  run(${CMAKE_COMMAND} -S "${src}" -B "${src}/build" -G Ninja "-DCMAKE_PREFIX_PATH=${prefix}"
      "-DCMAKE_CXX_FLAGS=${strict_flags}")
  run(${CMAKE_COMMAND} --build "${src}/build")
  if(NOT EXISTS "${src}/build/plugins/shard_${name}.so")
    message(FATAL_ERROR "${name}: no plugins/shard_${name}.so after the build")
  endif()
  run("${shard}" --plugin-dir "${src}/build/plugins" plugins)
  if(NOT run_output MATCHES "${kind}/${name} 0.1.0  \\(${src}/build/plugins/shard_${name}.so\\)")
    message(FATAL_ERROR "${name} not listed by shard plugins:\n${run_output}")
  endif()
  message(STATUS "${kind}/${name}: generated, built out of tree, loaded")
endforeach()
# Each template declares an effect with its neutral value; the listing shows it.
run("${shard}" --plugin-dir "${WORK_DIR}/oot_contact/build/plugins" plugins)
if(NOT run_output MATCHES "adhesion_force [^\n]*neutral 0")
  message(FATAL_ERROR "the contact template's neutral value is not listed:\n${run_output}")
endif()
# The tutorial's effect (docs/tutorials/measurement-loop.md part 6) extends the seed's beam through the installed
# header-only beam helpers; at its neutral value it must run the tiny beam exactly as beam_bond.
set(tutorial "${WORK_DIR}/crushing_bond")
run(${CMAKE_COMMAND} -S "${SHARD_SOURCE_DIR}/docs/tutorials/crushing_bond" -B "${tutorial}" -G Ninja
    "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_FLAGS=${strict_flags}")
run(${CMAKE_COMMAND} --build "${tutorial}")
set(tiny "${SHARD_SOURCE_DIR}/scenes/measurements/tiny_bending.toml")
run("${shard}" --plugin-dir "${tutorial}/plugins" run "${tiny}" --out "${WORK_DIR}/tiny_beam" --threads 1)
string(REGEX MATCH "peak load [^\n]*" with_beam "${run_log}")
run("${shard}" --plugin-dir "${tutorial}/plugins" run "${tiny}" --out "${WORK_DIR}/tiny_crushing" --threads 1
    --set bond.plugin=crushing_bond --set bond.crushing_ratio=0)
string(REGEX MATCH "peak load [^\n]*" with_crushing "${run_log}")
if(with_beam STREQUAL "" OR NOT with_beam STREQUAL with_crushing)
  message(FATAL_ERROR "crushing_bond at crushing_ratio 0 is not beam_bond: '${with_beam}' vs '${with_crushing}'")
endif()
run("${shard}" --plugin-dir "${tutorial}/plugins" run "${tiny}" --out "${WORK_DIR}/tiny_crushed" --threads 1
    --set bond.plugin=crushing_bond --set bond.crushing_ratio=2)
string(REGEX MATCH "peak load ([0-9.]+)" crushed "${run_log}")
string(REGEX MATCH "peak load ([0-9.]+)" intact "${with_beam}")
string(REGEX REPLACE "peak load " "" crushed "${crushed}")
string(REGEX REPLACE "peak load " "" intact "${intact}")
if(NOT crushed LESS intact)
  message(FATAL_ERROR "crushing_ratio 2 did not lower the peak load: ${crushed} N against ${intact} N")
endif()
message(STATUS "crushing_bond: built out of tree; neutral = beam_bond (${with_beam}); ratio 2: ${crushed} N")

# A second new-plugin into the same folder refuses to overwrite.
execute_process(COMMAND "${shard}" new-plugin contact oot_contact --dir "${WORK_DIR}/oot_contact"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "exists")
  message(FATAL_ERROR "new-plugin overwrote an existing plugin (rc ${rc}): ${err}")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
