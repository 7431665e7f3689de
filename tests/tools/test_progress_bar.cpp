// Progress bars: the line's format, and silence when disabled (standard error not a
// terminal: a pipe or a file gets nothing).
#include <gtest/gtest.h>

#include <sstream>

#include "progress_bar.hpp"

namespace proxima::test_progress_bar {

TEST(ProgressBar, LineShowsTheFractionDone) {
  EXPECT_EQ(tool::progress_line(0, 10, "frames", 10), "\r[          ] 0/10 frames");
  EXPECT_EQ(tool::progress_line(5, 10, "frames", 10), "\r[#####     ] 5/10 frames");
  EXPECT_EQ(tool::progress_line(10, 10, "steps", 4), "\r[####] 10/10 steps");
  EXPECT_EQ(tool::progress_line(12, 10, "x", 4), "\r[####] 12/10 x");  // never past full
  EXPECT_EQ(tool::progress_line(0, 0, "x", 3), "\r[###] 0/0 x");
}

TEST(ProgressBar, SilentWhenDisabled) {
  std::ostringstream out;
  tool::ProgressBar bar(out, false, 3, "frames");
  for (std::size_t i = 1; i <= 3; ++i) bar.update(i);
  EXPECT_TRUE(out.str().empty());
}

TEST(ProgressBar, RedrawsOnlyOnChangeAndEndsWithANewline) {
  std::ostringstream out;
  tool::ProgressBar bar(out, true, 2, "frames");
  bar.update(1);
  bar.update(1);
  bar.update(2);
  EXPECT_EQ(out.str(), tool::progress_line(1, 2, "frames") + tool::progress_line(2, 2, "frames") + "\n");
}

}  // namespace proxima::test_progress_bar
