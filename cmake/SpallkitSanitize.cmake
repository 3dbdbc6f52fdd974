# Sanitizer and fuzzing builds (docs/RELIABILITY.md).
#
#   -DSPALLKIT_SANITIZE=address,undefined   every target instrumented (gcc or clang); run the tests
#   -DSPALLKIT_FUZZ=ON                      clang only: the libraries instrumented for libFuzzer
#                                           (with address and undefined) and the fuzz/ targets
set(SPALLKIT_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined")
option(SPALLKIT_FUZZ "Build the libFuzzer targets in fuzz/ (clang)" OFF)

if(SPALLKIT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "SPALLKIT_FUZZ needs clang (CXX=clang++ CC=clang); scripts/fuzz.sh sets it")
  endif()
  if(NOT SPALLKIT_SANITIZE)
    set(SPALLKIT_SANITIZE "address,undefined")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(SPALLKIT_SANITIZE)
  # Stop at the first undefined-behaviour report (a test then fails instead of printing and going on).
  add_compile_options(-fsanitize=${SPALLKIT_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all -g)
  add_link_options(-fsanitize=${SPALLKIT_SANITIZE})
endif()
