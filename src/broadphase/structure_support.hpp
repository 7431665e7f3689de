#pragma once
/// @file structure_support.hpp
/// Internal helpers the broad-phase structures' sources share: a pair of ids in the order
/// ProxyPair keeps (lo < hi) and the bytes a vector holds reserved (memory_bytes()).

#include <proxima/broadphase/broadphase.hpp>

#include <cstddef>
#include <vector>

namespace proxima::detail {

/// The pair of two distinct ids, the smaller first (ProxyPair's order).
inline ProxyPair ordered_pair(ProxyId a, ProxyId b) { return a < b ? ProxyPair{a, b} : ProxyPair{b, a}; }

/// Bytes a vector has reserved (its capacity, not its size), for memory_bytes().
template <class T>
std::size_t capacity_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace proxima::detail
