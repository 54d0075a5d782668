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
  install(TARGETS ${NAME} LIBRARY DESTINATION ${SHARD_INSTALL_PLUGIN_DIR})
  if(NOT TARGET shard_all_plugins)
    add_custom_target(shard_all_plugins)
  endif()
  add_dependencies(shard_all_plugins ${NAME})
endfunction()

# A plugin's model as a static library, so tests can drive it directly and the plugin module
# wraps it. EXACT_LANES: sources whose SIMD lanes must round exactly as the scalar reference, so
# no a * b + c may be fused into one rounding (GCC would in an AVX-512 version, whose target
# enables FMA).
#
# LANE_KERNELS: sources written once for a lane type (shard::lanes, plugin_api/simd: lane_type.hpp),
# each compiled once per instruction set with SHARD_LANES_<SET> defined: SCALAR (the reference,
# T = double), BASELINE (xsimd's batch for the target's default set) and, on x86-64, AVX2 and
# AVX512 (chosen at run time, lane_sets.hpp). All with -ffp-contract=off, so every set rounds as
# the scalar reference.
function(shard_add_plugin_model NAME)
  cmake_parse_arguments(ARG "" "" "SOURCES;EXACT_LANES;LANE_KERNELS" ${ARGN})
  add_library(${NAME} STATIC ${ARG_SOURCES} ${ARG_EXACT_LANES})
  if(ARG_EXACT_LANES)
    set_source_files_properties(${ARG_EXACT_LANES} PROPERTIES COMPILE_OPTIONS -ffp-contract=off)
  endif()
  target_include_directories(${NAME} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(${NAME} PUBLIC shard::plugin_api)
  set_target_properties(${NAME} PROPERTIES CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_LANE_KERNELS)
    target_link_libraries(${NAME} PUBLIC shard_lanes)
    set(sets SCALAR BASELINE)
    if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
      list(APPEND sets AVX2 AVX512)
    endif()
    foreach(source IN LISTS ARG_LANE_KERNELS)
      get_filename_component(stem "${source}" NAME_WE)
      foreach(set IN LISTS sets)
        set(object ${NAME}_${stem}_${set})
        add_library(${object} OBJECT ${source})
        target_link_libraries(${object} PRIVATE shard_lanes)
        target_compile_definitions(${object} PRIVATE SHARD_LANES_${set})
        # GCC 12 warns that _mm512_sqrt_pd's own _mm512_undefined_pd() is "(maybe) used uninitialized"
        # (inside avx512fintrin.h, whatever the caller does): silenced for that object alone.
        target_compile_options(${object} PRIVATE -ffp-contract=off
                               $<$<STREQUAL:${set},AVX2>:-mavx2>
                               $<$<STREQUAL:${set},AVX512>:-mavx512f -Wno-maybe-uninitialized -Wno-uninitialized>)
        set_target_properties(${object} PROPERTIES CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
        target_sources(${NAME} PRIVATE $<TARGET_OBJECTS:${object}>)
      endforeach()
    endforeach()
  endif()
endfunction()
