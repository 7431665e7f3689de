#pragma once
/// @file contact_collector.hpp
/// Where `collide_all` puts its contacts: a collector receives every contact as it is found
/// and may end the query early (Jolt's CollideShapeCollector idea). ContactVector keeps them
/// all, FirstContact keeps one and stops at once, DeepestContact keeps the deepest; a world
/// or an application derives its own (filter by part, stop after N, accumulate a manifold).
#include <proxima/narrowphase/contact.hpp>

#include <optional>
#include <vector>

namespace proxima {

/// Receives contacts (world frame, normal from A to B, parts in sub_a / sub_b). A query
/// checks done() between parts (triangles, children) and returns as soon as it is set; the
/// points of the part being reported may still arrive after stop(), so a collector that
/// wants exactly N contacts ignores the extra ones.
class ContactCollector {
 public:
  ContactCollector() = default;
  ContactCollector(const ContactCollector&) = default;
  ContactCollector& operator=(const ContactCollector&) = default;
  virtual ~ContactCollector() = default;

  /// Called once for each contact found.
  virtual void add(const ContactPoint& contact) = 0;
  /// True once the collector wants no more contacts.
  bool done() const noexcept { return done_; }

 protected:
  /// Ends the query once the current part is reported.
  void stop() noexcept { done_ = true; }

 private:
  bool done_ = false;
};

/// Keeps every contact, in the order found.
class ContactVector final : public ContactCollector {
 public:
  void add(const ContactPoint& contact) override { contacts.push_back(contact); }
  std::vector<ContactPoint> contacts;  ///< the contacts received
};

/// Keeps the first contact and stops the query (a boolean test that also wants a witness).
class FirstContact final : public ContactCollector {
 public:
  void add(const ContactPoint& contact) override {
    if (!first) first = contact;
    stop();
  }
  std::optional<ContactPoint> first;  ///< the contact received, if any
};

/// Keeps the deepest contact (largest depth; the first of equal ones).
class DeepestContact final : public ContactCollector {
 public:
  void add(const ContactPoint& contact) override {
    if (!deepest || contact.depth > deepest->depth) deepest = contact;
  }
  std::optional<ContactPoint> deepest;  ///< the deepest contact received, if any
};

}  // namespace proxima
