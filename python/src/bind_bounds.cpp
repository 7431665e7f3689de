#include "module_parts.hpp"
namespace proxima::python {
void bind_bounds(py::module_&) {}
}  // namespace proxima::python
