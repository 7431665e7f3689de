#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/core/transform.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "support/random.hpp"

namespace proxima {
namespace test_transform {

constexpr Real kTol = sizeof(Real) == 4 ? Real(2e-5) : Real(1e-12);

void expect_near(const Vec3& a, const Vec3& b, Real tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Reference: the rotation matrix written out from the quaternion components (the formula
// of the workload format), independent of GLM's quaternion product.
Vec3 rotate_by_matrix(const Quat& q, const Vec3& v) {
  const Real w = q.w, x = q.x, y = q.y, z = q.z;
  return {(1 - 2 * (y * y + z * z)) * v.x + 2 * (x * y - w * z) * v.y + 2 * (x * z + w * y) * v.z,
          2 * (x * y + w * z) * v.x + (1 - 2 * (x * x + z * z)) * v.y + 2 * (y * z - w * x) * v.z,
          2 * (x * z - w * y) * v.x + 2 * (y * z + w * x) * v.y + (1 - 2 * (x * x + y * y)) * v.z};
}

TEST(Transform, ApplyMatchesRotationMatrixFormula) {
  test::Random rng(1);
  for (int i = 0; i < 2000; ++i) {
    const Transform t = rng.pose(Real(10));
    const Vec3 p = rng.vec3(Real(-5), Real(5));
    expect_near(t.apply(p), rotate_by_matrix(t.rotation, p) + t.position, kTol * 20);
    expect_near(t.apply_vector(p), rotate_by_matrix(t.rotation, p), kTol * 10);
  }
}

TEST(Transform, InverseUndoesApply) {
  test::Random rng(2);
  for (int i = 0; i < 2000; ++i) {
    const Transform t = rng.pose(Real(100));
    const Vec3 p = rng.vec3(Real(-50), Real(50));
    expect_near(t.inverse_apply(t.apply(p)), p, kTol * 200);
    expect_near(t.inverse().apply(t.apply(p)), p, kTol * 200);
    expect_near(t.inverse_apply_vector(t.apply_vector(p)), p, kTol * 100);
  }
}

TEST(Transform, CompositionAppliesRightThenLeft) {
  test::Random rng(3);
  for (int i = 0; i < 2000; ++i) {
    const Transform a = rng.pose(Real(10));
    const Transform b = rng.pose(Real(10));
    const Vec3 p = rng.vec3(Real(-5), Real(5));
    expect_near((a * b).apply(p), a.apply(b.apply(p)), kTol * 100);
    expect_near(relative(a, b).apply(p), a.inverse_apply(b.apply(p)), kTol * 100);
  }
}

TEST(Transform, RotationMatrixColumnsAreLocalAxes) {
  const Transform t{Vec3(0), glm::angleAxis(kPi / 2, Vec3(0, 0, 1))};
  const Mat3 m = t.rotation_matrix();
  expect_near(m[0], Vec3(0, 1, 0), kTol);
  expect_near(m[1], Vec3(-1, 0, 0), kTol);
  expect_near(t.apply(Vec3(1, 0, 0)), Vec3(0, 1, 0), kTol);
}

TEST(Transform, CreateValidates) {
  test::ScopedNoFpTraps no_traps;
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  auto bad_pos = Transform::create(Vec3(0, nan, 0), kIdentityQuat);
  ASSERT_FALSE(bad_pos.ok());
  EXPECT_EQ(bad_pos.error().field, "position.y");
  EXPECT_EQ(bad_pos.error().code, ErrorCode::NotFinite);
  auto bad_rot = Transform::create(Vec3(0), Quat(2, 0, 0, 0));
  ASSERT_FALSE(bad_rot.ok());
  EXPECT_EQ(bad_rot.error().field, "rotation");
  auto nan_rot = Transform::create(Vec3(0), Quat(nan, 0, 0, 0));
  ASSERT_FALSE(nan_rot.ok());
  EXPECT_EQ(nan_rot.error().code, ErrorCode::NotFinite);
  auto ok = Transform::create(Vec3(1, 2, 3), Quat(Real(1.0002), 0, 0, 0));
  ASSERT_TRUE(ok.ok());
  EXPECT_NEAR(glm::length(ok->rotation), Real(1), kTol);
#if PROXIMA_EXCEPTIONS
  EXPECT_THROW((void)bad_rot.value(), BadResultAccess);
#endif
}

// from_values against its definition: accepted exactly when every position component is finite
// with |x| <= kMaxCoordinate and the quaternion is finite with length within 1e-3 of 1 (checked
// here component by component, in long double), and then equal bit for bit to
// glm::normalize's answer; over random values near and across both limits, NaNs and infinities.
TEST(Transform, FromValuesAcceptsWhatCreateAcceptsAndNormalisesAsGlm) {
  test::ScopedNoFpTraps no_traps;
  test::Random rng(20261127);
  const Real specials[] = {std::numeric_limits<Real>::quiet_NaN(), std::numeric_limits<Real>::infinity(),
                           -std::numeric_limits<Real>::infinity(), kMaxCoordinate,
                           std::nextafter(kMaxCoordinate, std::numeric_limits<Real>::infinity())};
  int accepted = 0, rejected = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3 p = rng.vec3(-10, 10);
    Quat q = glm::normalize(Quat(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    q = q * (Real(1) + rng.uniform(Real(-2.5e-3), Real(2.5e-3)));  // about half of them outside the 1e-3 band
    if (i % 10 == 0) p[i / 10 % 3] = specials[i / 30 % 5];
    if (i % 10 == 1) q[i / 10 % 4] = specials[i / 40 % 3];
    const long double len2 =
        (long double)q.w * q.w + (long double)q.x * q.x + (long double)q.y * q.y + (long double)q.z * q.z;
    bool position_ok = true;
    for (int k = 0; k < 3; ++k) position_ok = position_ok && std::isfinite(p[k]) && std::abs(p[k]) <= kMaxCoordinate;
    const bool quat_ok = std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) &&
                         std::isfinite(len2) && std::abs(std::sqrt(len2) - 1.0L) <= 1e-3L;
    const std::optional<Transform> t = Transform::from_values(p, q);
    const bool near_band = std::isfinite(len2) && std::abs(std::abs(std::sqrt(len2) - 1.0L) - 1e-3L) < 1e-6L;
    if (!near_band) {  // within a rounding of the band's edge either answer is right
      EXPECT_EQ(t.has_value(), position_ok && quat_ok) << i;
    }
    EXPECT_EQ(t.has_value(), Transform::create(p, q).ok()) << i;
    if (!t) {
      ++rejected;
      continue;
    }
    ++accepted;
    const Quat n = glm::normalize(q);
    EXPECT_EQ(std::memcmp(&t->rotation, &n, sizeof n), 0) << i;
    EXPECT_EQ(std::memcmp(&t->position, &p, sizeof p), 0) << i;
  }
  EXPECT_GT(accepted, 5000);
  EXPECT_GT(rejected, 5000);
}

TEST(Tolerance, ScalesWithPrecision) {
  EXPECT_GT(kRelativeTolerance, kEpsilon);
  EXPECT_LT(kRelativeTolerance, Real(1e-4));
  EXPECT_EQ(linear_tolerance(Real(0.001)), kRelativeTolerance);
  EXPECT_EQ(linear_tolerance(Real(1000)), kRelativeTolerance * 1000);
}

}  // namespace test_transform
}  // namespace proxima
