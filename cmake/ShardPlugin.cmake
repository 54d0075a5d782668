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

# A plugin's model as a static library, so tests can drive it directly and the plugin module
# wraps it. EXACT_LANES: sources whose SIMD lanes must round exactly as the scalar reference, so
# no a * b + c may be fused into one rounding (GCC would in an AVX-512 version, whose target
# enables FMA).
function(shard_add_plugin_model NAME)
  cmake_parse_arguments(ARG "" "" "SOURCES;EXACT_LANES" ${ARGN})
  add_library(${NAME} STATIC ${ARG_SOURCES} ${ARG_EXACT_LANES})
  if(ARG_EXACT_LANES)
    set_source_files_properties(${ARG_EXACT_LANES} PROPERTIES COMPILE_OPTIONS -ffp-contract=off)
  endif()
  target_include_directories(${NAME} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${NAME} PUBLIC shard::plugin_api)
  set_target_properties(${NAME} PROPERTIES CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
endfunction()
