# Finds FFTW (double and single precision) through pkg-config and defines the imported targets
# PkgConfig::FFTW3 and PkgConfig::FFTW3F. Used by the build and by an installed
# spallkitConfig.cmake (the static DSP library's link interface names these targets).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(FFTW3 QUIET IMPORTED_TARGET fftw3)
  pkg_check_modules(FFTW3F QUIET IMPORTED_TARGET fftw3f)  # single precision (kurtogram)
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SpallkitFFTW REQUIRED_VARS FFTW3_LINK_LIBRARIES FFTW3F_LINK_LIBRARIES)
