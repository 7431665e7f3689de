// The extension module proxima._proxima; the package proxima re-exports it.
#include <proxima/core/config.hpp>

#include "module_parts.hpp"

PYBIND11_MODULE(_proxima, m) {
  using namespace proxima::python;
  m.doc() = "Proxima: collision detection for games, simulation and robotics (the compiled part).";
  m.attr("DOUBLE_PRECISION") = bool(PROXIMA_DOUBLE);
  bind_errors(m);
  bind_core(m);
  bind_shapes(m);
  bind_queries(m);
  bind_ccd(m);
  bind_bounds(m);
  bind_batch(m);
  bind_broadphase(m);
  bind_world(m);
  bind_d2(m);
  bind_world_d2(m);
  bind_render(m);
}
