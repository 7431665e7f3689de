// proxima: the command-line tool (demo, query protocol).
#include <proxima/core/config.hpp>

#include <cstdio>

int main() {
  std::printf("proxima %s (%s precision)\n", PROXIMA_VERSION_STRING, PROXIMA_DOUBLE ? "double" : "float");
  return 0;
}
