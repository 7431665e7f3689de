# cmake -P script: fails when the project's C++ files reach into another tree sideways.
#   - no include of a relative parent path (dot-dot) anywhere: internal headers are included from the library's internal
#     root (proxima::internal), shared test and bench code from proxima_support;
#   - public headers (include/proxima) include only public headers and the standard library,
#     GLM included, never an internal header of src/;
#   - the tool never includes a benchmark's file.
# Input: -DSOURCE=<project source dir>.
file(GLOB_RECURSE files
  "${SOURCE}/include/*.hpp" "${SOURCE}/src/*.cpp" "${SOURCE}/src/*.hpp"
  "${SOURCE}/tests/*.cpp" "${SOURCE}/tests/*.hpp" "${SOURCE}/tools/*.cpp" "${SOURCE}/tools/*.hpp"
  "${SOURCE}/bench/*.cpp" "${SOURCE}/bench/*.hpp" "${SOURCE}/support/*.cpp" "${SOURCE}/support/*.hpp"
  "${SOURCE}/examples/*.cpp")
set(bad)
foreach(f IN LISTS files)
  file(STRINGS "${f}" includes REGEX "^[ \t]*#[ \t]*include")
  file(RELATIVE_PATH rel "${SOURCE}" "${f}")
  foreach(line IN LISTS includes)
    if(line MATCHES "#[ \t]*include[ \t]*\"\\.\\./")
      list(APPEND bad "${rel}: relative include: ${line}")
    endif()
    if(rel MATCHES "^include/" AND line MATCHES "#[ \t]*include[ \t]*\"")
      list(APPEND bad "${rel}: a public header includes a non-public file: ${line}")
    endif()
    if(rel MATCHES "^tools/" AND line MATCHES "bench/")
      list(APPEND bad "${rel}: the tool includes a benchmark file: ${line}")
    endif()
  endforeach()
endforeach()
list(LENGTH files n)
if(bad)
  string(REPLACE ";" "\n  " bad_lines "${bad}")
  message(FATAL_ERROR "include hygiene:\n  ${bad_lines}")
endif()
message(STATUS "${n} files: no relative or sideways include")
