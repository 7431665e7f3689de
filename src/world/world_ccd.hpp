#pragma once
// Internal: the continuous-detection pass of CollisionWorld::step (world_ccd.cpp).
#include <proxima/ccd/motion.hpp>

#include "world/world_state.hpp"

namespace proxima::detail {

/// Step 5 of the step: impacts of the fast objects moved since the last step, and the
/// sensors they cross, swept on `executor` (the calling thread when a pair filter is set);
/// appends to w.events in the serial order (sorted later by the step).
void continuous_pass(CollisionWorld::Impl& w, const CollisionWorld& world, Executor& executor);

/// True when object `s`, moving along `motion`, is fast for `safety_factor`: a point of it
/// may move farther than safety_factor times its thinnest extent.
bool is_fast(const ObjectSlot& s, const Motion& motion, Real safety_factor);

}  // namespace proxima::detail
