/// @file dispatch.cpp
/// The dispatch table of the narrow phase: one cell per ordered pair of ShapeTypes. The rows
/// are built at compile time, each in its own generated file (dispatch_rows.hpp,
/// dispatch_cells.hpp); here the table of their addresses, so that a lookup is two loads.
#include "dispatch.hpp"

#include <proxima/core/assert.hpp>

#include <array>
#include <cstddef>
#include <utility>

#include "dispatch_rows.hpp"

namespace proxima::narrow {

namespace {

template <std::size_t... I>
constexpr std::array<const PairFunctions*, sizeof...(I)> row_addresses(std::index_sequence<I...>) {
  return {PairRow<typename Shapes3::template At<I>>::cells.data()...};
}

constinit const std::array<const PairFunctions*, Shapes3::size> kRows =
    row_addresses(std::make_index_sequence<Shapes3::size>{});

}  // namespace

const PairFunctions& pair_functions(ShapeType a, ShapeType b) noexcept {
  const auto ia = static_cast<std::size_t>(a);
  const auto ib = static_cast<std::size_t>(b);
  PROXIMA_ASSERT(ia < Shapes3::size && ib < Shapes3::size);
  return kRows[ia][ib];
}

}  // namespace proxima::narrow
