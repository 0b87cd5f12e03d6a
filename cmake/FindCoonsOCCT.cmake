# Finds OpenCASCADE (Debian: libocct-data-exchange-dev, libocct-modeling-algorithms-dev) by its
# headers and the toolkits coons_cad uses; defines the imported target CoonsOCCT::OCCT with the
# headers as SYSTEM includes (OCCT's own headers warn under -Wall -Wextra).
find_path(CoonsOCCT_INCLUDE_DIR Standard_Version.hxx PATH_SUFFIXES opencascade)
set(_coons_occt_toolkits TKSTEP TKSTEPBase TKSTEPAttr TKSTEP209 TKIGES TKXSBase TKShHealing TKTopAlgo
    TKGeomAlgo TKBRep TKGeomBase TKG3d TKG2d TKMath TKernel)
set(CoonsOCCT_LIBRARIES)
set(_coons_occt_missing)
foreach(tk ${_coons_occt_toolkits})
  find_library(CoonsOCCT_${tk}_LIBRARY ${tk})
  mark_as_advanced(CoonsOCCT_${tk}_LIBRARY)
  if(CoonsOCCT_${tk}_LIBRARY)
    list(APPEND CoonsOCCT_LIBRARIES ${CoonsOCCT_${tk}_LIBRARY})
  else()
    list(APPEND _coons_occt_missing ${tk})
  endif()
endforeach()
mark_as_advanced(CoonsOCCT_INCLUDE_DIR)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CoonsOCCT REQUIRED_VARS CoonsOCCT_INCLUDE_DIR CoonsOCCT_LIBRARIES
                                  REASON_FAILURE_MESSAGE "missing: ${_coons_occt_missing}")
if(CoonsOCCT_FOUND AND _coons_occt_missing)
  set(CoonsOCCT_FOUND FALSE)
endif()
if(CoonsOCCT_FOUND AND NOT TARGET CoonsOCCT::OCCT)
  add_library(CoonsOCCT::OCCT INTERFACE IMPORTED)
  set_target_properties(CoonsOCCT::OCCT PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${CoonsOCCT_INCLUDE_DIR}"
                                                   INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${CoonsOCCT_INCLUDE_DIR}"
                                                   INTERFACE_LINK_LIBRARIES "${CoonsOCCT_LIBRARIES}")
endif()
