// In-process tests of the continuous operations of the query protocol (toi, cast,
// safe_step): answers against closed forms computed here in double (a sphere moving into a
// box face, a rotating paddle against a resting ball, a sphere cast against a mesh face and
// a half-space, safe steps of spheres and of a turning box), the t = 0 contract (touching
// and moving apart, touching and moving in, overlapping), meshes and compounds, the options,
// the exact members of every kind of answer, and errors naming their field.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "query.hpp"
#include "query_operations.hpp"
#include "query_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_query_ccd {

using test::add, test::answer, test::D3, test::d3, test::dot, test::Json, test::js, test::norm, test::Rot, test::scale,
    test::sub;

// Accuracy of the float build's narrow phase on the lengths and directions checked here.
constexpr double kTol = sizeof(Real) == 4 ? 2e-4 : 1e-8;
// The default length tolerance of toi and cast (ToiOptions, CastOptions).
constexpr double kDefaultTolerance = 1e-4;

using Q = std::array<double, 4>;  // [x, y, z, w]

Q random_rotation(test::Random& rng) {
  const Quat q = rng.rotation();
  return {double(q.x), double(q.y), double(q.z), double(q.w)};
}

Json pose(const D3& position, const Q& q = {0, 0, 0, 1}) {
  return Json{{"position", js(position)}, {"rotation", Json::array({q[0], q[1], q[2], q[3]})}};
}

Json sphere(double r) { return Json{{"type", "sphere"}, {"radius", r}}; }
Json box(const D3& h) { return Json{{"type", "box"}, {"half_extents", js(h)}}; }

// A toi side moving from `from` to `to` (same rotation), or resting when to is absent.
Json mover(const Json& shape, const Json& from, const Json& to = nullptr) {
  Json side{{"shape", shape}, {"pose", from}};
  if (!to.is_null()) side["pose_end"] = to;
  return side;
}

std::vector<std::string> keys(const Json& j) {
  std::vector<std::string> names;
  for (auto it = j.begin(); it != j.end(); ++it) names.push_back(it.key());
  return names;
}

void expect_unit(const Json& v, const Json& context) { EXPECT_NEAR(norm(d3(v)), 1.0, kTol) << context.dump(); }

void expect_d3_near(const Json& actual, const D3& expected, double tolerance, const Json& context) {
  const D3 a = d3(actual);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], expected[k], tolerance) << "[" << k << "] " << context.dump();
}

TEST(QueryCcd, OperationsAreRegistered) {
  for (const char* name : {"toi", "cast", "safe_step"}) {
    const tool::Operation* op = tool::find_operation(name);
    ASSERT_NE(op, nullptr) << name;
    EXPECT_FALSE(op->synopsis.empty());
  }
}

// A sphere of radius r moving at speed s (per step) straight into a face of a turned box,
// starting `gap` away: it touches at t = gap / s, on the face, with the face's normal (from
// the sphere to the box). The same as a cast along the motion.
TEST(QueryCcd, SphereIntoBoxFaceHitsAtGapOverSpeed) {
  test::Random rng(901);
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    const D3 h{double(rng.uniform(Real(0.3), Real(2))), double(rng.uniform(Real(0.3), Real(2))),
               double(rng.uniform(Real(0.3), Real(2)))};
    const double r = double(rng.uniform(Real(0.1), Real(1)));
    const double gap = double(rng.uniform(Real(0.05), Real(3)));
    const double speed = double(rng.uniform(Real(0.5), Real(4)));
    const double y = 0.9 * h[1] * double(rng.uniform(Real(-1), Real(1)));
    const double z = 0.9 * h[2] * double(rng.uniform(Real(-1), Real(1)));
    const Q q = random_rotation(rng);
    const Rot rot = Rot::from_xyzw(q[0], q[1], q[2], q[3]);
    const D3 centre{double(rng.uniform(Real(-5), Real(5))), double(rng.uniform(Real(-5), Real(5))),
                    double(rng.uniform(Real(-5), Real(5)))};
    const D3 face_normal = rot.column(0);  // +x of the box, towards which the sphere moves
    const D3 start = add(centre, rot.apply({-(h[0] + r + gap), y, z}));
    const D3 end = add(start, scale(face_normal, speed));
    const Json b = mover(box(h), pose(centre, q));
    const Json request{{"op", "toi"}, {"a", mover(sphere(r), pose(start), pose(end))}, {"b", b}};
    const Json cast{
        {"op", "cast"}, {"a", mover(sphere(r), pose(start))}, {"translation", js(sub(end, start))}, {"b", b}};
    const Json t = answer(request);
    const Json c = answer(cast);
    if (gap > speed * (1 + 1e-3)) {
      EXPECT_FALSE(t["hit"].get<bool>()) << t.dump();
      EXPECT_EQ(t["status"], "separated") << t.dump();
      EXPECT_EQ(t["toi"].get<double>(), 1.0);
      EXPECT_FALSE(c["hit"].get<bool>()) << c.dump();
      EXPECT_EQ(c["status"], "separated") << c.dump();
      continue;
    }
    if (gap > speed * (1 - 1e-3)) continue;  // touches at the very end of the step
    ++hits;
    const double expected = gap / speed;
    const D3 contact = add(centre, rot.apply({-h[0], y, z}));
    for (const Json& a : {t, c}) {
      ASSERT_TRUE(a["hit"].get<bool>()) << a.dump();
      EXPECT_EQ(a["status"], "hit");
      const double at = a.contains("toi") ? a["toi"].get<double>() : a["t"].get<double>();
      // Within the tolerance before the contact, never after it.
      EXPECT_LE(at, expected + kTol) << a.dump();
      EXPECT_GE(at, expected - kDefaultTolerance / speed - kTol) << a.dump();
      expect_unit(a["normal"], a);
      expect_d3_near(a["normal"], face_normal, kTol, a);
      expect_d3_near(a["point"], contact, 10 * kTol * (1 + norm(centre)), a);
    }
    EXPECT_EQ(t["toi"], t["toi_upper"]);
    EXPECT_LE(t["toi_lower"].get<double>(), t["toi"].get<double>());
  }
  EXPECT_GT(hits, 50);
}

