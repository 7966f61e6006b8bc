# Installs the library, headers, CLI and a relocatable CMake package so that consumers can
# `find_package(odocal)` and link `odocal::odocal`.
include(CMakePackageConfigHelpers)

set(ODOCAL_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/odocal")

install(TARGETS odocal odocal_bag EXPORT odocalTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/odocal DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(ODOCAL_BUILD_APPS)
  install(TARGETS odocal_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

install(EXPORT odocalTargets NAMESPACE odocal:: DESTINATION ${ODOCAL_CMAKE_DIR})
configure_package_config_file(cmake/odocalConfig.cmake.in
                              "${PROJECT_BINARY_DIR}/odocalConfig.cmake"
                              INSTALL_DESTINATION ${ODOCAL_CMAKE_DIR})
write_basic_package_version_file("${PROJECT_BINARY_DIR}/odocalConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/odocalConfig.cmake"
              "${PROJECT_BINARY_DIR}/odocalConfigVersion.cmake"
              cmake/FindGeographicLib.cmake
        DESTINATION ${ODOCAL_CMAKE_DIR})
