// GoogleTest entry point for every Proxima test executable. It turns on the
// floating-point "invalid operation" trap so that any NaN produced by the library
// (0/0, inf - inf, sqrt(-1), 0 * inf) stops the test at the faulty instruction.
#include <gtest/gtest.h>

#include <cfenv>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
#if defined(__GLIBC__) && !defined(PROXIMA_NO_FP_TRAPS)
  feenableexcept(FE_INVALID);
#endif
  return RUN_ALL_TESTS();
}
