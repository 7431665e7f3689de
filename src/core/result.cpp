#include <proxima/core/assert.hpp>
#include <proxima/core/result.hpp>

#include <cstdlib>
#include <string>

#if PROXIMA_EXCEPTIONS && defined(__GNUC__) && !defined(__cpp_exceptions)
#error "Proxima is configured with exceptions but compiled without them: configure with -DPROXIMA_EXCEPTIONS=OFF"
#endif

namespace proxima {

const char* to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::NotFinite: return "not_finite";
    case ErrorCode::NonPositive: return "non_positive";
    case ErrorCode::Negative: return "negative";
    case ErrorCode::OutOfRange: return "out_of_range";
    case ErrorCode::Degenerate: return "degenerate";
    case ErrorCode::TooFew: return "too_few";
    case ErrorCode::InvalidArgument: return "invalid_argument";
    case ErrorCode::Internal: return "internal";
  }
  return "unknown";
}

namespace detail {

void bad_result_access(const Error& error) {
#if PROXIMA_EXCEPTIONS
  throw BadResultAccess(error);
#else
  const std::string text = std::string("Result::value() on an error (") + to_string(error.code) + "): " + error.what();
  assert_failed(text.c_str(), __FILE__, __LINE__);
  std::abort();  // the handler returned: value() has no value to give
#endif
}

}  // namespace detail

}  // namespace proxima
