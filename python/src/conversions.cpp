#include "conversions.hpp"

#include <proxima/core/validate.hpp>

#include <cmath>
#include <thread>

#include "module_parts.hpp"

namespace proxima::python {
namespace {

// proxima.Error, created once by bind_errors; a borrowed handle that outlives the module's
// teardown on purpose (never decremented at exit).
py::handle error_type;

}  // namespace

std::vector<double> to_numbers(py::handle value, std::size_t size, const char* field) {
  if (!py::isinstance<py::sequence>(value) && !py::isinstance<py::array>(value)) {
    raise_argument_error(field, "expected a sequence of " + std::to_string(size) + " numbers");
  }
  py::array_t<double, py::array::forcecast> array;
  try {
    array = py::array_t<double, py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!array || array.ndim() != 1 || static_cast<std::size_t>(array.shape(0)) != size) {
    raise_argument_error(field, "expected a sequence of " + std::to_string(size) + " numbers");
  }
  std::vector<double> out(size);
  for (std::size_t i = 0; i < size; ++i) {
    out[i] = array.at(static_cast<py::ssize_t>(i));
    if (!std::isfinite(out[i])) raise_argument_error(field, "must be finite");
  }
  return out;
}

std::vector<Vec3> to_points(py::handle value, const char* field) {
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!a || a.ndim() != 2 || a.shape(1) != 3) raise_argument_error(field, "expected an (N, 3) array of numbers");
  std::vector<Vec3> points(static_cast<std::size_t>(a.shape(0)));
  const double* d = a.data();
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = Vec3(Real(d[3 * i]), Real(d[3 * i + 1]), Real(d[3 * i + 2]));
  return points;
}

void set_error(const Error& error) {
  py::object instance = error_type(error.what());
  instance.attr("code") = to_string(error.code);
  instance.attr("field") = error.field;
  instance.attr("message") = error.message;
  PyErr_SetObject(error_type.ptr(), instance.ptr());
}

void raise_error(const Error& error) {
  set_error(error);
  throw py::error_already_set();
}

void raise_argument_error(const std::string& field, const std::string& message) {
  raise_error(make_error(ErrorCode::InvalidArgument, field, message));
}

Vec3 to_vec3(py::handle value, const char* field) {
  const std::vector<double> v = to_numbers(value, 3, field);
  return {Real(v[0]), Real(v[1]), Real(v[2])};
}

Quat to_quat(py::handle value, const char* field) {
  const std::vector<double> v = to_numbers(value, 4, field);
  return Quat(Real(v[3]), Real(v[0]), Real(v[1]), Real(v[2]));  // GLM: (w, x, y, z)
}

Real to_real(py::handle value, const char* field) {
  double x = 0;
  try {
    x = value.cast<double>();
  } catch (const py::cast_error&) {
    raise_argument_error(field, "expected a number");
  }
  if (std::isnan(x)) raise_argument_error(field, "must not be NaN");
  return Real(x);
}

py::array_t<double> to_numpy(const Vec3& v) {
  py::array_t<double> out(3);
  double* d = out.mutable_data();
  for (int i = 0; i < 3; ++i) d[i] = double(v[i]);
  return out;
}

py::array_t<double> to_numpy(const Quat& q) {
  py::array_t<double> out(4);
  double* d = out.mutable_data();
  d[0] = double(q.x);
  d[1] = double(q.y);
  d[2] = double(q.z);
  d[3] = double(q.w);
  return out;
}

std::size_t resolve_threads(long threads) {
  if (threads < 0) raise_argument_error("threads", "must be >= 0 (0: every hardware thread)");
  if (threads == 0) return std::max(1u, std::thread::hardware_concurrency());
  return static_cast<std::size_t>(threads);
}

void bind_errors(py::module_& m) {
  py::object type = py::reinterpret_steal<py::object>(
      PyErr_NewExceptionWithDoc("proxima.Error",
                                "An input the library rejected. Attributes: code (the kind of problem, e.g. "
                                "'not_finite'), field (the argument or field at fault, e.g. 'radius' or "
                                "'rays[3].direction'), message.",
                                PyExc_ValueError, nullptr));
  m.attr("Error") = type;
  error_type = type.release();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const BadResultAccess& e) {
      set_error(e.error());
    }
  });
}

}  // namespace proxima::python

namespace proxima::python {

Transform to_transform(py::handle value, const char* field) {
  if (value.is_none()) return Transform::identity();
  if (py::isinstance<Transform>(value)) return value.cast<Transform>();
  const std::vector<double> v = to_numbers(value, 7, field);
  const Vec3 position{Real(v[0]), Real(v[1]), Real(v[2])};
  const Quat rotation{Real(v[6]), Real(v[3]), Real(v[4]), Real(v[5])};
  Result<Transform> pose = Transform::create(position, rotation);
  if (!pose.ok()) {
    Error e = pose.error();
    e.field = std::string(field) + "." + e.field;
    raise_error(e);
  }
  return *pose;
}

}  // namespace proxima::python
