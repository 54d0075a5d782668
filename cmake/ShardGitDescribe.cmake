# Script mode (cmake -P): writes OUTPUT, a header defining SHARD_VERSION (-DVERSION=) and
# SHARD_GIT_DESCRIBE, `git describe` of SOURCE_DIR ("" outside a git checkout). The file is
# rewritten only when its text changes, so a build after no commit recompiles nothing.
foreach(var SOURCE_DIR OUTPUT VERSION)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "ShardGitDescribe.cmake: -D${var}= is required")
  endif()
endforeach()
set(describe "")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
  # Release tags are vX.Y.Z (docs/how-to/install.md, "Versions"); --always gives the commit when
  # none is reachable, --dirty marks uncommitted changes.
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --tags --match "v[0-9]*" --always --dirty
                  WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE describe RESULT_VARIABLE rc
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT rc EQUAL 0)
    set(describe "")
  endif()
endif()
file(CONFIGURE OUTPUT "${OUTPUT}" CONTENT
     "#define SHARD_VERSION \"${VERSION}\"\n#define SHARD_GIT_DESCRIBE \"${describe}\"\n")
