#pragma once
// The protocol's names of the narrow phase's statuses and methods, shared by the 3D and 2D
// pair operations.
#include <proxima/narrowphase/contact.hpp>

namespace proxima::tool {

/// "separated", "touching", "penetrating", "max_iterations", "degenerate", "invalid_input".
inline const char* status_name(PairStatus status) {
  switch (status) {
    case PairStatus::Separated: return "separated";
    case PairStatus::Touching: return "touching";
    case PairStatus::Penetrating: return "penetrating";
    case PairStatus::MaxIterations: return "max_iterations";
    case PairStatus::Degenerate: return "degenerate";
    case PairStatus::InvalidInput: return "invalid_input";
  }
  return "unknown";
}

/// "analytic", "gjk", "epa", "sat", "support", "closest_point".
inline const char* method_name(PairMethod method) {
  switch (method) {
    case PairMethod::Analytic: return "analytic";
    case PairMethod::Gjk: return "gjk";
    case PairMethod::Epa: return "epa";
    case PairMethod::Sat: return "sat";
    case PairMethod::Support: return "support";
    case PairMethod::ClosestPoint: return "closest_point";
  }
  return "unknown";
}

}  // namespace proxima::tool
