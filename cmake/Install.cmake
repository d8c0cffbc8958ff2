# Installs the libraries, their headers, the crowdbake command and a CMake package, so a game
# can use an installed crowdbake (tests/package: a consumer project built against it):
#   find_package(crowdbake CONFIG REQUIRED)
#   target_link_libraries(game PRIVATE crowdbake::runtime crowdbake::gpu)
# `cpack -G DEB` in the build folder makes a .deb of the same files.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CROWDBAKE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/crowdbake)

# Public name (crowdbake::NAME) of each installed library. Static libraries carry their
# private dependencies to the link: crowdbake_spirv (the embedded shaders) and the
# crowdbake_warnings flags target (compile options only, never propagated) come along.
set(crowdbake_installed base formats runtime crowd effects scene_effects gpu spirv warnings)
if(CROWDBAKE_BUILD_PIPELINE)
  list(APPEND crowdbake_installed pipeline)
endif()
set(crowdbake_install_targets "")
foreach(name IN LISTS crowdbake_installed)
  set_target_properties(crowdbake_${name} PROPERTIES EXPORT_NAME ${name})
  list(APPEND crowdbake_install_targets crowdbake_${name})
endforeach()

install(TARGETS ${crowdbake_install_targets} EXPORT crowdbakeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY base/include/ formats/include/ runtime/include/ runtime/crowd/include/
                  runtime/effects/include/ runtime/scene_effects/include/ runtime/gpu/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(CROWDBAKE_BUILD_PIPELINE)
  install(DIRECTORY pipeline/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(CROWDBAKE_BUILD_CLI)
  install(TARGETS crowdbake RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

install(EXPORT crowdbakeTargets NAMESPACE crowdbake:: DESTINATION ${CROWDBAKE_CMAKE_DIR})
configure_package_config_file(cmake/crowdbakeConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/crowdbakeConfig.cmake
                              INSTALL_DESTINATION ${CROWDBAKE_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/crowdbakeConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/crowdbakeConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/crowdbakeConfigVersion.cmake
        DESTINATION ${CROWDBAKE_CMAKE_DIR})

# The .deb: Debian's names for what the installed libraries and the command link.
set(CPACK_PACKAGE_NAME crowdbake)
set(CPACK_PACKAGE_VENDOR "crowdbake")
set(CPACK_PACKAGE_CONTACT "crowdbake developers <crowdbake@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Bakes skinned characters into packs and renders huge animated crowds with continuous LoD")
set(CPACK_DEBIAN_PACKAGE_SECTION devel)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(crowdbake_deb_depends "libdraco-dev, libmeshoptimizer-dev, libglm-dev, nlohmann-json3-dev"
                          "libvulkan-dev, libgmp-dev, libstb-dev, libzstd-dev")
if(CROWDBAKE_BUILD_PIPELINE)
  list(APPEND crowdbake_deb_depends "libassimp-dev, libjpeg-dev")
endif()
if(CROWDBAKE_BUILD_CLI)
  list(APPEND crowdbake_deb_depends "mesa-vulkan-drivers")
endif()
string(REPLACE ";" ", " CPACK_DEBIAN_PACKAGE_DEPENDS "${crowdbake_deb_depends}")
set(CPACK_GENERATOR DEB)
include(CPack)
