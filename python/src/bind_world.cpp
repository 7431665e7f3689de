#include "module_parts.hpp"
namespace proxima::python {
void bind_world(py::module_&) {}
}  // namespace proxima::python
