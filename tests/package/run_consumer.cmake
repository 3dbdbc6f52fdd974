# cmake -P script behind the package.FindPackageConsumer test (see CMakeLists.txt here).
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${step} failed (${code}):\n${out}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

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
run("configure" ${CMAKE_COMMAND} ${configure_args})
run("build" ${CMAKE_COMMAND} --build ${build})
run("run" ${build}/spallkit_consumer)
message("${output}")
if(NOT output MATCHES "spallkit [0-9.]+: Q_max [0-9.]+ N")
  message(FATAL_ERROR "unexpected consumer output")
endif()
