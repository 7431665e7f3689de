#pragma once
/// @file pair_table.hpp
/// Internal: the dispatch machinery of the narrow phase, independent of which shapes exist.
/// A ShapeList names the shape types in the order of their dense type enum; make_pair_row
/// builds, at compile time, row A of the N x N table: the cells Cell<A, S_j>::entry() for
/// every j. The 3D narrow phase builds one row per shape type, each in its own translation
/// unit (dispatch_cells.hpp, dispatch_row.cpp.in); a 2D module does the same over its own
/// list with its own cells.
#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

namespace proxima::narrow {

/// The shape types of a dispatch table, in the order of their type enum.
template <class... Shapes>
struct ShapeList {
  static constexpr std::size_t size = sizeof...(Shapes);
  template <std::size_t I>
  using At = std::tuple_element_t<I, std::tuple<Shapes...>>;
  /// The position of S in the list (its type enum's value).
  template <class S>
  static constexpr std::size_t index_of = [] {
    constexpr bool match[] = {std::is_same_v<S, Shapes>...};
    std::size_t i = 0;
    while (i < size && !match[i]) ++i;
    return i;
  }();
};

template <class List, template <class, class> class Cell, class Entry, class A, std::size_t... J>
constexpr std::array<Entry, sizeof...(J)> make_pair_row(std::index_sequence<J...>) {
  return {Cell<A, typename List::template At<J>>::entry()...};
}

/// Row A of the N x N table over List: cell j = Cell<A, At<j>>::entry(), all of type Entry;
/// built at compile time.
template <class List, template <class, class> class Cell, class Entry, class A>
constexpr std::array<Entry, List::size> make_pair_row() {
  return make_pair_row<List, Cell, Entry, A>(std::make_index_sequence<List::size>{});
}

}  // namespace proxima::narrow
