// Fuzz target: broad-phase operation sequences against brute force. One structure of the
// registry (make_broadphase; every one, "brute" included) receives a sequence of inserts,
// removes, single and batch updates, rebuilds, pair searches and box, point and ray queries;
// a model kept here (a map from id to box, kind and filter, pairs by testing every two
// boxes) says what each should give:
//   1. each call's status is Ok exactly when the model accepts it (finite box, min <= max,
//      |coordinate| <= kMaxCoordinate, id present or absent as the call needs), and a
//      refused call changes nothing;
//   2. find_pairs gives the model's pairs: closed boxes overlapping, not both static,
//      filters accepting each other, each pair once as (lo, hi), sorted;
//   3. box and point queries report exactly the overlapping proxies, each once; a ray query
//      exactly the proxies whose box geometry::ray_aabb hits within max_t;
//   4. validate() holds after every call; size() is the model's.
// Input: the structure, then operations of a few bytes each; ids below 48, coordinates on a
// grid of quarter units (so that boxes touch exactly) or, for some boxes, raw bit patterns.
#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_support.hpp"

namespace pf = proxima::fuzz;
using namespace proxima;

namespace {

struct ModelProxy {
  Aabb box;
  ProxyKind kind = ProxyKind::Moving;
  ProxyFilter filter;
};
using Model = std::map<ProxyId, ModelProxy>;

Real coordinate(pf::ByteReader& in) { return static_cast<Real>(static_cast<int>(in.byte()) - 128) * Real(0.25); }

Aabb read_box(pf::ByteReader& in) {
  if (in.byte() < 8)
    return {Vec3(in.raw_real(), in.raw_real(), in.raw_real()), Vec3(in.raw_real(), in.raw_real(), in.raw_real())};
  const Vec3 lo(coordinate(in), coordinate(in), coordinate(in));
  const Vec3 size(Real(in.byte() % 32) * Real(0.25), Real(in.byte() % 32) * Real(0.25),
                  Real(in.byte() % 32) * Real(0.25));
  return {lo, lo + size};
}

bool box_ok(const Aabb& b) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(b.min[i]) || !std::isfinite(b.max[i]) || b.min[i] > b.max[i]) return false;
    if (std::abs(b.min[i]) > kMaxCoordinate || std::abs(b.max[i]) > kMaxCoordinate) return false;
  }
  return true;
}

std::vector<ProxyPair> model_pairs(const Model& model) {
  std::vector<ProxyPair> pairs;
  for (auto i = model.begin(); i != model.end(); ++i) {
    for (auto j = std::next(i); j != model.end(); ++j) {
      const ModelProxy& a = i->second;
      const ModelProxy& b = j->second;
      if (a.kind == ProxyKind::Static && b.kind == ProxyKind::Static) continue;
      if (!can_pair(a.filter, b.filter) || !a.box.overlaps(b.box)) continue;
      pairs.push_back({i->first, j->first});
    }
  }
  return pairs;
}

void expect_status(BroadPhaseStatus got, bool accepted) {
  pf::check((got == BroadPhaseStatus::Ok) == accepted, "status differs from the model's");
}

void check_queries(const AnyBroadPhase& s, const Model& model, pf::ByteReader& in) {
  const Aabb box = read_box(in);
  if (box_ok(box)) {
    std::vector<ProxyId> got, want;
    s.query_aabb(box, [&](ProxyId id) { return got.push_back(id), true; });
    for (const auto& [id, p] : model) {
      if (p.box.overlaps(box)) want.push_back(id);
    }
    std::sort(got.begin(), got.end());
    pf::check(got == want, "query_aabb differs from brute force");
    got.clear();
    want.clear();
    s.query_point(box.min, [&](ProxyId id) { return got.push_back(id), true; });
    for (const auto& [id, p] : model) {
      if (p.box.contains(box.min)) want.push_back(id);
    }
    std::sort(got.begin(), got.end());
    pf::check(got == want, "query_point differs from brute force");
    const Ray ray{box.min, box.max - box.min + Vec3(Real(0.5) * coordinate(in), Real(0), Real(0.125))};
    const Real max_t = Real(in.byte() % 9) * Real(0.5);
    got.clear();
    want.clear();
    // The callback returns more than max_t: never a clip (0 would stop the query).
    s.query_ray(ray, max_t, [&](ProxyId id, Real) { return got.push_back(id), max_t + Real(1); });
    for (const auto& [id, p] : model) {
      const auto hit = geometry::ray_aabb(ray, max_t, p.box);
      if (hit && hit->t <= max_t) want.push_back(id);
    }
    std::sort(got.begin(), got.end());
    pf::check(got == want, "query_ray differs from brute force (geometry::ray_aabb per box)");
  }
}

