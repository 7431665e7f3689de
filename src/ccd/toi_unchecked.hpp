#pragma once
// Internal: time_of_impact on validated input, with or without the GJK-cast shortcut for
// translating convex pairs (shape_cast falls back to conservative advancement through it
// when its GJK cast cannot decide, so the shortcut must be off there).
#include <proxima/ccd/time_of_impact.hpp>

namespace proxima::detail {

/// time_of_impact without validation; `allow_cast` enables the translating-pair shortcut.
ToiResult time_of_impact_unchecked(ShapeRef a, const Motion& motion_a, ShapeRef b, const Motion& motion_b,
                                   const ToiOptions& options, bool allow_cast);

}  // namespace proxima::detail
