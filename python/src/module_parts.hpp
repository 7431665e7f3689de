#pragma once
/// @file module_parts.hpp
/// The binding files, each adding one part of the library to the module `proxima._proxima`
/// (module.cpp calls them in this order: later parts use the classes of earlier ones).
#include <proxima/core/result.hpp>

#include <pybind11/pybind11.h>

namespace proxima::python {

namespace py = pybind11;

void bind_errors(py::module_& m);      ///< proxima.Error (conversions.cpp)
void bind_core(py::module_& m);        ///< Transform, Aabb, enums (bind_core.cpp)
void bind_shapes(py::module_& m);      ///< every 3D shape (bind_shapes.cpp)
void bind_queries(py::module_& m);     ///< intersect, distance, collide, raycast, ... (bind_queries.cpp)
void bind_ccd(py::module_& m);         ///< toi, cast, safe_step (bind_ccd.cpp)
void bind_bounds(py::module_& m);      ///< bounding-volume fitting (bind_bounds.cpp)
void bind_batch(py::module_& m);       ///< batched queries on numpy arrays (bind_batch.cpp)
void bind_broadphase(py::module_& m);  ///< the broad phases (bind_broadphase.cpp)
void bind_world(py::module_& m);       ///< the collision world (bind_world.cpp)
void bind_d2(py::module_& m);          ///< the 2D module, as proxima.d2 (bind_d2.cpp)
void bind_world_d2(py::module_& m);    ///< the 2D collision world, proxima.d2.CollisionWorld (bind_world_d2.cpp)
void bind_render(py::module_& m);      ///< proxima.render, when the tool is built (bind_render.cpp)

/// Sets the Python error indicator to proxima.Error for `error` (no throw).
void set_error(const proxima::Error& error);

}  // namespace proxima::python