// The operations run so far (operation code, id), printed when a check fails.
std::vector<std::pair<int, ProxyId>>& history() {
  static std::vector<std::pair<int, ProxyId>> h;
  return h;
}

void run_operation(AnyBroadPhase& s, Model& model, pf::ByteReader& in, std::vector<ProxyPair>& pairs) {
  const std::uint8_t op = in.byte() % 9;
  const ProxyId id = in.index(48);
  history().emplace_back(op, id);
  switch (op) {
    case 0:
    case 1: {
      const Aabb box = read_box(in);
      const ProxyKind kind = in.flag() ? ProxyKind::Static : ProxyKind::Moving;
      const ProxyFilter filter{1u + in.index(3), in.flag() ? ~0u : 1u + in.index(3)};
      const bool accepted = box_ok(box) && !model.contains(id);
      expect_status(s.insert(id, box, kind, filter), accepted);
      if (accepted) model[id] = {box, kind, filter};
      break;
    }
    case 2:
      expect_status(s.remove(id), model.contains(id));
      model.erase(id);
      break;
    case 3:
    case 4: {
      const Aabb box = read_box(in);
      const bool accepted = box_ok(box) && model.contains(id);
      expect_status(s.update(id, box), accepted);
      if (accepted) model[id].box = box;
      break;
    }
    case 5: {
      std::vector<ProxyUpdate> updates;
      bool accepted = true;
      for (std::uint32_t i = 0, n = 1 + in.index(4); i < n; ++i) {
        const ProxyId u = (id + i) % 48;
        updates.push_back({u, read_box(in)});
        accepted = accepted && model.contains(u) && box_ok(updates.back().box);
      }
      expect_status(s.update(updates), accepted);
      if (accepted) {
        for (const ProxyUpdate& u : updates) model[u.id].box = u.box;
      }
      break;
    }
    case 6: s.rebuild(); break;
    case 7:
      s.find_pairs(pairs);
      pf::check(pairs == model_pairs(model), "find_pairs differs from brute force");
      break;
    default: check_queries(s, model, in); break;
  }
  pf::check(s.validate(), "validate() fails");
  pf::check(s.size() == model.size(), "size() differs from the model's");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pf::start_target();
  pf::ByteReader in(data, size);
  const std::vector<std::string_view> names = broadphase_names();
  Result<std::unique_ptr<AnyBroadPhase>> made =
      make_broadphase(names[in.index(static_cast<std::uint32_t>(names.size()))]);
  pf::check(made.ok(), "make_broadphase refused a registered name");
  AnyBroadPhase& s = *made.value();
  Model model;
  std::vector<ProxyPair> pairs;
  int step = 0;
  history().clear();
  pf::failure_context() = [&] {
    std::fprintf(stderr, "  structure %s, operation %d, %zu proxies\n", std::string(s.name()).c_str(), step,
                 model.size());
    for (const auto& [op, id] : history()) std::fprintf(stderr, "  op %d id %u\n", op, id);
    for (const auto& [id, p] : model) {
      std::fprintf(stderr, "  proxy %u kind %d\n", id, static_cast<int>(p.kind));
      pf::print_vec("min", p.box.min);
      pf::print_vec("max", p.box.max);
    }
  };
  for (; step < 256 && !in.empty(); ++step) run_operation(s, model, in, pairs);
  s.find_pairs(pairs);
  pf::check(pairs == model_pairs(model), "find_pairs differs from brute force");
  return 0;
}
