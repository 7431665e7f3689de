// Stress: a churning scene (every step objects are moved, added, removed, re-filtered,
// attached and detached; now and then teleported, reshaped or made static) run in three
// worlds at once, stepped on 1, 2 and 4 threads. The three must stay byte for byte equal
// (the state hash every step, the binary snapshot every 25 steps), and every 100 steps the
// touching pairs must equal an independent brute force (every pair of live objects through
// the narrow phase, with the filters and attachment rules applied by hand). 10,000 steps at
// full size (PROXIMA_TEST_SWEEP scales them); the sanitizer builds add leaks (ASan) and
// races (TSan) to what fails.
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>

#include <array>
#include <memory>
#include <sstream>
#include <sweep_size.hpp>

#include "world/world_scene.hpp"

namespace proxima::test {
namespace test_world_churn {

constexpr Real kDt = Real(1) / Real(60);

/// The root of the object's attachment tree, from the public descriptions.
ObjectHandle root_of(const CollisionWorld& world, ObjectHandle h) {
  for (std::optional<ObjectDesc> d = world.object(h); d && d->parent.is_set(); d = world.object(h)) h = d->parent;
  return h;
}

/// The touching pairs by brute force: every pair of live objects of different trees, not
/// both static, whose filters accept each other and which intersect.
std::vector<ObjectPair> reference_pairs(const CollisionWorld& world) {
  const std::vector<ObjectHandle> all = world.objects();
  std::vector<ObjectDesc> desc;
  std::vector<ObjectHandle> roots;
  for (ObjectHandle h : all) {
    desc.push_back(*world.object(h));
    roots.push_back(root_of(world, h));
  }
  std::vector<ObjectPair> out;
  const PairRequest request;
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      const ObjectDesc& a = desc[i];
      const ObjectDesc& b = desc[j];
      if (roots[i] == roots[j] || (a.kind == ObjectKind::Static && b.kind == ObjectKind::Static)) continue;
      if (!can_collide(a.filter, b.filter)) continue;
      if (intersect(a.geometry, a.pose, b.geometry, b.pose, request)) out.push_back({all[i], all[j]});
    }
  return out;
}

/// Pairs on which the world and the brute force disagree, less those within the narrow
/// phase's tolerance of touching (intersect counts a gap within tolerance, collide not).
std::vector<ObjectPair> clear_disagreements(const CollisionWorld& world) {
  const std::vector<ObjectPair> now = world_pairs(world);
  const std::vector<ObjectPair> reference = reference_pairs(world);
  const Real band = sizeof(Real) == 4 ? Real(2e-4) : Real(1e-8);
  std::vector<ObjectPair> out;
  for (const auto& diff : {minus(now, reference), minus(reference, now)})
    for (const ObjectPair& p : diff) {
      const ObjectDesc a = *world.object(p.a), b = *world.object(p.b);
      if (std::abs(distance(a.geometry, a.pose, b.geometry, b.pose).signed_distance) > band) out.push_back(p);
    }
  return out;
}

/// The worlds under test and what drives them: every change is drawn once and applied to
/// each world, which must accept or refuse it alike.
class Churn {
 public:
  explicit Churn(std::uint64_t seed) : rng_(seed) {
    for (std::size_t k = 0; k < worlds_.size(); ++k) worlds_[k] = std::make_unique<CollisionWorld>(make_world());
    for (int k = 0; k < 60; ++k) add();
    for (auto& w : worlds_) add_statics(*w);
  }

  /// One step of churn, then one step of every world (worlds_[k] moved and stepped on
  /// executors[k]).
  void step(const std::array<Executor*, 3>& executors) {
    moves_.clear();
    for (Mover& m : movers_) {
      Transform p = worlds_[0]->pose(m.handle);
      p.position += m.velocity;
      for (int a = 0; a < 3; ++a)
        if (std::abs(p.position[a]) > kExtent) m.velocity[a] = -m.velocity[a];
      moves_.push_back({m.handle, p});
    }
    for (std::size_t k = 0; k < worlds_.size(); ++k) {
      ASSERT_FALSE(worlds_[k]->move(moves_, *executors[k]).has_value());
    }
    change();
    for (std::size_t k = 0; k < worlds_.size(); ++k) {
      ASSERT_FALSE(worlds_[k]->step(kDt, *executors[k]).has_value());
    }
  }

  CollisionWorld& world(std::size_t k) { return *worlds_[k]; }
  std::size_t size() const { return movers_.size(); }

 private:
  void add_statics(CollisionWorld& world) {
    ObjectDesc floor;
    floor.geometry = floor_mesh(kExtent, 6);
    floor.kind = ObjectKind::Static;
    floor.pose = Transform{Vec3(0, 0, -kExtent), kIdentityQuat};
    EXPECT_TRUE(world.add(floor).ok());
  }

