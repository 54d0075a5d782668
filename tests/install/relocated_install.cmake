# A relocatable install, as a user moves it: `cmake --install` into a scratch prefix, the prefix
# moved to another folder, then the moved `shard` must list every plugin the build has, each from
# the moved prefix (never from the build tree), find its templates, and run an installed scene.
# The build tree is only read. LAUNCHER (optional, a list such as "mpiexec;-n;2"): the scene runs
# under it, and the run must say it was decomposed over that many MPI ranks (RANKS).
# Run: cmake -DSHARD_BUILD_DIR=<build> -DWORK_DIR=<scratch> -DVERSION=<x.y.z> [-DLAUNCHER=... -DRANKS=N]
#            -P relocated_install.cmake
set(required_vars SHARD_BUILD_DIR WORK_DIR VERSION)
include(${CMAKE_CURRENT_LIST_DIR}/command_line.cmake)

file(REMOVE_RECURSE "${WORK_DIR}")
run(${CMAKE_COMMAND} --install "${SHARD_BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
file(RENAME "${WORK_DIR}/prefix" "${WORK_DIR}/moved")
set(prefix "${WORK_DIR}/moved")
set(shard "${prefix}/bin/shard")
regex_escaped(prefix_pattern "${prefix}")
# Nothing but the install layout may point the moved command at plugins.
set(clean_env ${CMAKE_COMMAND} -E env --unset=SHARD_PLUGIN_PATH --unset=SHARD_TEMPLATE_DIR --unset=LD_LIBRARY_PATH)

# Every plugin of the build, listed by the build's own command ...
run(${clean_env} "${SHARD_BUILD_DIR}/bin/shard" plugins)
string(REGEX MATCHALL "\n[a-z_]+/[a-z_0-9]+ [^ \n]+  \\(" built "\n${run_output}")
list(LENGTH built built_count)
if(built_count LESS 5)
  message(FATAL_ERROR "the build lists ${built_count} plugins:\n${run_output}")
endif()
# ... is listed by the moved one, from a file in the moved prefix.
run(${clean_env} "${shard}" plugins)
set(installed "${run_output}")
foreach(entry IN LISTS built)
  string(STRIP "${entry}" entry)
  regex_escaped(pattern "${entry}")
  expect_match("moved install" "${installed}" "(^|\n)${pattern}${prefix_pattern}/[^)]+/shard/plugins/shard_[a-z_0-9]+\\.so\\)")
endforeach()
# (The scratch prefix may lie inside the build folder: its own paths are taken out first.)
string(REPLACE "${prefix}/" "<moved prefix>/" outside_prefix "${installed}")
string(FIND "${outside_prefix}" "${SHARD_BUILD_DIR}" build_path_at)
if(NOT build_path_at EQUAL -1)
  message(FATAL_ERROR "the moved install names the build tree:\n${installed}")
endif()
message(STATUS "moved install lists all ${built_count} plugins of the build, from ${prefix}")

# The release of the build (CMake's project version), and the checkout's git describe when the
# source is a git checkout.
run(${clean_env} "${shard}" --version)
regex_escaped(version_pattern "${VERSION}")
expect_match("shard --version" "${run_output}" "^shard ${version_pattern}( \\(git [^)]+\\))?\n$")

# The templates of `shard new-plugin` are found beside the moved command.
run(${clean_env} "${shard}" new-plugin contact moved_contact --dir "${WORK_DIR}/moved_contact")
if(NOT EXISTS "${WORK_DIR}/moved_contact/CMakeLists.txt")
  message(FATAL_ERROR "new-plugin from the moved install wrote no CMakeLists.txt")
endif()

# The installed main scene, with its geometry, checks and runs (a few hundred steps).
file(GLOB_RECURSE scene "${prefix}/share/*/four_point_bending.toml")
if(NOT scene)
  message(FATAL_ERROR "no four_point_bending.toml installed under ${prefix}/share")
endif()
run(${clean_env} "${shard}" check "${scene}")
run(${clean_env} ${LAUNCHER} "${shard}" run "${scene}" --out "${WORK_DIR}/run" --threads 1 --set simulation.duration=0.004)
if(NOT EXISTS "${WORK_DIR}/run/run.h5")
  message(FATAL_ERROR "the installed scene wrote no run.h5:\n${run_log}")
endif()
if(LAUNCHER)
  string(REPLACE ";" " " launcher_line "${LAUNCHER}")
  expect_match("the installed scene under ${launcher_line}" "${run_output}${run_log}" "over ${RANKS} MPI ranks")
endif()
message(STATUS "the installed four_point_bending.toml ran from the moved prefix")
file(REMOVE_RECURSE "${WORK_DIR}")
