# cmake -P script: fails when a C++ file of the project is not formatted by the root
# .clang-format. Input: -DSOURCE=<project source dir> -DCLANG_FORMAT=<program>.
file(GLOB_RECURSE files
  "${SOURCE}/include/*.hpp" "${SOURCE}/src/*.cpp" "${SOURCE}/src/*.hpp"
  "${SOURCE}/tests/*.cpp" "${SOURCE}/tests/*.hpp" "${SOURCE}/tools/*.cpp" "${SOURCE}/tools/*.hpp"
  "${SOURCE}/bench/*.cpp" "${SOURCE}/bench/*.hpp" "${SOURCE}/support/*.cpp" "${SOURCE}/support/*.hpp"
  "${SOURCE}/examples/*.cpp" "${SOURCE}/python/src/*.cpp" "${SOURCE}/python/src/*.hpp"
  "${SOURCE}/fuzz/*.cpp" "${SOURCE}/fuzz/*.hpp")
set(bad)
foreach(f IN LISTS files)
  execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror "${f}" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL 0)
    list(APPEND bad "${f}")
  endif()
endforeach()
list(LENGTH files n)
if(bad)
  string(REPLACE ";" "\n  " bad_lines "${bad}")
  message(FATAL_ERROR "not clang-formatted:\n  ${bad_lines}")
endif()
message(STATUS "${n} files formatted")
