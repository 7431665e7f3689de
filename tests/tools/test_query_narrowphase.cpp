// In-process tests of the narrow-phase operations of the query protocol (intersect,
// distance, collide): answers against analytic references computed here in double (sphere
// pairs, a sphere against a box, face-on-face boxes), the options of collide
// (max_contacts, contact_distance), the status and method names, and errors naming their
// field.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "json_expect.hpp"
#include "query.hpp"
#include "query_operations.hpp"
#include "query_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_query_narrowphase {

using test::add, test::answer, test::D3, test::d3, test::dot, test::Json, test::js, test::norm, test::scale, test::sub;

// Float GJK/analytic answers: relative accuracy of the float build's narrow phase.
constexpr double kTol = sizeof(Real) == 4 ? 2e-3 : 1e-7;

D3 random_d3(test::Random& rng, Real lo, Real hi) {
  const Vec3 v = rng.vec3(lo, hi);
  return {double(v.x), double(v.y), double(v.z)};
}

Json placed(const Json& shape, const D3& position) {
  return Json{{"shape", shape}, {"pose", {{"position", js(position)}}}};
}

TEST(QueryNarrowphase, OperationsAreRegistered) {
  for (const char* name : {"intersect", "distance", "collide"}) {
    const tool::Operation* op = tool::find_operation(name);
    ASSERT_NE(op, nullptr) << name;
    EXPECT_FALSE(op->synopsis.empty());
  }
}

// Two spheres: distance |c2 - c1| - r1 - r2 along the centre line, witnesses on the spheres.
TEST(QueryNarrowphase, SpherePairsMatchTheCentreLine) {
  test::Random rng(501);
  const std::set<std::string> statuses = {"separated", "touching", "penetrating"};
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const double r1 = double(rng.uniform(Real(0.1), Real(2)));
    const double r2 = double(rng.uniform(Real(0.1), Real(2)));
    const D3 c1 = random_d3(rng, Real(-3), Real(3));
    const D3 c2 = random_d3(rng, Real(-3), Real(3));
    const Json a = placed({{"type", "sphere"}, {"radius", r1}}, c1);
    const Json b = placed({{"type", "sphere"}, {"radius", r2}}, c2);
    const double len = norm(sub(c2, c1));
    if (len < 1e-3) continue;
    const D3 n = scale(sub(c2, c1), 1.0 / len);
    const double expected = len - r1 - r2;
    const Json d = answer({{"op", "distance"}, {"a", a}, {"b", b}});
    EXPECT_NEAR(d["distance"].get<double>(), expected, kTol * 10) << d.dump();
    const D3 pa = d3(d["point_a"]);
    const D3 pb = d3(d["point_b"]);
    const D3 dn = d3(d["normal"]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(pa[k], c1[k] + r1 * n[k], kTol * 10) << d.dump();
      EXPECT_NEAR(pb[k], c2[k] - r2 * n[k], kTol * 10) << d.dump();
      EXPECT_NEAR(dn[k], n[k], kTol * 10) << d.dump();
    }
    EXPECT_TRUE(statuses.count(d["status"].get<std::string>())) << d.dump();
    EXPECT_TRUE(d["method"].is_string());
    const bool hit = answer({{"op", "intersect"}, {"a", a}, {"b", b}})["hit"].get<bool>();
    if (std::abs(expected) > kTol) {
      EXPECT_EQ(hit, expected < 0) << expected;
    }
    hits += hit ? 1 : 0;
    const Json c = answer({{"op", "collide"}, {"a", a}, {"b", b}});
    if (std::abs(expected) > kTol) {
      EXPECT_EQ(c["hit"].get<bool>(), expected < 0) << c.dump();
      EXPECT_EQ(c["contacts"].size(), expected < 0 ? 1u : 0u) << c.dump();
    }
    if (!c["contacts"].empty()) {
      EXPECT_NEAR(c["contacts"][0]["depth"].get<double>(), -expected, kTol * 10) << c.dump();
    }
  }
  EXPECT_GT(hits, 20);
}

