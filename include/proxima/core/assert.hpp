#pragma once
/// @file assert.hpp
/// PROXIMA_ASSERT: internal invariant checks, on in debug builds (or with
/// PROXIMA_ENABLE_ASSERTS), routed through a replaceable handler.

namespace proxima {

/// Called when an assertion fails; the default prints the location and aborts.
using AssertHandler = void (*)(const char* expression, const char* file, int line);

/// Installs a new handler (nullptr restores the default) and returns the previous one.
AssertHandler set_assert_handler(AssertHandler handler);

/// Invokes the current handler (used by PROXIMA_ASSERT).
void assert_failed(const char* expression, const char* file, int line);

}  // namespace proxima

#if !defined(NDEBUG) || defined(PROXIMA_ENABLE_ASSERTS)
/// Checks an internal invariant in debug builds.
#define PROXIMA_ASSERT(expr) ((expr) ? static_cast<void>(0) : ::proxima::assert_failed(#expr, __FILE__, __LINE__))
#else
/// Checks an internal invariant in debug builds (compiled out here).
#define PROXIMA_ASSERT(expr) static_cast<void>(0)
#endif
