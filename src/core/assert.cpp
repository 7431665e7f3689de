#include <proxima/core/assert.hpp>

#include <cstdio>
#include <cstdlib>

namespace proxima {
namespace {

void default_handler(const char* expression, const char* file, int line) {
  std::fprintf(stderr, "proxima: assertion failed: %s (%s:%d)\n", expression, file, line);
  std::abort();
}

AssertHandler g_handler = &default_handler;

}  // namespace

AssertHandler set_assert_handler(AssertHandler handler) {
  AssertHandler previous = g_handler;
  g_handler = handler != nullptr ? handler : &default_handler;
  return previous;
}

void assert_failed(const char* expression, const char* file, int line) { g_handler(expression, file, line); }

}  // namespace proxima