// The brief's case, answered exactly: a ball 0.5 in radius from x = -3 to 3 reaches the face
// x = -1 of a unit box when its centre is at -1.5, a quarter of the way.
TEST(QueryCcd, SphereIntoBoxFaceExactQuarter) {
  const Json t = answer(Json::parse(
      R"({"op":"toi","a":{"shape":{"type":"sphere","radius":0.5},"pose":{"position":[-3,0,0]},"pose_end":{"position":[3,0,0]}},"b":{"shape":{"type":"box","half_extents":[1,1,1]}}})"));
  EXPECT_EQ(t.dump(),
            R"({"hit":true,"toi":0.25,"toi_lower":0.25,"toi_upper":0.25,"point":[-1.0,0.0,0.0],"normal":[1.0,0.0,0.0],)"
            R"("status":"hit","iterations":4})");
  const Json c = answer(Json::parse(
      R"({"op":"cast","a":{"shape":{"type":"sphere","radius":0.5},"pose":{"position":[-3,0,0]}},"translation":[6,0,0],"b":{"type":"box","half_extents":[1,1,1]}})"));
  EXPECT_EQ(c["t"].get<double>(), 0.25) << c.dump();
  expect_d3_near(c["point"], {-1, 0, 0}, kTol, c);
  expect_d3_near(c["normal"], {1, 0, 0}, kTol, c);
}

// A paddle (a box 2L x 2w x 1 about the origin) turning about z by `turn` over the step, and
// a ball of radius r resting at (d, h, 0) above its +y face: the face's line at angle theta is
// at distance h cos(theta) - d sin(theta) from the ball's centre, so they touch at
// theta = acos((w + r) / |(d, h)|) - atan2(d, h), t = theta / turn (constant angular
// velocity), with the normal (-sin(theta), cos(theta), 0) from the paddle to the ball.
TEST(QueryCcd, RotatingPaddleHitsRestingBallAtClosedFormAngle) {
  test::Random rng(902);
  const double half_length = 2, w = 0.1;
  int checked = 0;
  for (int i = 0; i < 60; ++i) {
    const double d = double(rng.uniform(Real(0.8), Real(1.8)));
    const double h = double(rng.uniform(Real(0.7), Real(1.5)));
    const double r = double(rng.uniform(Real(0.2), Real(0.5)));
    const double turn = double(rng.uniform(Real(1), Real(2.5)));
    const double theta = std::acos((w + r) / std::hypot(d, h)) - std::atan2(d, h);
    const double lever = d * std::cos(theta) + h * std::sin(theta);  // contact's distance along the paddle
    if (!(theta > 0.05 && theta < 0.95 * turn && lever < 0.95 * half_length)) continue;
    ++checked;
    const Json request{{"op", "toi"},
                       {"a", mover(box({half_length, w, 0.5}), pose({0, 0, 0}),
                                   pose({0, 0, 0}, {0, 0, std::sin(turn / 2), std::cos(turn / 2)}))},
                       {"b", mover(sphere(r), pose({d, h, 0}))}};
    const Json a = answer(request);
    ASSERT_TRUE(a["hit"].get<bool>()) << a.dump();
    EXPECT_EQ(a["status"], "hit");
    const double expected = theta / turn;
    const double closing_speed = turn * lever;  // of the paddle's contact point, per unit t
    EXPECT_LE(a["toi"].get<double>(), expected + kTol) << a.dump();
    EXPECT_GE(a["toi"].get<double>(), expected - kDefaultTolerance / closing_speed - kTol) << a.dump();
    const D3 n{-std::sin(theta), std::cos(theta), 0};
    expect_unit(a["normal"], a);
    expect_d3_near(a["normal"], n, 1e-3, a);
    expect_d3_near(a["point"], sub({d, h, 0}, scale(n, r)), 1e-3, a);
  }
  EXPECT_GT(checked, 20);
}