// A sphere against an axis-aligned box: distance from the clamped centre.
TEST(QueryNarrowphase, SphereBoxMatchesClampedCentre) {
  test::Random rng(502);
  const D3 h{1.0, 0.5, 2.0};
  for (int i = 0; i < 500; ++i) {
    const double r = double(rng.uniform(Real(0.1), Real(1)));
    const D3 c = random_d3(rng, Real(-3), Real(3));
    const D3 q{std::clamp(c[0], -h[0], h[0]), std::clamp(c[1], -h[1], h[1]), std::clamp(c[2], -h[2], h[2])};
    const double outside = norm(sub(c, q));
    if (outside == 0.0) continue;  // centre inside the box: depth needs the nearest face
    const Json box = {{"type", "box"}, {"half_extents", js(h)}};
    const Json sphere = placed({{"type", "sphere"}, {"radius", r}}, c);
    const Json d = answer({{"op", "distance"}, {"a", box}, {"b", sphere}});
    EXPECT_NEAR(d["distance"].get<double>(), outside - r, kTol * 10) << d.dump();
    const D3 pa = d3(d["point_a"]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(pa[k], q[k], kTol * 10) << d.dump();
  }
}

// Face on face boxes: a four-point manifold with the overlap as depth; max_contacts and
// contact_distance take effect.
TEST(QueryNarrowphase, CollideBoxesFaceOnFace) {
  const Json box = {{"type", "box"}, {"half_extents", {1, 1, 0.5}}};
  const Json top = placed({{"type", "box"}, {"half_extents", {0.5, 0.5, 0.5}}}, {0.2, -0.1, 0.9});
  const Json c = answer({{"op", "collide"}, {"a", box}, {"b", top}});
  EXPECT_TRUE(c["hit"].get<bool>());
  EXPECT_EQ(c["status"], "penetrating");
  ASSERT_EQ(c["contacts"].size(), 4u) << c.dump();
  test::expect_json_near(c["normal"], Json::array({0.0, 0.0, 1.0}), "normal", kTol);
  for (const Json& p : c["contacts"]) {
    EXPECT_NEAR(p["depth"].get<double>(), 0.1, kTol) << c.dump();
    test::expect_json_near(p["normal"], Json::array({0.0, 0.0, 1.0}), "contact normal", kTol);
    const D3 pa = d3(p["point_a"]);
    const D3 pb = d3(p["point_b"]);
    EXPECT_NEAR(pb[2] - pa[2], -0.1, kTol) << c.dump();
  }
  const Json one = answer({{"op", "collide"}, {"a", box}, {"b", top}, {"max_contacts", 1}});
  EXPECT_EQ(one["contacts"].size(), 1u) << one.dump();

  // 0.05 apart: nothing by default, speculative contacts (negative depth) within 0.1.
  const Json apart = placed({{"type", "box"}, {"half_extents", {0.5, 0.5, 0.5}}}, {0.2, -0.1, 1.05});
  const Json none = answer({{"op", "collide"}, {"a", box}, {"b", apart}});
  EXPECT_FALSE(none["hit"].get<bool>());
  EXPECT_TRUE(none["contacts"].empty());
  EXPECT_EQ(none["status"], "separated");
  const Json spec = answer({{"op", "collide"}, {"a", box}, {"b", apart}, {"contact_distance", 0.1}});
  EXPECT_TRUE(spec["hit"].get<bool>()) << spec.dump();
  ASSERT_FALSE(spec["contacts"].empty()) << spec.dump();
  for (const Json& p : spec["contacts"]) EXPECT_NEAR(p["depth"].get<double>(), -0.05, kTol) << spec.dump();
  const Json dist = answer({{"op", "distance"}, {"a", box}, {"b", apart}});
  EXPECT_NEAR(dist["distance"].get<double>(), 0.05, kTol) << dist.dump();
  EXPECT_FALSE(answer({{"op", "intersect"}, {"a", box}, {"b", apart}})["hit"].get<bool>());
}

// Every pair of shape types answers (no error, finite numbers, known names).
TEST(QueryNarrowphase, EveryPairOfTypesAnswers) {
  const std::vector<Json> shapes = {
      {{"type", "point"}},
      {{"type", "segment"}, {"vertices", {{0, 0, -1}, {0, 0, 1}}}},
      {{"type", "triangle"}, {"vertices", {{-1, 0, 0}, {1, 0, 0}, {0, 1, 0}}}},
      {{"type", "sphere"}, {"radius", 0.5}},
      {{"type", "capsule"}, {"radius", 0.3}, {"half_length", 0.5}},
      {{"type", "box"}, {"half_extents", {0.5, 0.4, 0.3}}},
      {{"type", "cylinder"}, {"radius", 0.4}, {"half_length", 0.6}},
      {{"type", "cone"}, {"radius", 0.4}, {"half_length", 0.6}},
      {{"type", "ellipsoid"}, {"radii", {0.5, 0.3, 0.4}}},
      {{"type", "convex"}, {"points", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}},
      {{"type", "halfspace"}, {"normal", {0, 0, 1}}, {"offset", 0}},
  };
  const std::set<std::string> statuses = {"separated",      "touching",   "penetrating",
                                          "max_iterations", "degenerate", "invalid_input"};
  const std::set<std::string> methods = {"analytic", "gjk", "epa", "sat", "support", "closest_point"};
  for (const Json& sa : shapes) {
    for (const Json& sb : shapes) {
      for (const D3& offset : {D3{0.3, 0.2, 0.1}, D3{3, 0, 0}}) {
        const Json b = placed(sb, offset);
        const Json d = answer({{"op", "distance"}, {"a", sa}, {"b", b}});
        const Json c = answer({{"op", "collide"}, {"a", sa}, {"b", b}});
        const std::string where = sa.dump() + " " + b.dump();
        EXPECT_TRUE(d["distance"].is_number()) << where;
        EXPECT_TRUE(statuses.count(d["status"].get<std::string>())) << where;
        EXPECT_TRUE(methods.count(d["method"].get<std::string>())) << where;
        EXPECT_TRUE(statuses.count(c["status"].get<std::string>())) << where;
        EXPECT_TRUE(methods.count(c["method"].get<std::string>())) << where;
        EXPECT_LE(c["contacts"].size(), 4u) << where;
        EXPECT_TRUE(answer({{"op", "intersect"}, {"a", sa}, {"b", b}})["hit"].is_boolean()) << where;
      }
    }
  }
}

TEST(QueryNarrowphase, ErrorsNameTheirField) {
  struct Case {
    const char* request;
    const char* field;
    const char* code;
  };
  const Case cases[] = {
      {R"({"id":1,"op":"distance","b":{"type":"sphere","radius":1}})", "a", "missing"},
      {R"({"id":1,"op":"intersect","a":{"type":"sphere","radius":1}})", "b", "missing"},
      {R"({"id":1,"op":"distance","a":{"shape":{"type":"sphere","radius":0}},"b":{"type":"sphere","radius":1}})",
       "a.shape.radius", "non_positive"},
      {R"({"id":1,"op":"distance","a":{"type":"sphere","radius":1},"b":{"shape":{"type":"box","half_extents":[1,1,1]},"pose":{"rotation":[0,0,0,3]}}})",
       "b.pose.rotation", "invalid_argument"},
      {R"({"id":1,"op":"collide","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"max_contacts":0})",
       "max_contacts", "out_of_range"},
      {R"({"id":1,"op":"collide","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"max_contacts":5})",
       "max_contacts", "out_of_range"},
      {R"({"id":1,"op":"collide","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"max_contacts":1.5})",
       "max_contacts", "wrong_type"},
      {R"({"id":1,"op":"collide","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"contact_distance":-1})",
       "contact_distance", "negative"},
      {R"({"id":1,"op":"collide","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"contact_distance":"x"})",
       "contact_distance", "wrong_type"},
      {R"({"id":1,"op":"distance","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"max_contacts":2})",
       "max_contacts", "unknown_field"},
      {R"({"id":1,"op":"intersect","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1},"target":{}})",
       "target", "unknown_field"},
  };
  for (const Case& c : cases) {
    bool rejected = false;
    const Json a = tool::answer_line(c.request, rejected);
    EXPECT_TRUE(rejected) << c.request;
    EXPECT_EQ(a.value("field", ""), c.field) << c.request << " -> " << a.dump();
    EXPECT_EQ(a.value("code", ""), c.code) << c.request << " -> " << a.dump();
  }
}

}  // namespace test_query_narrowphase
}  // namespace proxima
