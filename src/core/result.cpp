#include <proxima/core/result.hpp>

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

}  // namespace proxima