// A two-triangle quad (a mesh, z = 0 in its frame, normal +z) placed at a random pose, and a
// sphere above it cast along a direction that meets it: t = (height - r) / (closing speed).
// cull_back_faces drops it when the sphere comes from behind.
TEST(QueryCcd, SphereCastAgainstMeshFace) {
  const Json quad = Json::parse(
      R"({"type":"mesh","vertices":[[-2,-2,0],[2,-2,0],[2,2,0],[-2,2,0]],"triangles":[[0,1,2],[0,2,3]],"repair":false})");
  test::Random rng(903);
  for (int i = 0; i < 100; ++i) {
    const Q q = random_rotation(rng);
    const Rot rot = Rot::from_xyzw(q[0], q[1], q[2], q[3]);
    const D3 origin{double(rng.uniform(Real(-3), Real(3))), double(rng.uniform(Real(-3), Real(3))),
                    double(rng.uniform(Real(-3), Real(3)))};
    const D3 n = rot.column(2);
    const double r = double(rng.uniform(Real(0.1), Real(0.6)));
    const double height = r + double(rng.uniform(Real(0.1), Real(3)));
    const double x = double(rng.uniform(Real(-1.2), Real(1.2))), y = double(rng.uniform(Real(-1.2), Real(1.2)));
    if (std::abs(x - y) < 0.05) continue;  // near the diagonal both triangles are hit
    const D3 hit_local{x, y, 0};
    // Aim at hit_local from above, slanted by up to 45 degrees.
    const double sx = double(rng.uniform(Real(-0.5), Real(0.5))), sy = double(rng.uniform(Real(-0.5), Real(0.5)));
    const D3 along_local{sx, sy, -1};
    const double length = double(rng.uniform(Real(1.1), Real(3))) * (height - r);
    const D3 start_local = sub(add(hit_local, {0, 0, r}), scale(along_local, (height - r)));
    const D3 start = add(origin, rot.apply(start_local));
    const D3 translation = rot.apply(scale(along_local, length));
    const Json b{{"shape", quad}, {"pose", pose(origin, q)}};
    const Json request{
        {"op", "cast"}, {"a", mover(sphere(r), pose(start))}, {"translation", js(translation)}, {"b", b}};
    const Json a = answer(request);
    ASSERT_TRUE(a["hit"].get<bool>()) << a.dump();
    EXPECT_EQ(a["status"], "hit");
    EXPECT_NEAR(a["t"].get<double>(), (height - r) / length, 1e-3) << a.dump();
    expect_unit(a["normal"], a);
    expect_d3_near(a["normal"], scale(n, -1), 1e-3, a);
    expect_d3_near(a["point"], add(origin, rot.apply(hit_local)), 2e-3, a);
    ASSERT_TRUE(a.contains("part_b")) << a.dump();
    EXPECT_EQ(a["part_b"]["triangle"].get<int>(), x >= y ? 0 : 1) << a.dump();
    EXPECT_FALSE(a.contains("part_a"));

    Json culled = request;
    culled["cull_back_faces"] = true;
    EXPECT_EQ(answer(culled)["t"], a["t"]) << "front face";
    // From below, moving along the face's normal: one-sided, nothing to hit.
    const D3 below = add(origin, rot.apply({x, y, -height}));
    Json from_below{{"op", "cast"},
                    {"a", mover(sphere(r), pose(below))},
                    {"translation", js(scale(n, 2 * height))},
                    {"b", b},
                    {"cull_back_faces", true}};
    const Json none = answer(from_below);
    EXPECT_FALSE(none["hit"].get<bool>()) << none.dump();
    EXPECT_EQ(none["status"], "separated");
    from_below.erase("cull_back_faces");
    const Json hit = answer(from_below);
    EXPECT_TRUE(hit["hit"].get<bool>()) << hit.dump();
    EXPECT_NEAR(hit["t"].get<double>(), (height - r) / (2 * height), 1e-3) << hit.dump();
    expect_d3_near(hit["normal"], n, 1e-3, hit);
  }
}

// A half-space n.x <= offset: a sphere of radius r whose centre is H above the plane, moving
// at v with n.v < 0, touches it at t = (H - r) / (-n.v); a turned box when its lowest corner,
// H - sum |n.axis_i| h_i, reaches it. toi and cast agree; the normal is -n (towards the
// solid).
TEST(QueryCcd, HalfSpaceAgainstSphereAndBox) {
  test::Random rng(904);
  for (int i = 0; i < 100; ++i) {
    const Vec3 nv = rng.unit_vector();
    const D3 n{double(nv.x), double(nv.y), double(nv.z)};
    const double offset = double(rng.uniform(Real(-2), Real(2)));
    const Json plane{{"type", "halfspace"}, {"normal", js(n)}, {"offset", offset}};
    const bool use_box = i % 2 == 1;
    const D3 h{double(rng.uniform(Real(0.2), Real(1))), double(rng.uniform(Real(0.2), Real(1))),
               double(rng.uniform(Real(0.2), Real(1)))};
    const double r = double(rng.uniform(Real(0.2), Real(1)));
    const Q q = random_rotation(rng);
    const Rot rot = Rot::from_xyzw(q[0], q[1], q[2], q[3]);
    double reach = r;  // how far the shape extends below its centre along -n
    if (use_box)
      reach = std::abs(dot(n, rot.column(0))) * h[0] + std::abs(dot(n, rot.column(1))) * h[1] +
              std::abs(dot(n, rot.column(2))) * h[2];
    const double height = reach + double(rng.uniform(Real(0.1), Real(2)));
    const D3 lateral = rot.column(0);
    // Off the plane's origin sideways (perpendicular to n), `height` above it.
    const D3 centre = add(scale(n, offset + height), scale(sub(lateral, scale(n, dot(n, lateral))), 2.0));
    const D3 v = add(scale(n, -double(rng.uniform(Real(0.5), Real(4)))), scale(lateral, 0.5));
    const double expected = (height - reach) / -dot(n, v);
    const Json shape = use_box ? box(h) : sphere(r);
    const Json from = use_box ? pose(centre, q) : pose(centre);
    const Json to = use_box ? pose(add(centre, v), q) : pose(add(centre, v));
    const Json t = answer({{"op", "toi"}, {"a", mover(shape, from, to)}, {"b", plane}});
    const Json c = answer({{"op", "cast"}, {"a", mover(shape, from)}, {"translation", js(v)}, {"b", plane}});
    if (expected > 1.001) {
      EXPECT_EQ(t["status"], "separated") << t.dump();
      EXPECT_EQ(c["status"], "separated") << c.dump();
      continue;
    }
    if (expected > 0.999) continue;
    for (const Json& a : {t, c}) {
      ASSERT_EQ(a["status"], "hit") << a.dump();
      const double at = a.contains("toi") ? a["toi"].get<double>() : a["t"].get<double>();
      EXPECT_LE(at, expected + kTol) << a.dump();
      EXPECT_GE(at, expected - kDefaultTolerance / -dot(n, v) - 10 * kTol) << a.dump();
      expect_unit(a["normal"], a);
      expect_d3_near(a["normal"], scale(n, -1), kTol, a);
      // The contact point lies on the plane.
      EXPECT_NEAR(dot(n, d3(a["point"])), offset, 1e-3) << a.dump();
    }
  }
}

