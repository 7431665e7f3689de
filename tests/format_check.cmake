# cmake -P script: fails when a C++ file of the project is not formatted by the root
# .clang-format. Input: -DSOURCE=<project source dir> -DCLANG_FORMAT=<program>.
file(GLOB_RECURSE files
  "${SOURCE}/include/*.hpp" "${SOURCE}/src/*.cpp" "${SOURCE}/src/*.hpp"
  "${SOURCE}/tests/*.cpp" "${SOURCE}/tests/*.hpp" "${SOURCE}/tools/*.cpp" "${SOURCE}/tools/*.hpp"
  "${SOURCE}/bench/*.cpp" "${SOURCE}/bench/*.hpp" "${SOURCE}/support/*.cpp" "${SOURCE}/support/*.hpp"
  "${SOURCE}/examples/*.cpp" "${SOURCE}/python/src/*.cpp" "${SOURCE}/python/src/*.hpp"
  "${SOURCE}/fuzz/*.cpp" "${SOURCE}/fuzz/*.hpp")
# One clang-format process for every file (a process per file took a minute and a half of
# the CI's test time); the files it names in its diagnostics are the ones not formatted.
execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror ${files} RESULT_VARIABLE rc OUTPUT_QUIET
                ERROR_VARIABLE diagnostics)
list(LENGTH files n)
if(NOT rc EQUAL 0)
  string(REGEX MATCHALL "[^\n]*:[0-9]+:[0-9]+: error: code should be clang-formatted" hits "${diagnostics}")
  set(bad)
  foreach(hit IN LISTS hits)
    string(REGEX REPLACE ":[0-9]+:[0-9]+: error: code should be clang-formatted$" "" file "${hit}")
    list(APPEND bad "${file}")
  endforeach()
  if(NOT bad)
    message(FATAL_ERROR "clang-format failed (exit ${rc}):\n${diagnostics}")
  endif()
  list(REMOVE_DUPLICATES bad)
  string(REPLACE ";" "\n  " bad_lines "${bad}")
  message(FATAL_ERROR "not clang-formatted:\n  ${bad_lines}")
endif()
message(STATUS "${n} files formatted")
