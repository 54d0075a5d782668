# shard_add_plugin(NAME kind_name SOURCES a.cpp ... [LIBRARIES ...])
# Builds one runtime-loaded MODULE into the plugin folder of the build tree. Plugins link only
# against the public headers (shard::plugin_api), never against the kernel library.
function(shard_add_plugin NAME)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  add_library(${NAME} MODULE ${ARG_SOURCES})
  target_link_libraries(${NAME} PRIVATE shard::plugin_api ${ARG_LIBRARIES})
  set_target_properties(${NAME} PROPERTIES
    PREFIX "shard_"
    LIBRARY_OUTPUT_DIRECTORY "${SHARD_BUILD_PLUGIN_DIR}"
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  install(TARGETS ${NAME} LIBRARY DESTINATION lib/shard/plugins)
  if(NOT TARGET shard_all_plugins)
    add_custom_target(shard_all_plugins)
  endif()
  add_dependencies(shard_all_plugins ${NAME})
endfunction()
