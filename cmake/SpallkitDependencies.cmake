# Third-party dependencies, all from Debian 12 packages (see scripts/install-deps.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(PkgConfig REQUIRED)
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)
pkg_check_modules(FFTW3F REQUIRED IMPORTED_TARGET fftw3f)  # single precision (kurtogram)
find_package(HDF5 REQUIRED COMPONENTS C)
find_package(OpenMP REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(Ceres REQUIRED)
find_package(GTest REQUIRED)
if(SPALLKIT_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

# HDF5's CMake config gives plain variables; wrap them in one target.
add_library(spallkit_hdf5 INTERFACE)
target_include_directories(spallkit_hdf5 SYSTEM INTERFACE ${HDF5_INCLUDE_DIRS})
target_link_libraries(spallkit_hdf5 INTERFACE ${HDF5_C_LIBRARIES})
target_compile_definitions(spallkit_hdf5 INTERFACE ${HDF5_DEFINITIONS})

# Debian's per-module OpenCV -dev packages (core, imgproc, imgcodecs) ship no CMake config,
# only headers and libraries, so locate them directly. Much lighter than all of libopencv-dev.
find_path(OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
add_library(spallkit_opencv INTERFACE)
target_include_directories(spallkit_opencv SYSTEM INTERFACE ${OPENCV_INCLUDE_DIR})
foreach(module core imgproc imgcodecs)
  find_library(OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
  target_link_libraries(spallkit_opencv INTERFACE ${OPENCV_${module}_LIBRARY})
endforeach()

# MPI (optional, Open MPI from Debian): `spall dataset run` under `mpirun -n P` spreads a sweep's
# cases over the ranks. Without it the build still works and runs sweeps on local workers.
option(SPALLKIT_WITH_MPI "Use MPI for spall dataset when it is found" ON)
if(SPALLKIT_WITH_MPI)
  find_package(MPI COMPONENTS C QUIET)
endif()
