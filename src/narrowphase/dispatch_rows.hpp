#pragma once
/// @file dispatch_rows.hpp
/// Internal: the rows of the narrow phase's 13 x 13 dispatch table. Row A holds the cells
/// (A, B) for every B in ShapeType order. Each row is defined in its own translation unit,
/// generated from dispatch_row.cpp.in, so that the templates of the 121 convex pairs compile
/// in parallel rather than in one file; dispatch.cpp gathers the rows' addresses.
#include <proxima/shapes/shape.hpp>

#include <array>

#include "dispatch.hpp"
#include "pair_table.hpp"

namespace proxima::narrow {

/// Every shape type, in ShapeType order.
using Shapes3 = ShapeList<Point, Segment, Triangle, Sphere, Capsule, Box, Cylinder, Cone, Ellipsoid, ConvexHull,
                          HalfSpace, TriangleMesh, Compound>;
static_assert(Shapes3::size == static_cast<std::size_t>(kShapeTypeCount));

/// Row A of the dispatch table: `cells[j]` answers the pair (A, shape type j).
template <class A>
struct PairRow {
  static const std::array<PairFunctions, Shapes3::size> cells;
};

// Declarations of the rows defined in the generated dispatch_row_<shape>.cpp files.
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Point>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Segment>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Triangle>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Sphere>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Capsule>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Box>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Cylinder>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Cone>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Ellipsoid>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<ConvexHull>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<HalfSpace>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<TriangleMesh>::cells;
template <>
const std::array<PairFunctions, Shapes3::size> PairRow<Compound>::cells;

/// The cell (A, B) of the table; a mirrored cell (B, A) of row B calls it.
template <class A, class B>
const PairFunctions& cell_of() noexcept {
  return PairRow<A>::cells[Shapes3::index_of<B>];
}

}  // namespace proxima::narrow
