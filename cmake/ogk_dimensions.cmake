# ogk_dimensions.cmake -- the kernel's compile-time dimensions as cache options.
#
# A public header marks a dimension a build may change by guarding its default with #ifndef
# (ogk/config.h: "A build may override any of them with -D"; OGK_NOG_MAX_GRID, OGK_QP_MAX_N, ...).
# Every such macro becomes a cache variable of the same name, empty by default (the header's value).
# A value the user sets is a PUBLIC compile definition of the library: a consumer that links ogk::ogk
# (or reads ogk.pc) compiles with the same value, so its structs have the layout the library was
# built with. The list is read from the headers, so a newly guarded macro needs no change here.
#   ogk_dimension_options(<include-dir> <out-defs-var>)
function(ogk_dimension_options include_dir out_var)
  file(GLOB headers "${include_dir}/ogk/*.h")
  list(SORT headers)
  set(defs "")
  foreach(header IN LISTS headers)
    file(STRINGS "${header}" guards REGEX "^#ifndef OGK_[A-Z0-9_]+ *$")
    get_filename_component(header_name "${header}" NAME)
    foreach(guard IN LISTS guards)
      string(REGEX REPLACE "^#ifndef (OGK_[A-Z0-9_]+) *$" "\\1" name "${guard}")
      if(name MATCHES "_H$")
        continue() # the include guard, not a dimension
      endif()
      if(name STREQUAL "OGK_REAL_SINGLE")
        continue() # ogk/real.h's real type, not a dimension: the option OGK_PRECISION (CMakeLists.txt)
      endif()
      set(${name} "" CACHE STRING "override of ${name} (ogk/${header_name}); empty: the header's value")
      if(NOT "${${name}}" STREQUAL "")
        list(APPEND defs "${name}=${${name}}")
      endif()
    endforeach()
  endforeach()
  set(${out_var} "${defs}" PARENT_SCOPE)
endfunction()
