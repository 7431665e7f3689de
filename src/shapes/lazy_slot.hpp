#pragma once
/// @file lazy_slot.hpp
/// LazySlot<T> (internal): data derived from an immutable object, built at most once, on
/// first use, under std::call_once, so that one shared object may be queried from many
/// threads. A copy starts empty, never sharing the source's data: a TriangleMesh copies its
/// data for a mesh whose vertices then change (TriangleMesh::deformed), which must build
/// its own.

#include <memory>
#include <mutex>

namespace proxima::detail {

/// A value of T built by the first get(); T may be incomplete where the slot is declared.
template <class T>
class LazySlot {
 public:
  /// An empty slot.
  LazySlot() = default;
  /// An empty slot (the source's value is not copied).
  LazySlot(const LazySlot& /*unused*/) {}
  LazySlot& operator=(const LazySlot&) = delete;

  /// The value, built by `build()` (returning a T) on the first call only; concurrent first
  /// calls wait for the one build.
  template <class Build>
  const T& get(Build&& build) const {
    std::call_once(once_, [&] { value_ = std::make_shared<const T>(build()); });
    return *value_;
  }

 private:
  mutable std::once_flag once_;
  mutable std::shared_ptr<const T> value_;
};

}  // namespace proxima::detail
