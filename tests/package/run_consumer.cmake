# cmake -P script: configures, builds and runs tests/package/consumer in one of its modes.
# Inputs (-D): MODE, SOURCE (proxima source dir), WORK (scratch dir), BUILD (proxima build
# dir, for MODE=installed), GENERATOR, LAUNCHER (compiler launcher such as ccache; optional).
# The fetchcontent consumer builds the library without exceptions (PROXIMA_CONSUMER_NO_EXCEPTIONS).
# The consumers that compile the library from source (subdirectory, fetchcontent) build it unoptimised and with clang when it is installed: they test how the
# package is consumed, not its speed, and -O0 compiles the library several times faster.
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
  list(APPEND extra "-DPROXIMA_CONSUMER_NO_EXCEPTIONS=ON")
  # The library in unity batches (cmake/ProximaUnity.cmake), as CI builds it: they must
  # compile in a subproject, with clang and without exceptions too, and they compile the
  # library in about a third of the time.
  list(APPEND extra "-DPROXIMA_UNITY_BUILD=ON")
endif()

set(build_type Release)
if(NOT MODE STREQUAL "installed")
  set(build_type Debug)
  # A user's project built with the other compiler: the library's sources compile with
  # clang as well as GCC (and clang -O0 compiles them faster).
  find_program(clang_compiler NAMES clang++ clang++-14)
  if(clang_compiler)
    list(APPEND extra "-DCMAKE_CXX_COMPILER=${clang_compiler}")
  endif()
endif()
run(${CMAKE_COMMAND} -S "${SOURCE}/tests/package/consumer" -B "${WORK}/build" -G "${GENERATOR}"
  -DCMAKE_BUILD_TYPE=${build_type} -DPROXIMA_MODE=${MODE} "-DPROXIMA_SOURCE=${SOURCE}" ${extra})
run(${CMAKE_COMMAND} --build "${WORK}/build")
run("${WORK}/build/consumer")
