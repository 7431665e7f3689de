#pragma once
/// @file pair_table.hpp
/// Internal: the dispatch machinery of the narrow phase, independent of which shapes exist.
/// A ShapeList names the shape types in the order of their dense type enum; PairTable builds,
/// at compile time, the N x N array whose cell (i, j) is Cell<S_i, S_j>::entry(). The 3D
/// narrow phase instantiates it over its eleven convex shapes, half-space, mesh and compound
/// (dispatch.cpp); a 2D module instantiates it over its own list with its own cells.
#include <array>
#include <cstddef>
#include <tuple>
#include <utility>

namespace proxima::narrow {

/// The shape types of a dispatch table, in the order of their type enum.
template <class... Shapes>
struct ShapeList {
  static constexpr std::size_t size = sizeof...(Shapes);
  template <std::size_t I>
  using At = std::tuple_element_t<I, std::tuple<Shapes...>>;
};

template <class List, template <class, class> class Cell, class Entry, std::size_t... I>
constexpr std::array<Entry, sizeof...(I)> make_pair_cells(std::index_sequence<I...>) {
  constexpr std::size_t n = List::size;
  return {Cell<typename List::template At<I / n>, typename List::template At<I % n>>::entry()...};
}

/// N x N table over List, row-major: cell (i, j) = Cell<At<i>, At<j>>::entry(), all of
/// type Entry; built at compile time, so a lookup is one indexed load.
template <class List, template <class, class> class Cell, class Entry>
inline constexpr std::array<Entry, List::size * List::size> kPairTable =
    make_pair_cells<List, Cell, Entry>(std::make_index_sequence<List::size * List::size>{});

}  // namespace proxima::narrow
