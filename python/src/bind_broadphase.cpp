#include "module_parts.hpp"
namespace proxima::python {
void bind_broadphase(py::module_&) {}
}  // namespace proxima::python
