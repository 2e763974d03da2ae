#----------------------------------------------------------------
# Generated CMake target import file.
#----------------------------------------------------------------

# Commands may need to know the format version.
set(CMAKE_IMPORT_FILE_VERSION 1)

# Import target "ogk::ogk" for configuration ""
set_property(TARGET ogk::ogk APPEND PROPERTY IMPORTED_CONFIGURATIONS NOCONFIG)
set_target_properties(ogk::ogk PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_NOCONFIG "C"
  IMPORTED_LOCATION_NOCONFIG "${_IMPORT_PREFIX}/lib/libogk.a"
  )

list(APPEND _cmake_import_check_targets ogk::ogk )
list(APPEND _cmake_import_check_files_for_ogk::ogk "${_IMPORT_PREFIX}/lib/libogk.a" )

# Commands beyond this point should not need to know the version.
set(CMAKE_IMPORT_FILE_VERSION)
