#pragma once
/// @file pairs_polyhedral.hpp
/// Declarations of the closed-form pair routines of this group (contract in pair_support.hpp):
/// for each pair (A, B), A not after B in ShapeType order, the three functions pair_intersect,
/// pair_distance, pair_collide and the trait kAnalyticPair<A, B> = true.

#include <proxima/shapes/shape.hpp>

#include "pair_support.hpp"

namespace proxima::narrow {}  // namespace proxima::narrow
