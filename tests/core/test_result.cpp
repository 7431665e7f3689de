// Result<T>: errors name their field, and value() on an error follows the build's one
// policy (core/result.hpp): BadResultAccess with exceptions, the assert handler and abort
// without them (PROXIMA_EXCEPTIONS=OFF).
#include <gtest/gtest.h>

#include <proxima/core/assert.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>

#include <cstdio>
#include <limits>
#include <string>
#include <utility>

namespace proxima {
namespace test_result {

Result<Transform> bad_position() {
  return Transform::create(Vec3(Real(0), std::numeric_limits<Real>::quiet_NaN(), Real(0)), kIdentityQuat);
}

TEST(Result, HoldsTheValueOrTheError) {
  const Result<Transform> good = Transform::create(Vec3(1, 2, 3), kIdentityQuat);
  ASSERT_TRUE(good.ok());
  EXPECT_TRUE(static_cast<bool>(good));
  EXPECT_EQ(good.value().position, Vec3(1, 2, 3));
  EXPECT_EQ(good->position, Vec3(1, 2, 3));

  const Result<Transform> bad = bad_position();
  ASSERT_FALSE(bad.ok());
  EXPECT_FALSE(static_cast<bool>(bad));
  EXPECT_EQ(bad.error().code, ErrorCode::NotFinite);
  EXPECT_EQ(bad.error().field, "position.y");
  EXPECT_EQ(bad.error().what().rfind("position.y: ", 0), 0u);
}

TEST(Result, ValueMovesOut) {
  Result<std::string> r(std::string("moved"));
  const std::string s = std::move(r).value();
  EXPECT_EQ(s, "moved");
}

#if PROXIMA_EXCEPTIONS

TEST(Result, ValueOnAnErrorThrowsBadResultAccess) {
  Result<Transform> bad = bad_position();
  EXPECT_THROW((void)bad.value(), BadResultAccess);
  EXPECT_THROW((void)std::as_const(bad).value(), BadResultAccess);
  EXPECT_THROW((void)std::move(bad).value(), BadResultAccess);
  try {
    (void)bad_position().value();
    FAIL() << "value() returned on an error";
  } catch (const BadResultAccess& e) {
    EXPECT_EQ(e.error().code, ErrorCode::NotFinite);
    EXPECT_EQ(e.error().field, "position.y");
    EXPECT_EQ(std::string(e.what()).rfind("position.y: ", 0), 0u);
  }
}

#else

// A handler that reports and returns: value() must still not return.
void reporting_handler(const char* expression, const char* /*file*/, int /*line*/) {
  std::fprintf(stderr, "custom handler: %s\n", expression);
}

TEST(ResultDeathTest, ValueOnAnErrorCallsTheAssertHandlerAndAborts) {
  Result<Transform> bad = bad_position();
  EXPECT_DEATH((void)bad.value(), "Result::value\\(\\) on an error \\(not_finite\\): position\\.y: ");
  EXPECT_DEATH((void)std::as_const(bad).value(), "position\\.y");
  EXPECT_DEATH((void)std::move(bad).value(), "position\\.y");
}

TEST(ResultDeathTest, ValueNeverReturnsEvenWhenTheHandlerDoes) {
  const Result<Transform> bad = bad_position();
  EXPECT_DEATH(
      {
        set_assert_handler(&reporting_handler);
        (void)bad.value();
      },
      "custom handler: Result::value\\(\\) on an error \\(not_finite\\): position\\.y: ");
}

#endif

}  // namespace test_result
}  // namespace proxima
