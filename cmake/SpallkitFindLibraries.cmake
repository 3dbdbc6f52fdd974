# spallkit_find_finish(TARGET INCLUDE_VAR LIBRARY_VAR...): the end of a spallkit find module for a
# C/C++ library located with find_path / find_library. Reports found / not found for the module
# being run (REQUIRED and QUIET as the caller asked), then defines TARGET, an imported interface
# target carrying the include folder and the libraries. A macro: the <Package>_FOUND it sets
# belongs to the caller.
macro(spallkit_find_finish target include_var)
  include(FindPackageHandleStandardArgs)
  find_package_handle_standard_args(${CMAKE_FIND_PACKAGE_NAME}
                                    REQUIRED_VARS ${ARGN} ${include_var})
  if(${CMAKE_FIND_PACKAGE_NAME}_FOUND AND NOT TARGET ${target})
    set(_spallkit_libraries)
    foreach(_spallkit_var ${ARGN})
      list(APPEND _spallkit_libraries ${${_spallkit_var}})
    endforeach()
    add_library(${target} INTERFACE IMPORTED)
    set_target_properties(${target} PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${${include_var}}"
      INTERFACE_LINK_LIBRARIES "${_spallkit_libraries}")
    unset(_spallkit_libraries)
    unset(_spallkit_var)
  endif()
  mark_as_advanced(${include_var} ${ARGN})
endmacro()