// The t = 0 contract: touching and moving apart is no hit; touching and moving in is a hit
// at 0; overlapping is initially_overlapping with the depth and the push-out normal.
TEST(QueryCcd, TouchingAndOverlappingAtTheStart) {
  const Json a = mover(sphere(1), pose({0, 0, 0}));
  const Json touching = mover(sphere(0.5), pose({1.5, 0, 0}));
  // b moves away (+x), then in (-x).
  for (const double dx : {1.0, -1.0}) {
    const Json b = mover(sphere(0.5), pose({1.5, 0, 0}), pose({1.5 + dx, 0, 0}));
    const Json t = answer({{"op", "toi"}, {"a", a}, {"b", b}});
    const Json c = answer({{"op", "cast"}, {"a", a}, {"translation", js({-dx, 0, 0})}, {"b", touching}});
    for (const Json& r : {t, c}) {
      if (dx > 0) {
        EXPECT_FALSE(r["hit"].get<bool>()) << r.dump();
        EXPECT_EQ(r["status"], "separated") << r.dump();
        EXPECT_FALSE(r.contains("point"));
      } else {
        EXPECT_TRUE(r["hit"].get<bool>()) << r.dump();
        EXPECT_EQ(r["status"], "hit") << r.dump();
        EXPECT_EQ(r.contains("toi") ? r["toi"] : r["t"], 0.0) << r.dump();
        expect_d3_near(r["normal"], {1, 0, 0}, kTol, r);
        expect_d3_near(r["point"], {1, 0, 0}, kTol, r);
        EXPECT_FALSE(r.contains("depth"));
      }
    }
  }
  // Sliding along: touching and moving sideways is no hit either.
  const Json slide = answer({{"op", "cast"}, {"a", a}, {"translation", js({0, 3, 0})}, {"b", touching}});
  EXPECT_EQ(slide["status"], "separated") << slide.dump();

  // Overlapping spheres in any direction: depth r1 + r2 - |c|, normal along the centre line.
  test::Random rng(905);
  for (int i = 0; i < 100; ++i) {
    const double r1 = double(rng.uniform(Real(0.3), Real(1.5))), r2 = double(rng.uniform(Real(0.3), Real(1.5)));
    const Vec3 u = rng.unit_vector();
    const D3 dir{double(u.x), double(u.y), double(u.z)};
    const double distance = (r1 + r2) * double(rng.uniform(Real(0.2), Real(0.95)));
    const D3 ca{double(rng.uniform(Real(-3), Real(3))), 0.5, -1};
    const D3 cb = add(ca, scale(dir, distance));
    const D3 move = scale(dir, double(rng.uniform(Real(-3), Real(3))));
    const Json t = answer(
        {{"op", "toi"}, {"a", mover(sphere(r1), pose(ca), pose(add(ca, move)))}, {"b", mover(sphere(r2), pose(cb))}});
    const Json c = answer({{"op", "cast"},
                           {"a", mover(sphere(r1), pose(ca))},
                           {"translation", js(move)},
                           {"b", mover(sphere(r2), pose(cb))}});
    for (const Json& r : {t, c}) {
      EXPECT_TRUE(r["hit"].get<bool>()) << r.dump();
      EXPECT_EQ(r["status"], "initially_overlapping") << r.dump();
      EXPECT_EQ(r.contains("toi") ? r["toi"] : r["t"], 0.0) << r.dump();
      EXPECT_NEAR(r["depth"].get<double>(), r1 + r2 - distance, kTol * 10) << r.dump();
      expect_unit(r["normal"], r);
      expect_d3_near(r["normal"], dir, kTol * 10, r);
      // Midway between the deepest points of each sphere.
      const D3 mid = scale(add(add(ca, scale(dir, r1)), sub(cb, scale(dir, r2))), 0.5);
      expect_d3_near(r["point"], mid, kTol * 10, r);
    }
    EXPECT_EQ(t["toi_lower"], 0.0);
    EXPECT_EQ(t["toi_upper"], 0.0);
  }
  // Boxes: the push-out along the axis of least overlap.
  const Json boxes = answer(Json::parse(
      R"({"op":"toi","a":{"type":"box","half_extents":[1,1,1]},"b":{"shape":{"type":"box","half_extents":[1,1,1]},"pose":{"position":[0.2,1.7,0.1]},"pose_end":{"position":[5,5,5]}}})"));
  EXPECT_EQ(boxes["status"], "initially_overlapping") << boxes.dump();
  EXPECT_NEAR(boxes["depth"].get<double>(), 0.3, kTol) << boxes.dump();
  expect_d3_near(boxes["normal"], {0, 1, 0}, kTol, boxes);
}

