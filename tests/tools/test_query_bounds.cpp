// The `bound` and `fit` operations of the query protocol, checked without the library's
// fitters: analytic boxes of rotated boxes, containment of dense surface samples of every
// shape (computed here from the shapes' parametric surfaces and the [x, y, z, w] rotation
// written out as a matrix), tightness of boxes and k-DOPs against the samples' own extremes,
// and the minimal sphere against the lower bound of the point set's diameter.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "json_expect.hpp"
#include "query.hpp"
#include "query_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_query_bounds {

using test::add, test::answer, test::D3, test::d3, test::dot, test::Json, test::js, test::norm, test::Rot, test::scale,
    test::sub;

constexpr double kPiD = 3.14159265358979323846;
constexpr double kTol = test::kJsonTolerance;

struct Pose {
  Json json;
  D3 position;
  Rot rotation;
  D3 apply(const D3& local) const { return add(rotation.apply(local), position); }
};

Pose random_pose(test::Random& rng, Real extent) {
  const Vec3 p = rng.vec3(-extent, extent);
  const Quat q = rng.rotation();
  Pose pose;
  pose.position = {double(p.x), double(p.y), double(p.z)};
  pose.json = Json{{"position", js(pose.position)}, {"rotation", {double(q.x), double(q.y), double(q.z), double(q.w)}}};
  pose.rotation = Rot::from_xyzw(double(q.x), double(q.y), double(q.z), double(q.w));
  return pose;
}

double u01(test::Random& rng) { return double(rng.uniform(Real(0), Real(1))); }

// A random shape (protocol JSON) with points densely covering its surface, local frame,
// including its extreme points (corners, rims, apex, poles).
struct SampledShape {
  Json json;
  std::vector<D3> surface;
};

SampledShape random_shape(test::Random& rng, int kind) {
  SampledShape s;
  const double a = double(rng.uniform(Real(0.2), Real(2)));
  const double b = double(rng.uniform(Real(0.2), Real(2)));
  const double c = double(rng.uniform(Real(0.2), Real(2)));
  const int n = 400;
  auto ring = [&](double radius, double z, int count) {
    for (int k = 0; k < count; ++k) {
      const double t = 2 * kPiD * k / count;
      s.surface.push_back({radius * std::cos(t), radius * std::sin(t), z});
    }
  };
  switch (kind) {
    case 0:  // sphere
      s.json = {{"type", "sphere"}, {"radius", a}};
      for (int k = 0; k < n; ++k) {
        const double z = 2 * u01(rng) - 1, t = 2 * kPiD * u01(rng), r = std::sqrt(std::max(0.0, 1 - z * z));
        s.surface.push_back({a * r * std::cos(t), a * r * std::sin(t), a * z});
      }
      for (int k = 0; k < 3; ++k) {
        D3 e{0, 0, 0};
        e[k] = a;
        s.surface.push_back(e);
        e[k] = -a;
        s.surface.push_back(e);
      }
      break;
    case 1:  // capsule
      s.json = {{"type", "capsule"}, {"radius", a}, {"half_length", b}};
      for (int k = 0; k < n; ++k) {
        const double z = 2 * u01(rng) - 1, t = 2 * kPiD * u01(rng), r = std::sqrt(std::max(0.0, 1 - z * z));
        s.surface.push_back({a * r * std::cos(t), a * r * std::sin(t), a * z + (z >= 0 ? b : -b)});
      }
      s.surface.push_back({0, 0, a + b});
      s.surface.push_back({0, 0, -a - b});
      ring(a, b, 64);
      ring(a, -b, 64);
      break;
    case 2:  // box
      s.json = {{"type", "box"}, {"half_extents", {a, b, c}}};
      for (int k = 0; k < 8; ++k) s.surface.push_back({k & 1 ? a : -a, k & 2 ? b : -b, k & 4 ? c : -c});
      break;
    case 3:  // cylinder
      s.json = {{"type", "cylinder"}, {"radius", a}, {"half_length", b}};
      ring(a, b, 256);
      ring(a, -b, 256);
      break;
    case 4:  // cone: apex at +z half_length, base rim at -z half_length
      s.json = {{"type", "cone"}, {"radius", a}, {"half_length", b}};
      s.surface.push_back({0, 0, b});
      ring(a, -b, 256);
      break;
    case 5:  // ellipsoid
      s.json = {{"type", "ellipsoid"}, {"radii", {a, b, c}}};
      for (int i = 0; i <= 48; ++i) {
        const double phi = kPiD * i / 48;
        for (int k = 0; k < 48; ++k) {
          const double t = 2 * kPiD * k / 48;
          s.surface.push_back({a * std::sin(phi) * std::cos(t), b * std::sin(phi) * std::sin(t), c * std::cos(phi)});
        }
      }
      break;
    default: {  // convex hull of random points: its input points are its extremes
      Json points = Json::array();
      for (int k = 0; k < 12; ++k) {
        const D3 p = {a * (2 * u01(rng) - 1), b * (2 * u01(rng) - 1), c * (2 * u01(rng) - 1)};
        s.surface.push_back(p);
        points.push_back(js(p));
      }
      s.json = {{"type", "convex"}, {"points", points}};
    }
  }
  return s;
}

