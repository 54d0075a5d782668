# The installed CMake package: `cmake --install` puts the plugin API headers (plugin_api/CMakeLists.txt),
# the Shard libraries, the plugins, the `shard` command, the plugin templates, the example scenes
# and <libdir>/cmake/Shard/ in the prefix (paths: cmake/ShardLayout.cmake), so that an out-of-tree
# plugin project needs only
#     find_package(Shard REQUIRED)
#     shard_add_plugin(my_effect SOURCES my_effect.cpp)
# (docs/how-to/write-a-plugin.md). Included from the top-level CMakeLists.txt after the kernel and apps.
include(CMakePackageConfigHelpers)

# Exported as shard::plugin_api, the name the build tree uses too; the kernel library is installed
# for the `shard` command only (its headers are the host's, not the API).
set_target_properties(shard_plugin_api PROPERTIES EXPORT_NAME plugin_api)
install(EXPORT ShardTargets NAMESPACE shard:: DESTINATION ${SHARD_INSTALL_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ShardConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/ShardConfig.cmake INSTALL_DESTINATION ${SHARD_INSTALL_CMAKE_DIR}
  PATH_VARS SHARD_INSTALL_PLUGIN_DIR)
# The plugin ABI is checked at load time (kAbiVersion), so any 0.x package serves a plugin built
# for the same minor version.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/ShardConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/ShardConfig.cmake ${CMAKE_BINARY_DIR}/cmake/ShardConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/ShardPlugin.cmake
        DESTINATION ${SHARD_INSTALL_CMAKE_DIR})

# Shared libraries carry the release in their file name and, in their SONAME, the part that must
# match: major.minor while the major version is 0 (a 0.x minor release may change them), then the
# major version (docs/how-to/install.md, "Versions").
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(SHARD_SOVERSION "${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}")
else()
  set(SHARD_SOVERSION "${PROJECT_VERSION_MAJOR}")
endif()
foreach(library IN ITEMS shard_kernel shard_analysis shard_bending shard_mpi)
  if(TARGET ${library})
    set_target_properties(${library} PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${SHARD_SOVERSION})
  endif()
endforeach()

# `shard new-plugin` reads the templates; the scenes with their geometry and data run as they do
# from the source tree (shard::install_layout finds both).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/templates/ DESTINATION ${SHARD_INSTALL_DATA_DIR}/templates)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${SHARD_INSTALL_DATA_DIR}/scenes)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/CHANGELOG.md ${PROJECT_SOURCE_DIR}/LICENSE
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
