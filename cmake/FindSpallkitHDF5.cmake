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

include(${CMAKE_CURRENT_LIST_DIR}/SpallkitFindLibraries.cmake)
spallkit_find_finish(SpallkitHDF5::HDF5 SpallkitHDF5_INCLUDE_DIR SpallkitHDF5_LIBRARY)
