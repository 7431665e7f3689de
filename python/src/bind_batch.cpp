#include "module_parts.hpp"
namespace proxima::python {
void bind_batch(py::module_&) {}
}  // namespace proxima::python
