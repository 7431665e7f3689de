# proxima_set_warnings(<target>): the project's warning set, as errors when
# PROXIMA_WARNINGS_AS_ERRORS is on (CI turns it on).
function(proxima_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual -Wimplicit-fallthrough)
  if(PROXIMA_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
