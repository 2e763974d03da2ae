# ogk_version.cmake -- the kernel's version, read from kernel/include/ogk/version.h: that header is the
# one place the version is written (C code, CMake and the Python package all read it there).
#   ogk_read_version(<header> <out-var>)  sets <out-var> to "MAJOR.MINOR.PATCH"
function(ogk_read_version header out_var)
  file(STRINGS "${header}" lines REGEX "^#define OGK_VERSION_(MAJOR|MINOR|PATCH) +[0-9]+ *$")
  foreach(part MAJOR MINOR PATCH)
    set(value "")
    foreach(line IN LISTS lines)
      if(line MATCHES "^#define OGK_VERSION_${part} +([0-9]+) *$")
        set(value "${CMAKE_MATCH_1}")
      endif()
    endforeach()
    if(value STREQUAL "")
      message(FATAL_ERROR "${header}: no '#define OGK_VERSION_${part} <number>' line")
    endif()
    set(${part} "${value}")
  endforeach()
  set(${out_var} "${MAJOR}.${MINOR}.${PATCH}" PARENT_SCOPE)
endfunction()