double distance_to_segment(const D3& p, const D3& a, const D3& b) {
  const D3 ab = sub(b, a);
  const double len2 = dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(dot(sub(p, a), ab) / len2, 0.0, 1.0) : 0.0;
  return norm(sub(p, add(a, scale(ab, t))));
}

// Every bounding volume of every bounded shape contains the shape's world surface samples;
// the box and the k-DOPs are also tight on the samples' extremes (boxes, cylinders and cones
// have their extremes among the samples up to the rings' angular spacing).
TEST(QueryBounds, BoundVolumesContainTheShape) {
  test::Random rng(301);
  for (int trial = 0; trial < 140; ++trial) {
    const int kind = trial % 7;
    const SampledShape shape = random_shape(rng, kind);
    const Pose pose = random_pose(rng, Real(4));
    std::vector<D3> world;
    for (const D3& p : shape.surface) world.push_back(pose.apply(p));
    const Json target = {{"shape", shape.json}, {"pose", pose.json}};
    const std::string where = shape.json.dump();
    const double slack = 50 * kTol;  // sizes and positions are below 10

    const Json box = answer({{"op", "bound"}, {"target", target}, {"volume", "aabb"}});
    const D3 lo = d3(box["min"]), hi = d3(box["max"]);
    for (int k = 0; k < 3; ++k) {
      double sample_lo = 1e300, sample_hi = -1e300;
      for (const D3& p : world) {
        EXPECT_GE(p[k], lo[k] - slack) << where;
        EXPECT_LE(p[k], hi[k] + slack) << where;
        sample_lo = std::min(sample_lo, p[k]);
        sample_hi = std::max(sample_hi, p[k]);
      }
      if (kind == 2 || kind == 6) {  // polytopes: the samples hold the extremes exactly
        EXPECT_NEAR(lo[k], sample_lo, slack) << where;
        EXPECT_NEAR(hi[k], sample_hi, slack) << where;
      }
    }

    const Json sphere = answer({{"op", "bound"}, {"target", target}, {"volume", "sphere"}});
    for (const D3& p : world) {
      EXPECT_LE(norm(sub(p, d3(sphere["center"]))), sphere["radius"].get<double>() + slack) << where;
    }

    const Json obb = answer({{"op", "bound"}, {"target", target}, {"volume", "obb"}});
    for (const D3& p : world) {
      const D3 rel = sub(p, d3(obb["center"]));
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(std::abs(dot(rel, d3(obb["axes"][k]))), d3(obb["half_extents"])[k] + slack) << where;
      }
    }

    const Json capsule = answer({{"op", "bound"}, {"target", target}, {"volume", "capsule"}});
    const D3 p0 = d3(capsule["p0"]), p1 = d3(capsule["p1"]);
    const double radius = capsule["radius"].get<double>();
    for (const D3& p : world) EXPECT_LE(distance_to_segment(p, p0, p1), radius + slack) << where;
    if (kind == 0 || kind == 1) {  // spheres and capsules are their own bounding capsules
      const double expected_radius = shape.json["radius"].get<double>();
      EXPECT_NEAR(radius, expected_radius, slack) << where;
      const double half = kind == 1 ? shape.json["half_length"].get<double>() : 0.0;
      EXPECT_NEAR(norm(sub(p1, p0)), 2 * half, slack) << where;
    }

    for (const char* name : {"kdop6", "kdop14", "kdop18", "kdop26"}) {
      const Json kdop = answer({{"op", "bound"}, {"target", target}, {"volume", name}});
      const std::size_t slabs = kdop["directions"].size();
      EXPECT_EQ(slabs * 2, static_cast<std::size_t>(std::stoi(std::string(name).substr(4)))) << name;
      for (std::size_t i = 0; i < slabs; ++i) {
        const D3 d = d3(kdop["directions"][i]);
        double sample_lo = 1e300, sample_hi = -1e300;
        for (const D3& p : world) {
          sample_lo = std::min(sample_lo, dot(d, p));
          sample_hi = std::max(sample_hi, dot(d, p));
        }
        EXPECT_LE(kdop["min"][i].get<double>(), sample_lo + slack) << where << " " << name;
        EXPECT_GE(kdop["max"][i].get<double>(), sample_hi - slack) << where << " " << name;
        if (kind == 2 || kind == 6) {
          EXPECT_NEAR(kdop["min"][i].get<double>(), sample_lo, slack) << where << " " << name;
          EXPECT_NEAR(kdop["max"][i].get<double>(), sample_hi, slack) << where << " " << name;
        }
      }
    }
  }
}

