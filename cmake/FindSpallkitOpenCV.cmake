# Finds the three OpenCV modules the plotting target uses (core, imgproc, imgcodecs) and defines
# the imported target SpallkitOpenCV::OpenCV. Debian's per-module OpenCV -dev packages ship no
# CMake config, only headers and libraries, so they are located directly (much lighter than all
# of libopencv-dev). Used by the build and by an installed spallkitConfig.cmake.
find_path(SpallkitOpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
foreach(module core imgproc imgcodecs)
  find_library(SpallkitOpenCV_${module}_LIBRARY opencv_${module})
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/SpallkitFindLibraries.cmake)
spallkit_find_finish(SpallkitOpenCV::OpenCV SpallkitOpenCV_INCLUDE_DIR SpallkitOpenCV_core_LIBRARY
                     SpallkitOpenCV_imgproc_LIBRARY SpallkitOpenCV_imgcodecs_LIBRARY)
