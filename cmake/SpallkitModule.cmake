# spallkit_add_library(NAME DIR...): a library from every .cc under the given folders.
# Sources are globbed so a new concept is one new .h/.cc pair and nothing else.
function(spallkit_add_library name)
  set(sources)
  foreach(dir ${ARGN})
    file(GLOB_RECURSE found CONFIGURE_DEPENDS ${dir}/*.cc)
    list(APPEND sources ${found})
  endforeach()
  if(NOT sources)
    # A module with no sources yet still gives a linkable target.
    set(empty ${CMAKE_CURRENT_BINARY_DIR}/${name}_empty.cc)
    file(WRITE ${empty} "// empty module\n")
    set(sources ${empty})
  endif()
  add_library(${name} STATIC ${sources})
  target_include_directories(${name} PUBLIC ${SPALLKIT_INCLUDE_ROOT})
endfunction()
