# spallkit_add_library(NAME DIR...): a library from every .cc under the given folders.
# Sources are globbed so a new concept is one new .h/.cc pair and nothing else.
#
# NAME is spallkit_<module>; the library is also spallkit::<module> (an ALIAS here, the exported
# name in an install tree). Static unless BUILD_SHARED_LIBS is on. Its headers are installed under
# include/spallkit/<folder relative to the source root>/, so "sim/bearing/scene.h" includes the
# same way in the build and in the install tree.
include(GNUInstallDirs)

set(SPALLKIT_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/spallkit)

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
  add_library(${name} ${sources})
  string(REGEX REPLACE "^spallkit_" "" export_name ${name})
  add_library(spallkit::${export_name} ALIAS ${name})
  set_target_properties(${name} PROPERTIES EXPORT_NAME ${export_name})
  if(NOT DEFINED CMAKE_INSTALL_RPATH)
    # Shared: an installed module finds the modules it links in its own folder.
    set_target_properties(${name} PROPERTIES INSTALL_RPATH "$ORIGIN")
  endif()
  target_compile_features(${name} PUBLIC cxx_std_20)  # the headers use C++20 (<numbers>, <span>)
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${SPALLKIT_INCLUDE_ROOT}>
                                            $<INSTALL_INTERFACE:${SPALLKIT_INSTALL_INCLUDEDIR}>)
  install(TARGETS ${name} EXPORT spallkitTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  set_property(GLOBAL APPEND PROPERTY SPALLKIT_EXPORTED_MODULES ${export_name})
  foreach(dir ${ARGN})
    file(RELATIVE_PATH relative ${SPALLKIT_INCLUDE_ROOT} ${dir})
    install(DIRECTORY ${dir}/ DESTINATION ${SPALLKIT_INSTALL_INCLUDEDIR}/${relative}
            FILES_MATCHING PATTERN "*.h")
  endforeach()
endfunction()
