// The capture format's JSON text: numbers read back to the same value (std::from_chars is
// the reference), strings escape what JSON requires, base64 matches RFC 4648's vectors.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "debug/json_text.hpp"

namespace proxima::test_json_text {

TEST(JsonText, RealsReadBackExactly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> exponent(-30, 30);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  for (int i = 0; i < 2000; ++i) {
    const Real value = static_cast<Real>(mantissa(rng) * std::pow(10.0, exponent(rng)));
    std::string text;
    debug::json::real(text, value);
    Real back = 0;
    const auto result = std::from_chars(text.data(), text.data() + text.size(), back);
    ASSERT_EQ(result.ec, std::errc()) << text;
    ASSERT_EQ(back, value) << text;
  }
  std::string special;
  debug::json::real(special, std::numeric_limits<Real>::infinity());
  special += ' ';
  debug::json::real(special, Real(-0.0));
  EXPECT_EQ(special, "null 0");
}

TEST(JsonText, StringsEscapeQuotesBackslashesAndControls) {
  std::string out;
  debug::json::string(out, std::string("a\"b\\c\n\x01 \xc3\xa9"));
  EXPECT_EQ(out, "\"a\\\"b\\\\c\\u000a\\u0001 \xc3\xa9\"");
}

TEST(JsonText, Base64MatchesRfc4648) {
  EXPECT_EQ(debug::json::base64(""), "");
  EXPECT_EQ(debug::json::base64("f"), "Zg==");
  EXPECT_EQ(debug::json::base64("fo"), "Zm8=");
  EXPECT_EQ(debug::json::base64("foo"), "Zm9v");
  EXPECT_EQ(debug::json::base64("foob"), "Zm9vYg==");
  EXPECT_EQ(debug::json::base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(debug::json::base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(debug::json::base64(std::string("\xff\x00\xfe", 3)), "/wD+");
}

}  // namespace proxima::test_json_text
