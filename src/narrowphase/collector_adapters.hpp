#pragma once
/// @file collector_adapters.hpp
/// Internal: collectors that rewrite each contact and pass it on to another collector, so a
/// routine written for one side order (mesh as A, compound as A) serves the mirrored cell
/// and compound children tag their contacts on the way out. Each stops when the collector
/// it feeds is done.
#include <proxima/narrowphase/contact_collector.hpp>

#include <cstdint>

namespace proxima::narrow {

/// Passes each contact on with A and B swapped (mirrored()).
class MirroredCollector final : public ContactCollector {
 public:
  explicit MirroredCollector(ContactCollector& target) : target_(target) {}
  void add(const ContactPoint& contact) override {
    target_.add(mirrored(contact));
    if (target_.done()) stop();
  }

 private:
  ContactCollector& target_;
};

/// Passes each contact on with A's part named as top-level compound child `child` (an
/// outer compound's tag overwrites an inner one's).
class ChildOfACollector final : public ContactCollector {
 public:
  ChildOfACollector(ContactCollector& target, std::uint32_t child) : target_(target), child_(child) {}
  void add(const ContactPoint& contact) override {
    ContactPoint c = contact;
    c.sub_a.child = child_;
    target_.add(c);
    if (target_.done()) stop();
  }

 private:
  ContactCollector& target_;
  std::uint32_t child_;
};

/// Passes each contact on with both parts named: A's child `child_a`, B's child `child_b`.
class ChildPairCollector final : public ContactCollector {
 public:
  ChildPairCollector(ContactCollector& target, std::uint32_t child_a, std::uint32_t child_b)
      : target_(target), child_a_(child_a), child_b_(child_b) {}
  void add(const ContactPoint& contact) override {
    ContactPoint c = contact;
    c.sub_a.child = child_a_;
    c.sub_b.child = child_b_;
    target_.add(c);
    if (target_.done()) stop();
  }

 private:
  ContactCollector& target_;
  std::uint32_t child_a_;
  std::uint32_t child_b_;
};

}  // namespace proxima::narrow
