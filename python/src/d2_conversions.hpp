#pragma once
/// @file d2_conversions.hpp
/// Conversions of the 2D bindings (bind_d2.cpp defines them; bind_world_d2.cpp uses them
/// too): 2D vectors, poses (x, y, angle in radians) and point arrays from Python, vectors to
/// numpy, and shape arguments; proxima.Error names the field.
#include <proxima/d2/shape.hpp>

#include <vector>

#include "conversions.hpp"

namespace proxima::python {

/// A 2D vector from any sequence of 2 finite numbers, else proxima.Error naming `field`.
d2::Vec2 to_vec2(py::handle value, const char* field);
/// A new float64 numpy array of shape (2,).
py::array_t<double> to_numpy2(const d2::Vec2& v);
/// A 2D pose from None (identity) or (x, y, angle); proxima.Error names `field`.<part>.
d2::Pose to_pose2(py::handle value, const char* field);
/// Points from an (N, 2) array-like, else proxima.Error naming `field`.
std::vector<d2::Vec2> to_points2(py::handle value, const char* field);
/// The proxima.d2.Shape `value`, else proxima.Error naming `field`.
const d2::Shape& to_shape2(py::handle value, const char* field);

}  // namespace proxima::python
