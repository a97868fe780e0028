# Locate SUNDIALS CVODE (>= 6) and set ${out_var} to TRUE when found, with
# TUMBLE_SUNDIALS_TARGETS naming what tumble::cvode links.
#
# SUNDIALS exports SUNDIALSConfig.cmake. Its target names differ between releases:
#   6.x: SUNDIALS::cvode_shared / SUNDIALS::cvode_static, ... (no SUNDIALS::core)
#   7.x: SUNDIALS::cvode (an alias), ..., and SUNDIALS::core, which every module needs.
# We take, for each component, the first of SUNDIALS::<c>, SUNDIALS::<c>_shared,
# SUNDIALS::<c>_static that exists. Without a config file we fall back to find_library.
set(TUMBLE_SUNDIALS_COMPONENTS cvode nvecserial sunmatrixdense sunlinsoldense sunmatrixband
    sunlinsolband sunlinsolspgmr sunnonlinsolfixedpoint)

macro(tumble_find_sundials out_var)
  set(${out_var} FALSE)
  set(TUMBLE_SUNDIALS_TARGETS "")
  find_package(SUNDIALS 6 QUIET CONFIG)
  if(SUNDIALS_FOUND)
    set(_tumble_ok TRUE)
    # A SUNDIALS built with MPI (Debian 13's 7.x) puts MPI::MPI_C in SUNDIALS::core's link
    # interface and looks MPI up itself, but FindMPI defines MPI::MPI_C only when the C language
    # is enabled: a C++-only project (tumble, most of its users) then fails at generate time with
    # "MPI::MPI_C ... target was not found". MPI::MPI_CXX brings the same libmpi and mpi.h (which
    # SUNDIALS 7's sundials_types.h includes), so it stands in for it.
    foreach(_tumble_core SUNDIALS::core_shared SUNDIALS::core_static)
      if(TARGET ${_tumble_core} AND NOT TARGET MPI::MPI_C)
        get_target_property(_tumble_links ${_tumble_core} INTERFACE_LINK_LIBRARIES)
        if("MPI::MPI_C" IN_LIST _tumble_links)
          if(NOT TARGET MPI::MPI_CXX)
            find_package(MPI QUIET COMPONENTS CXX)
          endif()
          if(TARGET MPI::MPI_CXX)
            add_library(MPI::MPI_C INTERFACE IMPORTED)
            target_link_libraries(MPI::MPI_C INTERFACE MPI::MPI_CXX)
          else()
            message(STATUS "tumble: this SUNDIALS was built with MPI, and MPI was not found "
                           "(Debian: apt-get install mpi-default-dev)")
            set(_tumble_ok FALSE)
          endif()
        endif()
      endif()
    endforeach()
    foreach(_c IN LISTS TUMBLE_SUNDIALS_COMPONENTS ITEMS core)
      set(_tumble_t "")
      foreach(_cand SUNDIALS::${_c} SUNDIALS::${_c}_shared SUNDIALS::${_c}_static)
        if(NOT _tumble_t AND TARGET ${_cand})
          set(_tumble_t ${_cand})
        endif()
      endforeach()
      if(_tumble_t)
        list(APPEND TUMBLE_SUNDIALS_TARGETS ${_tumble_t})
      elseif(NOT _c STREQUAL "core")  # core exists only from 7.0 on
        set(_tumble_ok FALSE)
      endif()
    endforeach()
    set(${out_var} ${_tumble_ok})
  endif()
  if(NOT ${out_var} AND SUNDIALS_CONFIG AND DEFINED SUNDIALS_NOT_FOUND_MESSAGE)
    # A config file that refused (e.g. Debian 13's SUNDIALS looks up OpenMP, which Clang finds
    # only with libomp-dev): say why, since the libraries found below lack its MPI/OpenMP flags.
    message(WARNING "tumble: ${SUNDIALS_CONFIG} was found but refused: "
                    "${SUNDIALS_NOT_FOUND_MESSAGE} Looking for the libraries by name instead.")
  endif()
  if(NOT ${out_var})
    set(TUMBLE_SUNDIALS_TARGETS "")
    find_path(TUMBLE_CVODE_INCLUDE_DIR cvode/cvode.h)
    set(_tumble_ok TRUE)
    foreach(_c IN LISTS TUMBLE_SUNDIALS_COMPONENTS)
      find_library(TUMBLE_SUNDIALS_${_c}_LIBRARY NAMES sundials_${_c})
      if(NOT TUMBLE_SUNDIALS_${_c}_LIBRARY)
        set(_tumble_ok FALSE)
      endif()
    endforeach()
    if(TUMBLE_CVODE_INCLUDE_DIR AND _tumble_ok)
      foreach(_c IN LISTS TUMBLE_SUNDIALS_COMPONENTS)
        if(NOT TARGET tumble_sundials::${_c})
          add_library(tumble_sundials::${_c} UNKNOWN IMPORTED)
          set_target_properties(tumble_sundials::${_c} PROPERTIES
            IMPORTED_LOCATION "${TUMBLE_SUNDIALS_${_c}_LIBRARY}"
            INTERFACE_INCLUDE_DIRECTORIES "${TUMBLE_CVODE_INCLUDE_DIR}")
        endif()
        list(APPEND TUMBLE_SUNDIALS_TARGETS tumble_sundials::${_c})
      endforeach()
      set(${out_var} TRUE)
    endif()
  endif()
  if(${out_var})
    message(STATUS "tumble: SUNDIALS CVODE found: ${TUMBLE_SUNDIALS_TARGETS}")
  else()
    message(STATUS "tumble: SUNDIALS CVODE (>= 6) not found; tumble::cvode is not available")
  endif()
endmacro()