// safe_step of two spheres: the gap |c| - r1 - r2, less the target, over the closing speed
// n.(v_a - v_b); null when they do not close along n, 0 when already within the target.
TEST(QueryCcd, SafeStepOfSpheresIsGapOverClosingSpeed) {
  test::Random rng(906);
  int finite = 0, never = 0;
  for (int i = 0; i < 300; ++i) {
    const double r1 = double(rng.uniform(Real(0.2), Real(1))), r2 = double(rng.uniform(Real(0.2), Real(1)));
    const D3 ca{double(rng.uniform(Real(-4), Real(4))), double(rng.uniform(Real(-4), Real(4))),
                double(rng.uniform(Real(-4), Real(4)))};
    const Vec3 u = rng.unit_vector();
    const D3 n{double(u.x), double(u.y), double(u.z)};
    const double gap = double(rng.uniform(Real(0.1), Real(3)));
    const D3 cb = add(ca, scale(n, r1 + r2 + gap));
    const D3 va{double(rng.uniform(Real(-3), Real(3))), double(rng.uniform(Real(-3), Real(3))),
                double(rng.uniform(Real(-3), Real(3)))};
    const D3 vb{double(rng.uniform(Real(-3), Real(3))), double(rng.uniform(Real(-3), Real(3))),
                double(rng.uniform(Real(-3), Real(3)))};
    const D3 wa{double(rng.uniform(Real(-3), Real(3))), 0, 1};  // a sphere turning moves no point closer
    const double target = i % 3 == 0 ? double(rng.uniform(Real(0), Real(0.5))) : 0.0;
    Json request{
        {"op", "safe_step"},
        {"a", {{"shape", sphere(r1)}, {"pose", pose(ca)}, {"linear_velocity", js(va)}, {"angular_velocity", js(wa)}}},
        {"b", {{"shape", sphere(r2)}, {"pose", pose(cb)}, {"linear_velocity", js(vb)}}}};
    if (target > 0) request["target_distance"] = target;
    const Json a = answer(request);
    ASSERT_EQ(keys(a), std::vector<std::string>{"dt"});
    const double closing = dot(n, sub(va, vb));
    if (gap <= target) {
      EXPECT_EQ(a["dt"].get<double>(), 0.0) << a.dump();
    } else if (closing <= 1e-3) {
      if (closing < -1e-3) {
        EXPECT_TRUE(a["dt"].is_null()) << a.dump();
        ++never;
      }
    } else {
      const double expected = (gap - target) / closing;
      ASSERT_TRUE(a["dt"].is_number()) << a.dump();
      EXPECT_NEAR(a["dt"].get<double>(), expected, 1e-3 * std::max(1.0, expected) / std::min(1.0, closing)) << a.dump();
      // A safe step is never longer than the gap allows (up to rounding).
      if (closing > 0.1) {
        EXPECT_LE(a["dt"].get<double>(), expected * (1 + 1e-4) + 1e-5) << a.dump();
      }
      ++finite;
    }
  }
  EXPECT_GT(finite, 50);
  EXPECT_GT(never, 50);
}

// safe_step of the paddle of RotatingPaddleHitsRestingBallAtClosedFormAngle turning at 1 rad/s about z, and the ball
// resting above its face: the gap h - w - r closes at most at |n x w| times the box's corner radius (the motion bound
// of safe_step.hpp); a half-space below a falling ball: gap over speed.
TEST(QueryCcd, SafeStepOfTurningBoxAndHalfSpace) {
  const Json paddle = answer(Json::parse(
      R"({"op":"safe_step","a":{"shape":{"type":"box","half_extents":[2,0.1,0.5]},"angular_velocity":[0,0,1]},"b":{"shape":{"type":"sphere","radius":0.4},"pose":{"position":[1.5,1,0]}},"target_distance":0.1})"));
  const double corner = std::sqrt(2.0 * 2.0 + 0.1 * 0.1 + 0.5 * 0.5);
  EXPECT_NEAR(paddle["dt"].get<double>(), (1 - 0.1 - 0.4 - 0.1) / corner, kTol) << paddle.dump();

  const Json ground = answer(Json::parse(
      R"({"op":"safe_step","a":{"type":"halfspace","normal":[0,0,1],"offset":0},"b":{"shape":{"type":"sphere","radius":1},"pose":{"position":[0,0,3]},"linear_velocity":[0,0,-4]}})"));
  EXPECT_NEAR(ground["dt"].get<double>(), 0.5, 1e-4) << ground.dump();
  EXPECT_LE(ground["dt"].get<double>(), 0.5) << ground.dump();
  const Json rising = answer(Json::parse(
      R"({"op":"safe_step","a":{"type":"halfspace","normal":[0,0,1],"offset":0},"b":{"shape":{"type":"sphere","radius":1},"pose":{"position":[0,0,3]},"linear_velocity":[5,0,4]}})"));
  EXPECT_EQ(rising.dump(), R"({"dt":null})");
  const Json resting =
      answer(Json::parse(R"({"op":"safe_step","a":{"type":"sphere","radius":1},"b":{"type":"sphere","radius":1}})"));
  EXPECT_EQ(resting.dump(), R"({"dt":0.0})");
}

