#pragma once
// Comparison of protocol answers with expected answers: same members, numbers within a
// relative tolerance that scales with Real, strings equal (an expected string starting with
// '~' only has to occur in the actual one).
#include <gtest/gtest.h>

#include <proxima/core/math.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace proxima::test {

/// Relative tolerance for numbers that went through Real arithmetic.
inline constexpr double kJsonTolerance = sizeof(Real) == 4 ? 2e-5 : 1e-11;

/// Adds a failure (with `where` as context) for every difference between actual and expected;
/// numbers may differ by `tolerance` relative to max(1, |expected|).
inline void expect_json_near(const nlohmann::ordered_json& actual, const nlohmann::ordered_json& expected,
                             const std::string& where, double tolerance = kJsonTolerance) {
  if (expected.is_number()) {
    ASSERT_TRUE(actual.is_number()) << where << ": expected a number, got " << actual.dump();
    const double a = actual.get<double>();
    const double e = expected.get<double>();
    EXPECT_LE(std::abs(a - e), tolerance * std::max(1.0, std::abs(e))) << where << ": " << a << " vs " << e;
  } else if (expected.is_string()) {
    ASSERT_TRUE(actual.is_string()) << where << ": expected a string, got " << actual.dump();
    const std::string e = expected.get<std::string>();
    const std::string a = actual.get<std::string>();
    if (!e.empty() && e.front() == '~') {
      EXPECT_NE(a.find(e.substr(1)), std::string::npos) << where << ": \"" << a << "\" lacks \"" << e.substr(1) << "\"";
    } else {
      EXPECT_EQ(a, e) << where;
    }
  } else if (expected.is_array()) {
    ASSERT_TRUE(actual.is_array()) << where << ": expected an array, got " << actual.dump();
    ASSERT_EQ(actual.size(), expected.size()) << where;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      expect_json_near(actual[i], expected[i], where + "[" + std::to_string(i) + "]", tolerance);
    }
  } else if (expected.is_object()) {
    ASSERT_TRUE(actual.is_object()) << where << ": expected an object, got " << actual.dump();
    for (auto it = expected.begin(); it != expected.end(); ++it) {
      ASSERT_TRUE(actual.contains(it.key())) << where << ": missing \"" << it.key() << "\" in " << actual.dump();
      expect_json_near(actual[it.key()], it.value(), where + "." + it.key(), tolerance);
    }
    for (auto it = actual.begin(); it != actual.end(); ++it) {
      EXPECT_TRUE(expected.contains(it.key())) << where << ": unexpected \"" << it.key() << "\" in " << actual.dump();
    }
  } else {
    EXPECT_EQ(actual, expected) << where;
  }
}

}  // namespace proxima::test
