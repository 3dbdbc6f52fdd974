# Install tree: `spall`, the libraries, their headers (include/spallkit/<module>/...) and a CMake
# package, so another project does
#     find_package(spallkit CONFIG REQUIRED)
#     target_link_libraries(app PRIVATE spallkit::sim)
# The targets themselves are installed by spallkit_add_library (cmake/SpallkitModule.cmake).
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

set(SPALLKIT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/spallkit)
get_property(SPALLKIT_EXPORTED_MODULES GLOBAL PROPERTY SPALLKIT_EXPORTED_MODULES)

install(EXPORT spallkitTargets NAMESPACE spallkit:: DESTINATION ${SPALLKIT_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/spallkitConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/spallkitConfig.cmake
                              INSTALL_DESTINATION ${SPALLKIT_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/spallkitConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/spallkitConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/spallkitConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/FindSpallkitFFTW.cmake
              ${CMAKE_CURRENT_LIST_DIR}/FindSpallkitHDF5.cmake
              ${CMAKE_CURRENT_LIST_DIR}/FindSpallkitOpenCV.cmake
              ${CMAKE_CURRENT_LIST_DIR}/SpallkitFindLibraries.cmake
        DESTINATION ${SPALLKIT_INSTALL_CMAKEDIR})