// Meshes and compounds on either side, moving or still: a floor mesh and a compound of a ball
// and a cube falling onto it (both touch after 2.5 of 6), answered with the parts.
TEST(QueryCcd, MeshesAndCompounds) {
  const std::string floor =
      R"({"type":"mesh","vertices":[[-5,-5,0],[5,-5,0],[5,5,0],[-5,5,0]],"triangles":[[0,1,2],[0,2,3]],"repair":false})";
  const std::string body =
      R"({"type":"compound","children":[{"shape":{"type":"sphere","radius":0.5},"pose":{"position":[2,1,0]}},{"shape":{"type":"box","half_extents":[0.5,0.5,0.5]},"pose":{"position":[-1,-3,0.5]}}]})";
  const Json t = answer(Json::parse(R"({"op":"toi","a":)" + floor + R"(,"b":{"shape":)" + body +
                                    R"(,"pose":{"position":[0,0,3]},"pose_end":{"position":[0,0,-3]}}})"));
  ASSERT_EQ(t["status"], "hit") << t.dump();
  EXPECT_NEAR(t["toi"].get<double>(), 2.5 / 6, 1e-4) << t.dump();
  expect_d3_near(t["normal"], {0, 0, 1}, kTol, t);
  EXPECT_NEAR(t["point"][2].get<double>(), 0.0, 1e-3) << t.dump();
  ASSERT_TRUE(t.contains("part_a") && t.contains("part_b")) << t.dump();
  EXPECT_EQ(t["part_b"]["child"].get<int>(), 0) << t.dump();  // the ball reaches lower than the cube
  EXPECT_TRUE(t["part_a"].contains("triangle"));

  // The compound cast down at the floor: the ball child reaches it at 2.5 of 6.
  const Json c = answer(Json::parse(R"({"op":"cast","a":{"shape":)" + body +
                                    R"(,"pose":{"position":[0,0,3]}},"translation":[0,0,-6],"b":)" + floor + "}"));
  ASSERT_EQ(c["status"], "hit") << c.dump();
  EXPECT_NEAR(c["t"].get<double>(), 2.5 / 6, 1e-4) << c.dump();
  expect_d3_near(c["normal"], {0, 0, -1}, kTol, c);
  expect_d3_near(c["point"], {2, 1, 0}, 1e-3, c);
  EXPECT_EQ(c["part_a"]["child"].get<int>(), 0) << c.dump();
  EXPECT_EQ(c["part_b"]["triangle"].get<int>(), 0) << c.dump();  // (2, 1) lies in triangle [0, 1, 2]

  // Two meshes: the floor rising into a tetrahedron file hanging above it.
  const Json m = answer(Json::parse(R"({"op":"toi","a":{"shape":)" + floor +
                                    R"(,"pose_end":{"position":[0,0,4]}},"b":{"shape":{"type":"mesh","file":")" +
                                    test::data_file("tetrahedron.obj") + R"("},"pose":{"position":[0.5,0.5,2]}}})"));
  ASSERT_EQ(m["status"], "hit") << m.dump();
  EXPECT_NEAR(m["toi"].get<double>(), 0.5, 1e-4) << m.dump();
  expect_d3_near(m["normal"], {0, 0, 1}, kTol, m);
}

TEST(QueryCcd, OptionsTargetToleranceIterations) {
  // Target distance 0.25: the ball stops 0.25 short of the face, at (1.5 - 0.25) / 6.
  const std::string base =
      R"("a":{"shape":{"type":"sphere","radius":0.5},"pose":{"position":[-3,0,0]},"pose_end":{"position":[3,0,0]}},"b":{"type":"box","half_extents":[1,1,1]})";
  const Json skin = answer(Json::parse(R"({"op":"toi",)" + base + R"(,"target_distance":0.25})"));
  EXPECT_NEAR(skin["toi"].get<double>(), 1.25 / 6, kTol) << skin.dump();
  const Json cast_skin = answer(Json::parse(
      R"({"op":"cast","a":{"shape":{"type":"sphere","radius":0.5},"pose":{"position":[-3,0,0]}},"translation":[6,0,0],"b":{"type":"box","half_extents":[1,1,1]},"target_distance":0.25})"));
  EXPECT_NEAR(cast_skin["t"].get<double>(), 1.25 / 6, kTol) << cast_skin.dump();
  // A loose tolerance on the turning paddle: the hit comes up to 0.05 early, never late.
  const std::string paddle =
      R"("a":{"shape":{"type":"box","half_extents":[2,0.1,0.5]},"pose_end":{"rotation":[0,0,0.70710678,0.70710678]}},"b":{"shape":{"type":"sphere","radius":0.4},"pose":{"position":[1.5,1,0]}})";
  const double theta = std::acos(0.5 / std::hypot(1.5, 1.0)) - std::atan2(1.5, 1.0);
  const double exact = theta / (std::numbers::pi / 2);
  const Json loose = answer(Json::parse(R"({"op":"toi",)" + paddle + R"(,"tolerance":0.05})"));
  EXPECT_LE(loose["toi"].get<double>(), exact + kTol) << loose.dump();
  EXPECT_GE(loose["toi"].get<double>(), exact - 0.05 / (std::numbers::pi / 2 * 1.7) - kTol) << loose.dump();
  const Json tight = answer(Json::parse(R"({"op":"toi",)" + paddle + R"(,"tolerance":0})"));
  EXPECT_NEAR(tight["toi"].get<double>(), exact, 1e-4) << tight.dump();
  // One iteration cannot reach the paddle's hit: the bracket proved so far.
  const Json capped = answer(Json::parse(R"({"op":"toi",)" + paddle + R"(,"max_iterations":1})"));
  EXPECT_EQ(capped["status"], "max_iterations") << capped.dump();
  EXPECT_FALSE(capped["hit"].get<bool>());
  EXPECT_EQ(capped["iterations"].get<int>(), 1);
  EXPECT_LT(capped["toi_lower"].get<double>(), exact);
  EXPECT_EQ(capped["toi"], capped["toi_lower"]);
  EXPECT_EQ(capped["toi_upper"].get<double>(), 1.0);
}

