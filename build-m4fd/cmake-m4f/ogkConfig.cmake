# ogkConfig.cmake -- found by find_package(ogk): the targets ogk::ogk (static library) and, where the
# package was built with it, ogk::ogk_shared, with the compile definitions the library was built with.

####### Expanded from @PACKAGE_INIT@ by configure_package_config_file() #######
####### Any changes to this file will be overwritten by the next CMake run ####
####### The input file was ogkConfig.cmake.in                            ########

get_filename_component(PACKAGE_PREFIX_DIR "${CMAKE_CURRENT_LIST_DIR}/../../../" ABSOLUTE)

macro(set_and_check _var _file)
  set(${_var} "${_file}")
  if(NOT EXISTS "${_file}")
    message(FATAL_ERROR "File or directory ${_file} referenced by variable ${_var} does not exist !")
  endif()
endmacro()

macro(check_required_components _NAME)
  foreach(comp ${${_NAME}_FIND_COMPONENTS})
    if(NOT ${_NAME}_${comp}_FOUND)
      if(${_NAME}_FIND_REQUIRED_${comp})
        set(${_NAME}_FOUND FALSE)
      endif()
    endif()
  endforeach()
endmacro()

####################################################################################

include("${CMAKE_CURRENT_LIST_DIR}/ogkTargets.cmake")

# The dimension overrides the library was built with ("NAME=VALUE;..."; empty: the headers' values).
# ogk::ogk carries them already; this is for a consumer that builds other code against the headers.
set(ogk_DIMENSIONS "")
# The real type the library was built with (kernel/include/ogk/real.h): "double", or "single" (float), whose
# definition OGK_REAL_SINGLE=1 ogk::ogk carries too; ogk_DEFINITIONS holds every definition a program must
# share with the library (the dimensions' and the real type's), for code built against the headers alone.
set(ogk_PRECISION "double")
set(ogk_DEFINITIONS "")
set(ogk_SHARED_FOUND OFF)

check_required_components(ogk)
