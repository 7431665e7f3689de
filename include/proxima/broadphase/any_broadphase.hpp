#pragma once
/// @file any_broadphase.hpp
/// AnyBroadPhase: a type-erased broad phase (one virtual call per operation, never per
/// element) for the CLI, benchmarks and applications that pick a structure at run time. It is
/// the one place where query callbacks are type-erased (FunctionRef: one indirect call per
/// reported proxy); the concrete structures call their callable directly.
/// It wraps any BroadPhaseStructure, forwards every call, and holds a PairTracker so
/// `update_pairs()` returns the pairs begun and ended since its previous call.
/// `make_broadphase(name)` builds one by name from the registry (broadphase_registry.cpp);
/// `broadphase_names()` lists the names. AnyBroadPhase itself satisfies BroadPhaseStructure.

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/core/result.hpp>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace proxima {

/// Type-erased broad phase (see the file comment). Not copyable.
class AnyBroadPhase {
 public:
  AnyBroadPhase() = default;
  AnyBroadPhase(const AnyBroadPhase&) = delete;
  AnyBroadPhase& operator=(const AnyBroadPhase&) = delete;
  virtual ~AnyBroadPhase() = default;

  /// Registry name of the wrapped structure ("sap", "tree", ...).
  virtual std::string_view name() const = 0;
  /// True when find_pairs(out, executor) really runs on the executor.
  virtual bool parallel() const = 0;

  /// As BroadPhaseStructure::insert.
  virtual BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {}) = 0;
  /// As BroadPhaseStructure::remove.
  virtual BroadPhaseStatus remove(ProxyId id) = 0;
  /// As BroadPhaseStructure::update (one proxy).
  virtual BroadPhaseStatus update(ProxyId id, const Aabb& box) = 0;
  /// As BroadPhaseStructure::update (batch, all or nothing).
  virtual BroadPhaseStatus update(std::span<const ProxyUpdate> updates) = 0;
  /// As BroadPhaseStructure::rebuild.
  virtual void rebuild() = 0;
  /// Every pair, sorted; on `executor` where the structure supports it (parallel()), else
  /// serially on the calling thread. Identical output either way.
  virtual void find_pairs(std::vector<ProxyPair>& out, Executor& executor) = 0;
  /// Every pair, sorted, on the calling thread.
  void find_pairs(std::vector<ProxyPair>& out) { find_pairs(out, serial_executor()); }
  /// As BroadPhaseStructure::query_aabb; returns the query's counters.
  virtual BroadPhaseStats query_aabb(const Aabb& box, OverlapQueryCallback on_overlap) const = 0;
  /// As BroadPhaseStructure::query_point; returns the query's counters.
  virtual BroadPhaseStats query_point(const Vec3& point, OverlapQueryCallback on_overlap) const = 0;
  /// As BroadPhaseStructure::query_ray; returns the query's counters.
  virtual BroadPhaseStats query_ray(const Ray& ray, Real max_t, RayQueryCallback on_ray) const = 0;
  /// As BroadPhaseStructure::validate.
  virtual bool validate() const = 0;
  /// As BroadPhaseStructure::stats (the last find_pairs' counters).
  virtual BroadPhaseStats stats() const = 0;
  /// As BroadPhaseStructure::size.
  virtual std::size_t size() const = 0;

  /// Finds the pairs (kept in pairs()) and returns the delta against the previous call
  /// (the first call reports every pair as begun).
  const PairDelta& update_pairs(Executor& executor = serial_executor()) {
    find_pairs(pairs_, executor);
    return tracker_.update(pairs_);
  }
  /// The pairs of the last update_pairs call, sorted.
  const std::vector<ProxyPair>& pairs() const { return pairs_; }
  /// The delta of the last update_pairs call.
  const PairDelta& delta() const { return tracker_.delta(); }

 private:
  std::vector<ProxyPair> pairs_;
  PairTracker tracker_;
};

/// True when S offers find_pairs(out, executor).
template <class S>
concept ParallelBroadPhase = requires(S& s, std::vector<ProxyPair>& out, Executor& executor) {
  { s.find_pairs(out, executor) } -> std::same_as<void>;
};

/// AnyBroadPhase around a BroadPhaseStructure held by value.
template <BroadPhaseStructure S>
class BroadPhaseAdapter final : public AnyBroadPhase {
 public:
  /// Wraps `structure` under registry name `name` (a string literal or other static text).
  explicit BroadPhaseAdapter(std::string_view name, S structure = S()) : name_(name), s_(std::move(structure)) {}

  using AnyBroadPhase::find_pairs;

  std::string_view name() const override { return name_; }
  bool parallel() const override { return ParallelBroadPhase<S>; }
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {}) override {
    return s_.insert(id, box, kind, filter);
  }
  BroadPhaseStatus remove(ProxyId id) override { return s_.remove(id); }
  BroadPhaseStatus update(ProxyId id, const Aabb& box) override { return s_.update(id, box); }
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates) override { return s_.update(updates); }
  void rebuild() override { s_.rebuild(); }
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor) override {
    if constexpr (ParallelBroadPhase<S>) {
      s_.find_pairs(out, executor);
    } else {
      (void)executor;
      s_.find_pairs(out);
    }
  }
  BroadPhaseStats query_aabb(const Aabb& box, OverlapQueryCallback on_overlap) const override {
    return s_.query_aabb(box, on_overlap);
  }
  BroadPhaseStats query_point(const Vec3& point, OverlapQueryCallback on_overlap) const override {
    return s_.query_point(point, on_overlap);
  }
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, RayQueryCallback on_ray) const override {
    return s_.query_ray(ray, max_t, on_ray);
  }
  bool validate() const override { return s_.validate(); }
  BroadPhaseStats stats() const override { return s_.stats(); }
  std::size_t size() const override { return s_.size(); }

  /// The wrapped structure.
  S& structure() { return s_; }
  /// The wrapped structure.
  const S& structure() const { return s_; }

 private:
  std::string_view name_;
  S s_;
};

/// Registry entry: a name, a one-line description and a factory.
struct BroadPhaseEntry {
  std::string_view name;                     ///< e.g. "sap"
  std::string_view description;              ///< one line, for help texts
  std::unique_ptr<AnyBroadPhase> (*make)();  ///< new default-configured instance
};

/// Every registered structure, in registry order (broadphase_registry.cpp).
std::span<const BroadPhaseEntry> broadphase_registry();
/// The registered names, in registry order.
std::vector<std::string_view> broadphase_names();
/// A new structure by name; an Error (field "structure") listing the names when unknown.
Result<std::unique_ptr<AnyBroadPhase>> make_broadphase(std::string_view name);

static_assert(BroadPhaseStructure<AnyBroadPhase>);

}  // namespace proxima