// Every kind of answer has exactly the documented members, in order.
TEST(QueryCcd, AnswersHaveExactlyTheDocumentedMembers) {
  using Keys = std::vector<std::string>;
  const std::string ball = R"({"shape":{"type":"sphere","radius":1},"pose":{"position":[0,0,0]}})";
  const auto toi = [&](const std::string& b, const std::string& extra = "") {
    return answer(Json::parse(R"({"id":"k","op":"toi","a":)" + ball + R"(,"b":)" + b + extra + "}"));
  };
  const Keys toi_hit{"id", "hit", "toi", "toi_lower", "toi_upper", "point", "normal", "status", "iterations"};
  const Keys toi_overlap{"id",    "hit",    "toi",   "toi_lower", "toi_upper",
                         "point", "normal", "depth", "status",    "iterations"};
  const Keys toi_none{"id", "hit", "toi", "toi_lower", "toi_upper", "status", "iterations"};
  EXPECT_EQ(
      keys(
          toi(R"({"shape":{"type":"sphere","radius":1},"pose":{"position":[5,0,0]},"pose_end":{"position":[0,0,0]}})")),
      toi_hit);
  EXPECT_EQ(keys(toi(R"({"shape":{"type":"sphere","radius":1},"pose":{"position":[1,0,0]}})")), toi_overlap);
  EXPECT_EQ(keys(toi(R"({"shape":{"type":"sphere","radius":1},"pose":{"position":[5,0,0]}})")), toi_none);
  EXPECT_EQ(
      keys(toi(R"({"shape":{"type":"sphere","radius":1},"pose":{"position":[5,0,0]},"pose_end":{"position":[0,0,0]}})",
               R"(,"max_iterations":1)")),
      toi_none);
  Keys toi_mesh = toi_hit;
  toi_mesh.insert(toi_mesh.begin() + 7, "part_b");
  EXPECT_EQ(
      keys(toi(
          R"({"shape":{"type":"mesh","vertices":[[-5,-5,0],[5,-5,0],[0,5,0]],"triangles":[[0,1,2]]},"pose":{"position":[0,0,5]},"pose_end":{"position":[0,0,0]}})")),
      toi_mesh);

  const auto cast = [&](const std::string& translation, const std::string& b) {
    return answer(Json::parse(R"({"id":"k","op":"cast","a":)" + ball + R"(,"translation":)" + translation + R"(,"b":)" +
                              b + "}"));
  };
  const std::string far = R"({"shape":{"type":"sphere","radius":1},"pose":{"position":[5,0,0]}})";
  EXPECT_EQ(keys(cast("[5,0,0]", far)), (Keys{"id", "hit", "t", "point", "normal", "status", "iterations"}));
  EXPECT_EQ(keys(cast("[-5,0,0]", far)), (Keys{"id", "hit", "t", "status", "iterations"}));
  EXPECT_EQ(keys(cast("[5,0,0]", R"({"type":"sphere","radius":1})")),
            (Keys{"id", "hit", "t", "point", "normal", "depth", "status", "iterations"}));
  EXPECT_EQ(
      keys(cast(
          "[0,0,-5]",
          R"({"type":"compound","children":[{"shape":{"type":"sphere","radius":1},"pose":{"position":[0,0,-3]}}]})")),
      (Keys{"id", "hit", "t", "point", "normal", "part_b", "status", "iterations"}));

  const Json step = answer(Json::parse(R"({"id":"k","op":"safe_step","a":)" + ball + R"(,"b":)" + far + "}"));
  EXPECT_EQ(step.dump(), R"({"id":"k","dt":null})");
}

void expect_rejected(const std::string& request, const std::string& field, const std::string& code) {
  const Json a = answer(Json::parse(request), false);
  EXPECT_EQ(a.value("field", ""), field) << request << " -> " << a.dump();
  EXPECT_EQ(a.value("code", ""), code) << request << " -> " << a.dump();
  EXPECT_EQ(a.value("error", "").rfind(field + ": ", 0), 0u) << a.dump();
}

