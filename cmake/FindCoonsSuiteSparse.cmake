# Finds the parts of SuiteSparse that coons uses (CHOLMOD, UMFPACK and their dependencies).
# Debian's libsuitesparse-dev (5.12) ships no CMake configuration, so this looks for the headers
# and libraries directly and defines the imported target CoonsSuiteSparse::SuiteSparse.
#
#   CoonsSuiteSparse_FOUND         true when everything below was found
#   CoonsSuiteSparse_INCLUDE_DIR   the folder holding cholmod.h and umfpack.h

find_path(CoonsSuiteSparse_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
set(_coons_ss_libs cholmod umfpack amd colamd camd ccolamd suitesparseconfig)
set(_coons_ss_found_libs)
set(_coons_ss_missing)
foreach(_lib IN LISTS _coons_ss_libs)
  find_library(CoonsSuiteSparse_${_lib}_LIBRARY NAMES ${_lib})
  if(CoonsSuiteSparse_${_lib}_LIBRARY)
    list(APPEND _coons_ss_found_libs ${CoonsSuiteSparse_${_lib}_LIBRARY})
  else()
    list(APPEND _coons_ss_missing ${_lib})
  endif()
  mark_as_advanced(CoonsSuiteSparse_${_lib}_LIBRARY)
endforeach()
# METIS is optional: CHOLMOD's default ordering uses it when CHOLMOD was built with it.
find_library(CoonsSuiteSparse_metis_LIBRARY NAMES metis)
mark_as_advanced(CoonsSuiteSparse_metis_LIBRARY)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CoonsSuiteSparse
  REQUIRED_VARS CoonsSuiteSparse_INCLUDE_DIR CoonsSuiteSparse_cholmod_LIBRARY
                CoonsSuiteSparse_umfpack_LIBRARY CoonsSuiteSparse_suitesparseconfig_LIBRARY
  REASON_FAILURE_MESSAGE "install the Debian package libsuitesparse-dev (missing: ${_coons_ss_missing})")

if(CoonsSuiteSparse_FOUND AND NOT TARGET CoonsSuiteSparse::SuiteSparse)
  add_library(CoonsSuiteSparse::SuiteSparse INTERFACE IMPORTED)
  set_target_properties(CoonsSuiteSparse::SuiteSparse PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${CoonsSuiteSparse_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${_coons_ss_found_libs}")
endif()
mark_as_advanced(CoonsSuiteSparse_INCLUDE_DIR)
