# Third-party dependencies, all from Debian 12 packages (see scripts/install-deps.sh). Each is
# looked for only when something that is built uses it; spallkitConfig.cmake.in finds the same
# ones for an install tree.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(SpallkitFFTW REQUIRED)
find_package(SpallkitHDF5 REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(CLI11 REQUIRED)  # the `spall` program only
find_package(nlohmann_json 3.10 REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(Ceres REQUIRED)  # identify; sim uses its header-only ceres::Jet
find_package(SpallkitOpenCV REQUIRED)  # plot only
if(SPALLKIT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(SPALLKIT_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

# Older names of the HDF5 and OpenCV targets, for CMake files that still use them.
add_library(spallkit_hdf5 ALIAS SpallkitHDF5::HDF5)
add_library(spallkit_opencv ALIAS SpallkitOpenCV::OpenCV)

# MPI (optional, Open MPI from Debian): `spall dataset run` under `mpirun -n P` spreads a sweep's
# cases over the ranks. Without it the build still works and runs sweeps on local workers.
option(SPALLKIT_WITH_MPI "Use MPI for spall dataset when it is found" ON)
if(SPALLKIT_WITH_MPI)
  # The CXX component (C API, no C++ bindings) so a C++-only project using an installed
  # spallkit::study finds it too.
  set(MPI_CXX_SKIP_MPICXX ON)
  find_package(MPI COMPONENTS CXX QUIET)
endif()
