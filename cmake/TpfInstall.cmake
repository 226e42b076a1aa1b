# Installs tpf::core so that a controller finds it with find_package(tpf).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS tpf_core tpf_warnings EXPORT tpfTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/tpf DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The twin's robot, pad, parameter and scenario files and the weights: what the tool's defaults
# name. The measured logs in data/real stay in the source tree (their licences beside them).
install(DIRECTORY data/ DESTINATION ${CMAKE_INSTALL_DATADIR}/tpf PATTERN real EXCLUDE)
install(EXPORT tpfTargets NAMESPACE tpf:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tpf)
configure_package_config_file(cmake/tpfConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/tpfConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tpf)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/tpfConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/tpfConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/tpfConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tpf)
