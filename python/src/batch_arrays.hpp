#pragma once
/// @file batch_arrays.hpp
/// What the batched calls share: rows read straight from a caller's numpy array (float32 or
/// float64, any strides: no copy), poses validated before any work, output rows as numpy
/// structured dtypes written in place (into `out=` when given), and the work spread over a
/// thread pool with the GIL released.
#include <proxima/core/executor.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "conversions.hpp"

namespace proxima::python {

/// Rows of `cols` numbers in a caller's array, read in place.
class RowReader {
 public:
  /// Checks that `value` is an (N, cols) array (or, with `allow_single`, one row of `cols`
  /// numbers broadcast to every row); float32 and float64 are read in place, anything else
  /// is converted to float64 once. proxima.Error names `field`.
  RowReader(py::handle value, py::ssize_t cols, const char* field, bool allow_single);
  /// Number of rows; 0 for a broadcast single row (see single()).
  py::ssize_t rows() const { return single_ ? 0 : rows_; }
  /// True for one row broadcast to every row.
  bool single() const { return single_; }
  /// Calls accept(i, number) for rows i = begin, begin + 1, … end - 1, where number(j) is the
  /// row's number j as a Real, until accept returns false; returns that row's index, or -1 when
  /// every row was accepted. The element type is chosen once, so the loop reads by plain
  /// pointer arithmetic.
  template <class F>
  py::ssize_t find_rejected(py::ssize_t begin, py::ssize_t end, F&& accept) const {
    return f64_ ? find_rejected_as<double>(begin, end, accept) : find_rejected_as<float>(begin, end, accept);
  }
  /// Number j of row i (row 0 when single).
  double at(py::ssize_t i, py::ssize_t j) const {
    const char* p = data_ + (single_ ? 0 : i * row_stride_) + j * col_stride_;
    return f64_ ? *reinterpret_cast<const double*>(p) : double(*reinterpret_cast<const float*>(p));
  }

 private:
  template <class T, class F>
  py::ssize_t find_rejected_as(py::ssize_t begin, py::ssize_t end, F& accept) const {
    const py::ssize_t row_stride = single_ ? 0 : row_stride_;
    for (py::ssize_t i = begin; i < end; ++i) {
      const char* row = data_ + i * row_stride;
      const auto number = [&](int j) { return Real(*reinterpret_cast<const T*>(row + j * col_stride_)); };
      if (!accept(i, number)) return i;
    }
    return -1;
  }

  py::array array_;  // keeps the caller's buffer (or the converted copy) alive
  const char* data_ = nullptr;
  py::ssize_t rows_ = 0, row_stride_ = 0, col_stride_ = 0;
  bool f64_ = true, single_ = false;
};

/// The row count shared by the batch's arrays (broadcast single rows fit any), else
/// proxima.Error naming the second array.
py::ssize_t common_rows(const RowReader& a, const char* field_a, const RowReader& b, const char* field_b);

/// Poses (px, py, pz, qx, qy, qz, qw) of every row, validated: a non-finite number or a
/// quaternion that is not unit (within 1e-3) raises proxima.Error naming "field[i]".
std::vector<Transform> read_poses(const RowReader& rows, py::ssize_t n, const char* field);

/// max_t of a batch of n rays: None (unbounded: one infinity), one number (one value for
/// every ray), or a 1-D array of n numbers; anything else raises proxima.Error naming
/// "max_t". Values are not checked here (the caller names the bad ray).
std::vector<double> read_limits(py::handle max_t, py::ssize_t n);

/// The points of an (N, 3) array (world frame); a non-finite number raises proxima.Error
/// naming "points[i]".
std::vector<Vec3> read_points(py::handle points);

/// A thread pool of `threads` threads, made on first use and kept; a forked child
/// (multiprocessing) makes its own, since a parent's threads do not exist in it.
Executor& thread_pool(std::size_t threads);

/// Calls task(begin, end) over [0, n) with the GIL released, on the calling thread when
/// threads resolves to 1 or n is small, else on a thread pool of that many threads.
void parallel_for(std::size_t n, long threads, RangeTask task);

/// `out` when given (a C-contiguous, writable array of dtype T and length n, else
/// proxima.Error naming "out"), else a new array.
template <class T>
py::array_t<T> output_array(py::handle out, py::ssize_t n) {
  if (out.is_none()) return py::array_t<T>(n);
  if (!py::isinstance<py::array>(out)) raise_argument_error("out", "expected a numpy array");
  py::array a = py::reinterpret_borrow<py::array>(out);
  const bool ok = a.dtype().equal(py::dtype::of<T>()) && a.ndim() == 1 && a.shape(0) == n &&
                  (a.flags() & py::array::c_style) && a.writeable();
  if (!ok) {
    raise_argument_error("out", "expected a writable, contiguous array of " + std::to_string(n) + " items of dtype " +
                                    std::string(py::str(py::dtype::of<T>())));
  }
  return py::reinterpret_borrow<py::array_t<T>>(out);
}

/// Row of distance_batch's answer (dtype proxima.DISTANCE_DTYPE).
struct DistanceRow {
  double signed_distance;  ///< > 0 gap, < 0 penetration
  double point_a[3];       ///< witness on A, world frame
  double point_b[3];       ///< witness on B
  double normal[3];        ///< unit, A to B
  std::uint8_t status;     ///< proxima.PairStatus value
};

/// Row of raycast_batch's answer (dtype proxima.RAY_HIT_DTYPE).
struct RayHitRow {
  bool hit;           ///< true when the ray hit within max_t
  double t;           ///< ray parameter (units of the direction's length); max_t on a miss
  double point[3];    ///< hit point, world frame
  double normal[3];   ///< unit outward normal at the hit
  std::int64_t part;  ///< mesh triangle or compound child hit, -1 for none
};

/// Row of closest_point_batch's answer (dtype proxima.SURFACE_POINT_DTYPE).
struct SurfacePointRow {
  double point[3];         ///< nearest surface point, world frame
  double normal[3];        ///< unit outward normal there
  double signed_distance;  ///< > 0 outside, < 0 inside
};

}  // namespace proxima::python
