// libFuzzer entry point of the strict OFF mesh reader (tools/mesh_off.cpp), checked by
// mesh_reader_checks.hpp.
#include <cstddef>
#include <cstdint>

#include "mesh_reader_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return proxima::fuzz::check_read_mesh(proxima::tool::read_off(proxima::fuzz::file_bytes(data, size)));
}