  void add() {
    ObjectDesc d;
    d.geometry = random_geometry(rng_, Real(0.8));
    d.pose = Transform{rng_.vec3(-kExtent, kExtent), rng_.rotation()};
    d.user_data = next_user_++;
    ObjectHandle h;
    for (auto& w : worlds_) {
      const Result<ObjectHandle> got = w->add(d);
      ASSERT_TRUE(got.ok());
      if (h.is_set()) {
        ASSERT_EQ(*got, h);
      }
      h = *got;
    }
    movers_.push_back({h, rng_.vec3(Real(-0.25), Real(0.25)), Vec3(0)});
  }

  Mover& any() { return movers_[std::size_t(rng_.integer(0, int(movers_.size()) - 1))]; }

  /// Applies `call` to every world; all must answer alike (error or none).
  template <class Call>
  void on_all(Call&& call) {
    const bool first = call(*worlds_[0]);
    for (std::size_t k = 1; k < worlds_.size(); ++k) ASSERT_EQ(call(*worlds_[k]), first);
  }

  /// The changes of one step: remove one, add one, re-filter one, attach one, detach one;
  /// sometimes teleport, reshape or change the kind of one.
  void change() {
    const ObjectHandle gone = any().handle;
    on_all([&](CollisionWorld& w) { return w.remove(gone).has_value(); });
    std::erase_if(movers_, [&](const Mover& m) { return !worlds_[0]->contains(m.handle); });
    while (movers_.size() < 60) add();
    CollisionFilter filter;
    filter.layer = std::uint64_t(rng_.integer(1, 3));
    filter.mask = rng_.integer(0, 3) == 0 ? std::uint64_t(rng_.integer(1, 3)) : ~0ull;
    filter.group = rng_.integer(0, 2);
    const ObjectHandle refiltered = any().handle;
    on_all([&](CollisionWorld& w) { return w.set_filter(refiltered, filter).has_value(); });
    const ObjectHandle child = any().handle, parent = any().handle;
    const Transform local = relative(worlds_[0]->pose(parent), worlds_[0]->pose(child));
    on_all([&](CollisionWorld& w) { return w.attach(child, parent, local).has_value(); });
    const ObjectHandle loose = any().handle;
    on_all([&](CollisionWorld& w) { return w.attach(loose, ObjectHandle{}, Transform::identity()).has_value(); });
    const int rare = rng_.integer(0, 9);
    const ObjectHandle odd = any().handle;
    if (rare == 0) {
      const Transform to{rng_.vec3(-kExtent, kExtent), rng_.rotation()};
      on_all([&](CollisionWorld& w) { return w.teleport(odd, to).has_value(); });
    } else if (rare == 1) {
      const Shape geometry = random_geometry(rng_, Real(0.8));
      on_all([&](CollisionWorld& w) { return w.set_geometry(odd, geometry).has_value(); });
    } else if (rare == 2) {
      const ObjectKind kind = rng_.integer(0, 1) == 0 ? ObjectKind::Static : ObjectKind::Moving;
      on_all([&](CollisionWorld& w) { return w.set_kind(odd, kind).has_value(); });
    }
  }

  Random rng_;
  std::array<std::unique_ptr<CollisionWorld>, 3> worlds_;
  std::vector<Mover> movers_;
  std::vector<ObjectMove> moves_;
  std::uint64_t next_user_ = 0;
};

std::string snapshot(const CollisionWorld& world) {
  std::ostringstream out;
  EXPECT_FALSE(world.save(out).has_value());
  return out.str();
}

TEST(WorldChurn, OneTwoAndFourThreadsStayByteForByteEqualAndMatchTheBruteForce) {
  Churn churn(77);
  ThreadPool two(2), four(4);
  const std::array<Executor*, 3> executors{&serial_executor(), &two, &four};
  const int steps = sweep_size(10000);
  std::size_t touching = 0, ended = 0;
  for (int s = 1; s <= steps; ++s) {
    churn.step(executors);
    if (HasFatalFailure()) return;
    const std::uint64_t hash = churn.world(0).state_hash();
    ASSERT_EQ(churn.world(1).state_hash(), hash) << "2 threads, step " << s;
    ASSERT_EQ(churn.world(2).state_hash(), hash) << "4 threads, step " << s;
    touching += churn.world(0).contacts().size();
    ended += churn.world(0).events().end.size();
    if (s % 25 == 0) {
      const std::string bytes = snapshot(churn.world(0));
      ASSERT_EQ(snapshot(churn.world(1)), bytes) << "2 threads, step " << s;
      ASSERT_EQ(snapshot(churn.world(2)), bytes) << "4 threads, step " << s;
    }
    if (s % 100 == 0 || s == steps) {
      const std::vector<ObjectPair> wrong = clear_disagreements(churn.world(2));
      ASSERT_TRUE(wrong.empty()) << "step " << s << ": " << pair_text(wrong);
    }
  }
  EXPECT_GT(touching, std::size_t(steps)) << "the scene must keep pairs touching";
  EXPECT_GT(ended, std::size_t(steps) / 10) << "the churn must end pairs";
}

}  // namespace test_world_churn
}  // namespace proxima::test
