# cmake -P script behind the package.FindPackageConsumer test (see CMakeLists.txt here).
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${step} failed (${code}):\n${out}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

# EXPECT_SHARED: SPALLKIT_BUILD_DIR must be a configured BUILD_SHARED_LIBS=ON tree; otherwise the
# test says why it is skipped (ctest's SKIP_REGULAR_EXPRESSION) and stops.
if(EXPECT_SHARED)
  set(cache ${SPALLKIT_BUILD_DIR}/CMakeCache.txt)
  if(NOT EXISTS ${cache})
    message("package test skipped: no shared-library build at ${SPALLKIT_BUILD_DIR}")
    return()
  endif()
  file(STRINGS ${cache} shared REGEX "^BUILD_SHARED_LIBS:BOOL=")
  if(NOT shared MATCHES "=(ON|TRUE|1)$")
    message("package test skipped: ${SPALLKIT_BUILD_DIR} is not a BUILD_SHARED_LIBS=ON build")
    return()
  endif()
  # Brought up to date first (incremental: a no-op when nothing changed), so that the libraries
  # installed match the headers installed from the source tree.
  run("build ${SPALLKIT_BUILD_DIR}" ${CMAKE_COMMAND} --build ${SPALLKIT_BUILD_DIR})
endif()

set(prefix ${WORK_DIR}/prefix)
set(build ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})
run("install" ${CMAKE_COMMAND} --install ${SPALLKIT_BUILD_DIR} --prefix ${prefix})
foreach(installed bin/spall include/spallkit/sim/quasistatic/harris_jones.h
        include/spallkit/core/bearing.h lib/cmake/spallkit/spallkitConfig.cmake
        lib/cmake/spallkit/spallkitConfigVersion.cmake)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "not installed: ${prefix}/${installed}")
  endif()
endforeach()

set(configure_args -S ${CONSUMER_SOURCE_DIR} -B ${build} -G ${GENERATOR}
                   -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
                   -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
if(CXX_COMPILER_LAUNCHER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_COMPILER_LAUNCHER})
endif()
if(EXPECT_SHARED AND NOT EXISTS ${prefix}/lib/libspallkit_sim.so)
  message(FATAL_ERROR "not installed: ${prefix}/lib/libspallkit_sim.so")
endif()
# The installed program runs from the prefix (with shared libraries: found through its RPATH).
run("installed spall" ${prefix}/bin/spall --version)
if(NOT output MATCHES "spallkit [0-9.]+")
  message(FATAL_ERROR "unexpected spall --version output: ${output}")
endif()

run("configure" ${CMAKE_COMMAND} ${configure_args})
run("build" ${CMAKE_COMMAND} --build ${build})
run("run" ${build}/spallkit_consumer)
message("${output}")
if(NOT output MATCHES "spallkit [0-9.]+: Q_max [0-9.]+ N")
  message(FATAL_ERROR "unexpected consumer output")
endif()
