# Writes the provenance header (src/coons/study/build_info.h.in → OUT) with the revision of the
# source tree at build time (git describe --always --dirty), rewriting OUT only when the revision
# changed, so that a build after a commit names that commit and nothing recompiles otherwise.
# Run by the target coons_build_info: cmake -DSOURCE_DIR=… -DIN=… -DOUT=… [-DGIT=…] -P BuildInfo.cmake
set(COONS_GIT_REVISION "unknown")
if(GIT)
  execute_process(COMMAND ${GIT} describe --always --dirty
                  WORKING_DIRECTORY ${SOURCE_DIR}
                  OUTPUT_VARIABLE _coons_git OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE _coons_git_result ERROR_QUIET)
  if(_coons_git_result EQUAL 0 AND NOT _coons_git STREQUAL "")
    set(COONS_GIT_REVISION "${_coons_git}")
  endif()
endif()
configure_file(${IN} ${OUT} @ONLY)  # (leaves OUT untouched when its content would not change)
