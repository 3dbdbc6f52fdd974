# Finds the three OpenCV modules the plotting target uses (core, imgproc, imgcodecs) and defines
# the imported target SpallkitOpenCV::OpenCV. Debian's per-module OpenCV -dev packages ship no
# CMake config, only headers and libraries, so they are located directly (much lighter than all
# of libopencv-dev). Used by the build and by an installed spallkitConfig.cmake.
find_path(SpallkitOpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(_spallkit_opencv_libraries)
set(_spallkit_opencv_required SpallkitOpenCV_INCLUDE_DIR)
foreach(module core imgproc imgcodecs)
  find_library(SpallkitOpenCV_${module}_LIBRARY opencv_${module})
  list(APPEND _spallkit_opencv_libraries ${SpallkitOpenCV_${module}_LIBRARY})
  list(APPEND _spallkit_opencv_required SpallkitOpenCV_${module}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SpallkitOpenCV REQUIRED_VARS ${_spallkit_opencv_required})

if(SpallkitOpenCV_FOUND AND NOT TARGET SpallkitOpenCV::OpenCV)
  add_library(SpallkitOpenCV::OpenCV INTERFACE IMPORTED)
  set_target_properties(SpallkitOpenCV::OpenCV PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${SpallkitOpenCV_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_spallkit_opencv_libraries}")
endif()
mark_as_advanced(SpallkitOpenCV_INCLUDE_DIR)
unset(_spallkit_opencv_libraries)
unset(_spallkit_opencv_required)
