# The version a build reports (kernel/include/shard/version.hpp): PROJECT_VERSION from the top-level
# project() and `git describe` of the checkout, taken at every build (at configure time it would go
# stale with the next commit) into a generated header that only kernel/src/version.cpp includes.
set(SHARD_VERSION_HEADER "${CMAKE_BINARY_DIR}/generated/shard_git_describe.h")
add_custom_target(shard_git_describe
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DOUTPUT=${SHARD_VERSION_HEADER}
          -DVERSION=${PROJECT_VERSION} -P ${CMAKE_CURRENT_LIST_DIR}/ShardGitDescribe.cmake
  BYPRODUCTS ${SHARD_VERSION_HEADER}
  COMMENT "Version: git describe of the checkout"
  VERBATIM)
set_source_files_properties(${PROJECT_SOURCE_DIR}/kernel/src/version.cpp TARGET_DIRECTORY shard_kernel
  PROPERTIES INCLUDE_DIRECTORIES "${CMAKE_BINARY_DIR}/generated")
add_dependencies(shard_kernel shard_git_describe)
