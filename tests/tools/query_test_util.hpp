#pragma once
// Helpers shared by the in-process query-protocol tests: a request answered through the
// protocol, 3-vectors in double, and the rotation matrix of an [x, y, z, w] quaternion written
// out independently of GLM (the reference the tests compare the tool's answers with).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "query.hpp"

namespace proxima::test {

using Json = tool::Json;
using D3 = std::array<double, 3>;

/// Answers one request through the protocol and checks whether it was rejected as expected.
inline Json answer(const Json& request, bool expect_ok = true) {
  bool rejected = false;
  Json a = tool::answer_request(request, rejected);
  EXPECT_EQ(rejected, !expect_ok) << request.dump() << " -> " << a.dump();
  return a;
}

inline D3 d3(const Json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }
inline Json js(const D3& v) { return Json::array({v[0], v[1], v[2]}); }
inline double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline D3 add(const D3& a, const D3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline D3 scale(const D3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double norm(const D3& a) { return std::sqrt(dot(a, a)); }

// Rotation matrix (row-major) of the unit quaternion [x, y, z, w].
struct Rot {
  double m[3][3];
  static Rot from_xyzw(double x, double y, double z, double w) {
    const double n = std::sqrt(x * x + y * y + z * z + w * w);
    x /= n, y /= n, z /= n, w /= n;
    return Rot{{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
  }
  D3 apply(const D3& v) const {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
  }
  D3 apply_inverse(const D3& v) const {
    return {m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2], m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
            m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2]};
  }
  D3 column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
};

}  // namespace proxima::test
