# Finds the HDF5 C library and defines the imported target SpallkitHDF5::HDF5. CMake's FindHDF5
# needs the C language enabled in the calling project (it test-compiles a C file), which a C++
# project using an installed spallkit need not have; this one asks pkg-config (Debian: hdf5.pc,
# the serial flavour), else looks for the header and library directly. Used by the build and by
# an installed spallkitConfig.cmake.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(SpallkitHDF5_PC QUIET hdf5)
endif()
find_path(SpallkitHDF5_INCLUDE_DIR hdf5.h HINTS ${SpallkitHDF5_PC_INCLUDE_DIRS}
          PATH_SUFFIXES hdf5/serial)
find_library(SpallkitHDF5_LIBRARY hdf5 HINTS ${SpallkitHDF5_PC_LIBRARY_DIRS}
             PATH_SUFFIXES hdf5/serial)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SpallkitHDF5
                                  REQUIRED_VARS SpallkitHDF5_LIBRARY SpallkitHDF5_INCLUDE_DIR)

if(SpallkitHDF5_FOUND AND NOT TARGET SpallkitHDF5::HDF5)
  add_library(SpallkitHDF5::HDF5 UNKNOWN IMPORTED)
  set_target_properties(SpallkitHDF5::HDF5 PROPERTIES
    IMPORTED_LOCATION "${SpallkitHDF5_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${SpallkitHDF5_INCLUDE_DIR}")
endif()
mark_as_advanced(SpallkitHDF5_INCLUDE_DIR SpallkitHDF5_LIBRARY)
