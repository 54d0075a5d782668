# The installed CMake package: `cmake --install` puts the plugin API headers (kernel/CMakeLists.txt),
# libshard_kernel, the plugins, the `shard` command, the plugin templates and lib/cmake/Shard/ in the
# prefix, so that an out-of-tree plugin project needs only
#     find_package(Shard REQUIRED)
#     shard_add_plugin(my_effect SOURCES my_effect.cpp)
# (docs/how-to/write-a-plugin.md). Included from the top-level CMakeLists.txt after the kernel and apps.
include(CMakePackageConfigHelpers)
set(SHARD_INSTALL_CMAKE_DIR lib/cmake/Shard)

# Exported as shard::plugin_api, the name the build tree uses too; the kernel library is installed
# for the `shard` command only (its headers are the host's, not the API).
set_target_properties(shard_plugin_api PROPERTIES EXPORT_NAME plugin_api)
install(EXPORT ShardTargets NAMESPACE shard:: DESTINATION ${SHARD_INSTALL_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ShardConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/ShardConfig.cmake INSTALL_DESTINATION ${SHARD_INSTALL_CMAKE_DIR})
# The plugin ABI is checked at load time (kAbiVersion), so any 0.x package serves a plugin built
# for the same minor version.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/ShardConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/ShardConfig.cmake ${CMAKE_BINARY_DIR}/cmake/ShardConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/ShardPlugin.cmake
        DESTINATION ${SHARD_INSTALL_CMAKE_DIR})

# `shard new-plugin` reads these (installed: <prefix>/share/shard/templates; build tree: the source).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/templates/ DESTINATION share/shard/templates)
if(TARGET shard_app)
  target_compile_definitions(shard_app PRIVATE SHARD_SOURCE_TEMPLATE_DIR="${PROJECT_SOURCE_DIR}/templates")
endif()