// A rotated box's AABB, OBB and bounding sphere, analytically.
TEST(QueryBounds, RotatedBoxVolumesAreAnalytic) {
  test::Random rng(302);
  for (int trial = 0; trial < 300; ++trial) {
    const Pose pose = random_pose(rng, Real(10));
    const D3 h = {double(rng.uniform(Real(0.1), Real(3))), double(rng.uniform(Real(0.1), Real(3))),
                  double(rng.uniform(Real(0.1), Real(3)))};
    const Json target = {{"shape", {{"type", "box"}, {"half_extents", js(h)}}}, {"pose", pose.json}};
    const Json box = answer({{"op", "bound"}, {"target", target}, {"volume", "aabb"}});
    for (int k = 0; k < 3; ++k) {
      double extent = 0;
      for (int j = 0; j < 3; ++j) extent += std::abs(pose.rotation.m[k][j]) * h[j];
      EXPECT_NEAR(box["min"][k].get<double>(), pose.position[k] - extent, 100 * kTol);
      EXPECT_NEAR(box["max"][k].get<double>(), pose.position[k] + extent, 100 * kTol);
    }
    const Json obb = answer({{"op", "bound"}, {"target", target}, {"volume", "obb"}});
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(obb["half_extents"][k].get<double>(), h[k], 100 * kTol);
      EXPECT_NEAR(obb["center"][k].get<double>(), pose.position[k], 100 * kTol);
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(obb["axes"][k][r].get<double>(), pose.rotation.m[r][k], 100 * kTol);
    }
    const Json sphere = answer({{"op", "bound"}, {"target", target}, {"volume", "sphere"}});
    EXPECT_NEAR(sphere["radius"].get<double>(), norm(h), 100 * kTol);
  }
}

std::vector<D3> random_points(test::Random& rng, int n, double spread) {
  std::vector<D3> points;
  for (int i = 0; i < n; ++i) {
    points.push_back(
        {spread * (2 * u01(rng) - 1), 0.5 * spread * (2 * u01(rng) - 1), 0.25 * spread * (2 * u01(rng) - 1)});
  }
  return points;
}

Json points_json(const std::vector<D3>& points) {
  Json j = Json::array();
  for (const D3& p : points) j.push_back(js(p));
  return j;
}

