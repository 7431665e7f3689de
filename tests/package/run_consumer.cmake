# cmake -P script: configures, builds and runs tests/package/consumer in one of its modes.
# Inputs (-D): MODE, SOURCE (proxima source dir), WORK (scratch dir), BUILD (proxima build
# dir, for MODE=installed), GENERATOR, LAUNCHER (the compiler launcher of the outer build,
# e.g. ccache; may be empty).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}")
  endif()
endfunction()

set(extra)
if(LAUNCHER)
  list(APPEND extra "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
if(MODE STREQUAL "installed")
  run(${CMAKE_COMMAND} --install "${BUILD}" --prefix "${WORK}/prefix")
  list(APPEND extra "-DCMAKE_PREFIX_PATH=${WORK}/prefix")
elseif(MODE STREQUAL "fetchcontent")
  find_package(Git QUIET)
  if(GIT_FOUND AND EXISTS "${SOURCE}/.git")
    execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE}" rev-parse HEAD
      OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
    if(rc EQUAL 0)
      list(APPEND extra "-DPROXIMA_GIT_TAG=${head}")
    endif()
  endif()
endif()

run(${CMAKE_COMMAND} -S "${SOURCE}/tests/package/consumer" -B "${WORK}/build" -G "${GENERATOR}"
  -DCMAKE_BUILD_TYPE=Release -DPROXIMA_MODE=${MODE} "-DPROXIMA_SOURCE=${SOURCE}" ${extra})
run(${CMAKE_COMMAND} --build "${WORK}/build")
run("${WORK}/build/consumer")
