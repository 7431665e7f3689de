#include "module_parts.hpp"
namespace proxima::python {
void bind_d2(py::module_&) {}
}  // namespace proxima::python