// Fitted volumes contain their points; boxes and k-DOPs are attained by them; the minimal
// sphere is at least half the set's diameter and at most Ritter's; the reported volume
// matches the volume's own formula.
TEST(QueryBounds, FittedVolumesContainTheirPoints) {
  test::Random rng(303);
  const double pi = kPiD;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = rng.integer(1, 60);
    const std::vector<D3> points = random_points(rng, n, double(rng.uniform(Real(0.5), Real(5))));
    const Json pj = points_json(points);
    const double slack = 50 * kTol;
    double diameter = 0;
    for (const D3& p : points) {
      for (const D3& q : points) diameter = std::max(diameter, norm(sub(p, q)));
    }

    const Json box = answer({{"op", "fit"}, {"points", pj}, {"volume", "aabb"}});
    double volume = 1;
    for (int k = 0; k < 3; ++k) {
      double lo = 1e300, hi = -1e300;
      for (const D3& p : points) lo = std::min(lo, p[k]), hi = std::max(hi, p[k]);
      EXPECT_NEAR(box["min"][k].get<double>(), lo, slack);
      EXPECT_NEAR(box["max"][k].get<double>(), hi, slack);
      volume *= hi - lo;
    }
    EXPECT_NEAR(box["volume_m3"].get<double>(), volume, slack * std::max(1.0, volume));

    double ritter_radius = 0;
    for (const char* name : {"sphere_ritter", "sphere_centroid", "sphere_aabb", "sphere"}) {
      const Json s = answer({{"op", "fit"}, {"points", pj}, {"volume", name}});
      const double r = s["radius"].get<double>();
      for (const D3& p : points) EXPECT_LE(norm(sub(p, d3(s["center"]))), r + slack) << name;
      EXPECT_NEAR(s["volume_m3"].get<double>(), 4.0 / 3 * pi * r * r * r, slack * std::max(1.0, r * r * r * 4));
      if (std::string(name) == "sphere_ritter") ritter_radius = r;
      if (std::string(name) == "sphere") {
        EXPECT_GE(r, 0.5 * diameter - slack);
        EXPECT_LE(r, ritter_radius + slack);
        if (n == 2) {
          EXPECT_NEAR(r, 0.5 * diameter, slack);
        }
      }
    }

    for (const char* name : {"obb", "obb_pca", "obb_dito14", "obb_dito26"}) {
      const Json obb = answer({{"op", "fit"}, {"points", pj}, {"volume", name}});
      const D3 h = d3(obb["half_extents"]);
      for (const D3& p : points) {
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(std::abs(dot(sub(p, d3(obb["center"])), d3(obb["axes"][k]))), h[k] + slack) << name;
        }
      }
      EXPECT_NEAR(obb["volume_m3"].get<double>(), 8 * h[0] * h[1] * h[2], slack * std::max(1.0, volume));
      if (std::string(name) == "obb") {
        EXPECT_LE(obb["volume_m3"].get<double>(), volume * (1 + 1e-3) + slack);
      }
    }

    const Json capsule = answer({{"op", "fit"}, {"points", pj}, {"volume", "capsule"}});
    for (const D3& p : points) {
      EXPECT_LE(distance_to_segment(p, d3(capsule["p0"]), d3(capsule["p1"])), capsule["radius"].get<double>() + slack);
    }

    for (const char* name : {"kdop6", "kdop14", "kdop18", "kdop26"}) {
      const Json kdop = answer({{"op", "fit"}, {"points", pj}, {"volume", name}});
      for (std::size_t i = 0; i < kdop["directions"].size(); ++i) {
        const D3 d = d3(kdop["directions"][i]);
        double lo = 1e300, hi = -1e300;
        for (const D3& p : points) lo = std::min(lo, dot(d, p)), hi = std::max(hi, dot(d, p));
        EXPECT_NEAR(kdop["min"][i].get<double>(), lo, slack) << name;
        EXPECT_NEAR(kdop["max"][i].get<double>(), hi, slack) << name;
      }
    }

    if (n >= 4) {
      const Json hull = answer({{"op", "fit"}, {"points", pj}, {"volume", "hull"}});
      // Every point lies behind every face plane (plane from the face loop's first vertices).
      const Json& v = hull["vertices"];
      for (const Json& face : hull["faces"]) {
        const D3 a = d3(v[face[0].get<std::size_t>()]);
        const D3 b = d3(v[face[1].get<std::size_t>()]);
        const D3 c = d3(v[face[2].get<std::size_t>()]);
        const D3 ab = sub(b, a), ac = sub(c, a);
        D3 nrm = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]};
        nrm = scale(nrm, 1 / norm(nrm));
        for (const D3& p : points) EXPECT_LE(dot(sub(p, a), nrm), 100 * slack);
      }
      EXPECT_LE(hull["volume_m3"].get<double>(), volume + slack);
    }
  }
}