TEST(QueryCcd, BadInputNamesTheField) {
  const std::string ball = R"({"type":"sphere","radius":1})";
  const std::string toi = R"({"op":"toi","b":)" + ball + R"(,"a":)";
  expect_rejected(R"({"op":"toi","b":)" + ball + "}", "a", "missing");
  expect_rejected(R"({"op":"toi","a":)" + ball + "}", "b", "missing");
  expect_rejected(toi + "[1]}", "a", "wrong_type");
  expect_rejected(toi + R"({"pose":{}}})", "a.shape", "missing");
  expect_rejected(toi + R"({"shape":{"type":"sphere","radius":0}}})", "a.shape.radius", "non_positive");
  expect_rejected(toi + R"({"type":"sphere","radius":-1}})", "a.radius", "non_positive");
  expect_rejected(toi + R"({"shape":)" + ball + R"(,"pose":{"rotation":[0,0,0,2]}}})", "a.pose.rotation",
                  "invalid_argument");
  expect_rejected(toi + R"({"shape":)" + ball + R"(,"pose_end":{"rotation":[0,0,0,2]}}})", "a.pose_end.rotation",
                  "invalid_argument");
  expect_rejected(toi + R"({"shape":)" + ball + R"(,"pose_end":{"position":[0,"y",0]}}})", "a.pose_end.position.y",
                  "wrong_type");
  expect_rejected(toi + R"({"shape":)" + ball + R"(,"pose_end":{"position":[0,0,1e300]}}})", "a.pose_end.position.z",
                  "out_of_range");
  expect_rejected(toi + R"({"shape":)" + ball + R"(,"velocity":[0,0,1]}})", "a.velocity", "unknown_field");
  expect_rejected(R"({"op":"toi","a":)" + ball + R"(,"b":{"shape":)" + ball + R"(,"pose_end":[0,0,0]}})", "b.pose_end",
                  "wrong_type");
  expect_rejected(toi + ball + R"(,"target_distance":-1})", "target_distance", "negative");
  expect_rejected(toi + ball + R"(,"target_distance":"far"})", "target_distance", "wrong_type");
  expect_rejected(toi + ball + R"(,"tolerance":-0.001})", "tolerance", "negative");
  expect_rejected(toi + ball + R"(,"max_iterations":0})", "max_iterations", "out_of_range");
  expect_rejected(toi + ball + R"(,"max_iterations":-5})", "max_iterations", "out_of_range");
  expect_rejected(toi + ball + R"(,"max_iterations":2.5})", "max_iterations", "wrong_type");
  expect_rejected(toi + ball + R"(,"max_iterations":10000000000})", "max_iterations", "out_of_range");
  expect_rejected(toi + ball + R"(,"translation":[1,0,0]})", "translation", "unknown_field");

  const std::string cast = R"({"op":"cast","b":)" + ball + R"(,"a":)" + ball;
  expect_rejected(cast + "}", "translation", "missing");
  expect_rejected(cast + R"(,"translation":[1,0]})", "translation", "wrong_type");
  expect_rejected(cast + R"(,"translation":[1,0,1e300]})", "translation.z", "out_of_range");
  expect_rejected(R"({"op":"cast","translation":[1,0,0],"a":)" + ball + "}", "b", "missing");
  expect_rejected(
      R"({"op":"cast","translation":[1,0,0],"b":)" + ball + R"(,"a":{"shape":)" + ball + R"(,"pose_end":{}}})",
      "a.pose_end", "unknown_field");
  expect_rejected(R"({"op":"cast","translation":[1,0,0],"a":)" + ball + R"(,"b":{"shape":)" + ball +
                      R"(,"pose":{"position":[0,true,0]}}})",
                  "b.pose.position.y", "wrong_type");
  expect_rejected(R"({"op":"cast","translation":[1,0,0],"a":)" + ball + R"(,"b":{"shape":)" + ball +
                      R"(,"pose":{"rotation":[0,0,0,0.5]}}})",
                  "b.pose.rotation", "invalid_argument");
  expect_rejected(R"({"op":"cast","translation":[1,0,0],"a":)" + ball +
                      R"(,"b":{"type":"mesh","vertices":[[0,0,0],[1,0,0],[0,1,0]],"triangles":[[0,1,3]]}})",
                  "b.triangles[0][2]", "out_of_range");
  expect_rejected(cast + R"(,"translation":[1,0,0],"target_distance":-0.5})", "target_distance", "negative");
  expect_rejected(cast + R"(,"translation":[1,0,0],"tolerance":-1})", "tolerance", "negative");
  expect_rejected(cast + R"(,"translation":[1,0,0],"max_iterations":0})", "max_iterations", "out_of_range");
  expect_rejected(cast + R"(,"translation":[1,0,0],"max_iterations":"many"})", "max_iterations", "wrong_type");
  expect_rejected(cast + R"(,"translation":[1,0,0],"cull_back_faces":1})", "cull_back_faces", "wrong_type");
  expect_rejected(cast + R"(,"translation":[1,0,0],"colour":"red"})", "colour", "unknown_field");

  const std::string step = R"({"op":"safe_step","b":)" + ball + R"(,"a":)";
  expect_rejected(R"({"op":"safe_step","a":)" + ball + "}", "b", "missing");
  expect_rejected(step + R"({"shape":)" + ball + R"(,"linear_velocity":[0,0,"fast"]}})", "a.linear_velocity.z",
                  "wrong_type");
  expect_rejected(step + R"({"shape":)" + ball + R"(,"angular_velocity":[0,0]}})", "a.angular_velocity", "wrong_type");
  expect_rejected(step + R"({"shape":)" + ball + R"(,"pose":{"rotation":[1,1,0,0]}}})", "a.pose.rotation",
                  "invalid_argument");
  expect_rejected(step + R"({"shape":)" + ball + R"(,"pose_end":{}}})", "a.pose_end", "unknown_field");
  expect_rejected(step + ball + R"(,"target_distance":-1})", "target_distance", "negative");
  expect_rejected(step + ball + R"(,"tolerance":0.1})", "tolerance", "unknown_field");
}

// End to end: the three operations through the executable, one answer line each.
TEST(QueryCcd, ExecutableAnswersEachOperation) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "proxima_query_ccd.jsonl";
  {
    std::ofstream out(file);
    out << R"({"id":1,"op":"toi","a":{"shape":{"type":"sphere","radius":0.5},"pose":{"position":[-3,0,0]},"pose_end":{"position":[3,0,0]}},"b":{"type":"box","half_extents":[1,1,1]}})"
        << "\n"
        << R"({"id":2,"op":"cast","a":{"shape":{"type":"sphere","radius":0.5},"pose":{"position":[0,0,3]}},"translation":[0,0,-5],"b":{"type":"halfspace","normal":[0,0,1],"offset":0}})"
        << "\n"
        << R"({"id":3,"op":"safe_step","a":{"type":"sphere","radius":1},"b":{"shape":{"type":"sphere","radius":1},"pose":{"position":[3,0,0]},"linear_velocity":[1,0,0]}})"
        << "\n";
  }
  const test::CliRun run = test::run_cli("query '" + file.string() + "'");
  std::filesystem::remove(file);
  EXPECT_EQ(run.status, 0) << run.output;
  std::vector<Json> lines;
  std::size_t start = 0;
  for (std::size_t end; (end = run.output.find('\n', start)) != std::string::npos; start = end + 1) {
    lines.push_back(Json::parse(run.output.substr(start, end - start)));
  }
  ASSERT_EQ(lines.size(), 3u) << run.output;
  EXPECT_EQ(lines[0]["toi"].get<double>(), 0.25);
  EXPECT_EQ(lines[1]["t"].get<double>(), 0.5);
  EXPECT_TRUE(lines[2]["dt"].is_null());
}

}  // namespace test_query_ccd
}  // namespace proxima
