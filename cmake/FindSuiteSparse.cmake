# FindSuiteSparse: Debian's libsuitesparse-dev ships no CMake config, so find the
# headers under include/suitesparse and the libraries by name.
#
# Defines imported targets SuiteSparse::UMFPACK and SuiteSparse::CHOLMOD (each with
# the AMD/COLAMD/config libraries they need) and SuiteSparse_FOUND.

find_path(SuiteSparse_INCLUDE_DIR NAMES umfpack.h cholmod.h PATH_SUFFIXES suitesparse)

foreach(lib suitesparseconfig amd colamd camd ccolamd umfpack cholmod)
  string(TOUPPER ${lib} LIB)
  find_library(SuiteSparse_${LIB}_LIBRARY NAMES ${lib})
  list(APPEND _ss_required SuiteSparse_${LIB}_LIBRARY)
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS SuiteSparse_INCLUDE_DIR ${_ss_required})

if(SuiteSparse_FOUND)
  function(_suitesparse_target name lib)
    if(NOT TARGET SuiteSparse::${name})
      add_library(SuiteSparse::${name} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${name} PROPERTIES
        IMPORTED_LOCATION "${lib}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
      if(ARGN)
        set_property(TARGET SuiteSparse::${name} PROPERTY INTERFACE_LINK_LIBRARIES ${ARGN})
      endif()
    endif()
  endfunction()
  _suitesparse_target(config ${SuiteSparse_SUITESPARSECONFIG_LIBRARY})
  _suitesparse_target(AMD ${SuiteSparse_AMD_LIBRARY} SuiteSparse::config)
  _suitesparse_target(COLAMD ${SuiteSparse_COLAMD_LIBRARY} SuiteSparse::config)
  _suitesparse_target(CAMD ${SuiteSparse_CAMD_LIBRARY} SuiteSparse::config)
  _suitesparse_target(CCOLAMD ${SuiteSparse_CCOLAMD_LIBRARY} SuiteSparse::config)
  _suitesparse_target(UMFPACK ${SuiteSparse_UMFPACK_LIBRARY} SuiteSparse::AMD SuiteSparse::config)
  _suitesparse_target(CHOLMOD ${SuiteSparse_CHOLMOD_LIBRARY}
    SuiteSparse::AMD SuiteSparse::COLAMD SuiteSparse::CAMD SuiteSparse::CCOLAMD SuiteSparse::config)
endif()

mark_as_advanced(SuiteSparse_INCLUDE_DIR)