TEST(QueryBounds, HullOfACubeAndItsInterior) {
  Json points = Json::array();
  for (int k = 0; k < 8; ++k) points.push_back({k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1});
  points.push_back({0.2, 0.1, -0.3});
  points.push_back({0, 0, 0});
  const Json hull = answer({{"op", "fit"}, {"points", points}, {"volume", "hull"}});
  EXPECT_EQ(hull["vertices"].size(), 8u);
  EXPECT_EQ(hull["faces"].size(), 6u);  // coplanar facets merged into squares
  for (const Json& face : hull["faces"]) EXPECT_EQ(face.size(), 4u);
  EXPECT_NEAR(hull["volume_m3"].get<double>(), 8.0, 100 * kTol);
  const Json sphere = answer({{"op", "fit"}, {"points", points}, {"volume", "sphere"}});
  EXPECT_NEAR(sphere["radius"].get<double>(), std::sqrt(3.0), 100 * kTol);
}

TEST(QueryBounds, HalfSpaceHasOnlyUnboundedBoxAndSphere) {
  const Json target = {{"type", "halfspace"}, {"normal", {0, 0, 1}}, {"offset", 2}};
  const Json box = answer({{"op", "bound"}, {"target", target}, {"volume", "aabb"}});
  EXPECT_NEAR(box["max"][2].get<double>(), 2.0, 100 * kTol);
  // Printed as the shortest decimal of the Real: it reads back as exactly -kRealMax.
  EXPECT_EQ(static_cast<Real>(box["min"][2].get<double>()), -kRealMax);
  EXPECT_EQ(static_cast<Real>(box["max"][0].get<double>()), kRealMax);
  for (const char* name : {"obb", "capsule", "kdop14"}) {
    const Json e = answer({{"op", "bound"}, {"target", target}, {"volume", name}}, false);
    EXPECT_EQ(e["field"], "target.shape.type") << name;
    EXPECT_EQ(e["code"], "unbounded") << name;
  }
}

TEST(QueryBounds, FitErrorsNameTheirField) {
  struct Case {
    Json request;
    const char* field;
    const char* code;
  };
  const Case cases[] = {
      {{{"op", "fit"}, {"volume", "sphere"}, {"points", Json::array()}}, "points", "too_few"},
      {{{"op", "fit"}, {"volume", "hull"}, {"points", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}}},
       "points",
       "degenerate"},
      {{{"op", "fit"}, {"volume", "obb"}, {"points", {{0, 0, 0}, {1, 0, 1e300}}}}, "points[1].z", "out_of_range"},
      {{{"op", "fit"}, {"volume", "obb"}, {"points", {{0, 0, 0}, {1, 0}}}}, "points[1]", "wrong_type"},
      {{{"op", "fit"}, {"volume", "obb"}}, "points", "missing"},
      {{{"op", "fit"}, {"points", {{0, 0, 0}}}}, "volume", "missing"},
      {{{"op", "fit"}, {"points", {{0, 0, 0}}}, {"volume", 6}}, "volume", "wrong_type"},
      {{{"op", "bound"}, {"target", {{"type", "sphere"}, {"radius", 1}}}, {"volume", "hull"}},
       "volume",
       "unknown_volume"},
      {{{"op", "bound"}, {"target", {{"type", "sphere"}, {"radius", 0}}}, {"volume", "aabb"}},
       "target.radius",
       "non_positive"},
  };
  for (const Case& c : cases) {
    const Json e = answer(c.request, false);
    EXPECT_EQ(e.value("field", ""), c.field) << c.request.dump() << " -> " << e.dump();
    EXPECT_EQ(e.value("code", ""), c.code) << c.request.dump() << " -> " << e.dump();
  }
}

}  // namespace test_query_bounds
}  // namespace proxima
