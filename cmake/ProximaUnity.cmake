# Unity batches (PROXIMA_UNITY_BUILD, on in the CI presets): a target's sources compiled a
# few at a time, each batch one translation unit that includes its files. The headers of the
# standard library, GLM, GoogleTest, nlohmann-json and pybind11 are then parsed, and their
# templates compiled, once per batch instead of once per file.
#
# The batches are generated here rather than by CMake's UNITY_BUILD: each batch includes its
# sources by their paths from the project root (found through an include directory), so a
# batch's text is the same in every checkout and ccache reuses it across clones in other
# folders (CI builds a fresh clone); CMake's batches name the sources by absolute path.
# Sources outside the project tree (generated files) and sources with compile options or
# definitions of their own stay single.

option(PROXIMA_UNITY_BUILD "Compile the library, the tool, the Python module and the tests in unity batches" OFF)

# proxima_unity_sources(<out_var> <name> <batch_size> <source>...): the sources to give
# add_library / add_executable for target <name>: with PROXIMA_UNITY_BUILD, the generated
# batch files (of at most <batch_size> sources each) and the sources left single; else the
# sources as given. A target built from batches needs the project root as an include
# directory (proxima_unity_includes).
function(proxima_unity_sources out_var name batch_size)
  if(NOT PROXIMA_UNITY_BUILD)
    set(${out_var} ${ARGN} PARENT_SCOPE)
    return()
  endif()
  set(single)
  set(batched)
  foreach(source IN LISTS ARGN)
    get_filename_component(path "${source}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    file(RELATIVE_PATH relative "${PROJECT_SOURCE_DIR}" "${path}")
    get_source_file_property(options "${path}" COMPILE_OPTIONS)
    get_source_file_property(definitions "${path}" COMPILE_DEFINITIONS)
    if(relative MATCHES "^\\.\\./" OR options OR definitions)
      list(APPEND single "${source}")
    else()
      list(APPEND batched "${relative}")
    endif()
  endforeach()
  set(outputs ${single})
  set(batch "")
  set(count 0)
  list(LENGTH batched total)
  set(seen 0)
  foreach(relative IN LISTS batched)
    string(APPEND batch "#include \"${relative}\"\n")
    math(EXPR count "${count} + 1")
    math(EXPR seen "${seen} + 1")
    if(count EQUAL batch_size OR seen EQUAL total)
      list(LENGTH outputs index)
      set(batch_file "${CMAKE_CURRENT_BINARY_DIR}/unity/${name}_${index}.cpp")
      file(GENERATE OUTPUT "${batch_file}" CONTENT "${batch}")
      list(APPEND outputs "${batch_file}")
      set(batch "")
      set(count 0)
    endif()
  endforeach()
  set(${out_var} ${outputs} PARENT_SCOPE)
endfunction()

# proxima_unity_includes(<target>): the project root as a private include directory of a
# target built from proxima_unity_sources' batches (nothing without PROXIMA_UNITY_BUILD).
function(proxima_unity_includes target)
  if(PROXIMA_UNITY_BUILD)
    target_include_directories(${target} PRIVATE "${PROJECT_SOURCE_DIR}")
  endif()
endfunction()
