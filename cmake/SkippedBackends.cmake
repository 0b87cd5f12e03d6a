# coons_skipped_backend(<condition...> <id> <description> <how>): when the condition holds, a
# CTest test "backend_<id>" that prints "skipped: <description> not built (<how>)" and reports
# itself as skipped (SKIP_RETURN_CODE), so a missing optional backend is visible in the configure
# summary and in every test summary instead of silently absent.
function(coons_skipped_backend)
  list(LENGTH ARGV count)
  math(EXPR last "${count} - 1")
  list(GET ARGV ${last} how)
  math(EXPR i "${last} - 1")
  list(GET ARGV ${i} description)
  math(EXPR i "${last} - 2")
  list(GET ARGV ${i} id)
  list(SUBLIST ARGV 0 ${i} condition)
  if(${condition})
    set(text "skipped: ${description} not built (${how})")
    message(STATUS "coons: tests ${text}")
    add_test(NAME backend_${id} COMMAND sh -c "echo '${text}'; exit 77")
    set_tests_properties(backend_${id} PROPERTIES SKIP_RETURN_CODE 77)
  endif()
endfunction()
