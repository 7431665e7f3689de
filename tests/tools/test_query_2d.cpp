// The query protocol's 2D operations: every op answers as the library does on the same
// shapes, chains report their segment, and bad input names the request's field.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/d2/narrowphase.hpp>
#include <proxima/d2/time_of_impact.hpp>

#include <limits>

#include "json_shapes_2d.hpp"
#include "query_test_util.hpp"

namespace proxima::test {
namespace {

const Json kCircle = {{"type", "circle"}, {"radius", 1}};
const Json kBox = {{"type", "box2d"}, {"half_extents", {1, 2}}};
const Json kFloor = {{"type", "chain"}, {"points", {{10, 0}, {5, 0}, {0, 0}, {-5, 2}}}};

Json placed(const Json& shape, double x, double y, double angle) {
  return {{"shape", shape}, {"pose", {{"position", {x, y}}, {"angle", angle}}}};
}

double num(const Json& j) { return j.get<double>(); }

TEST(Query2d, DistanceAndIntersectAnswerAsTheLibrary) {
  const Json a = placed(kCircle, 0, 0, 0), b = placed(kBox, 3, 0.5, 0.3);
  const Json d = answer({{"op", "distance"}, {"a", a}, {"b", b}});
  const d2::Shape circle = d2::Circle::create(Real(1)).value();
  const d2::Shape box = d2::Polygon::box(Real(1), Real(2)).value();
  const d2::DistanceResult r =
      d2::distance(circle, d2::Pose::identity(), box, d2::Pose::from({3, Real(0.5)}, Real(0.3)));
  EXPECT_NEAR(num(d["distance"]), r.signed_distance, 1e-6);
  EXPECT_NEAR(num(d["point_b"][0]), r.point_b.x, 1e-6);
  EXPECT_NEAR(num(d["normal"][1]), r.normal.y, 1e-6);
  EXPECT_EQ(d["status"], "separated");
  EXPECT_FALSE(answer({{"op", "intersect"}, {"a", a}, {"b", b}})["hit"].get<bool>());
  EXPECT_TRUE(answer({{"op", "intersect"}, {"a", a}, {"b", placed(kBox, 1.5, 0, 0)}})["hit"].get<bool>());
}

TEST(Query2d, CollideGivesTheManifold) {
  const Json ground = {{"type", "box2d"}, {"half_extents", {5, 1}}};
  const Json tri = {{"type", "polygon"}, {"points", {{0, 0}, {1, 0}, {0, 1}}}};
  const Json m = answer({{"op", "collide"}, {"a", ground}, {"b", placed(tri, 0, 0.95, 0)}});
  ASSERT_TRUE(m["hit"].get<bool>());
  ASSERT_EQ(m["contacts"].size(), 2u);
  for (const Json& c : m["contacts"]) {
    EXPECT_NEAR(num(c["depth"]), 0.05, 1e-5);
    EXPECT_NEAR(num(c["point_a"][1]), 1.0, 1e-6);
  }
  const Json chain_contact = answer({{"op", "collide"}, {"a", kFloor}, {"b", placed(kCircle, 2, 0.9, 0)}});
  ASSERT_TRUE(chain_contact["hit"].get<bool>());
  EXPECT_EQ(chain_contact["part_a"]["segment"], 1);
  EXPECT_NEAR(num(chain_contact["normal"][1]), 1.0, 1e-6);
}

TEST(Query2d, RaysContainmentClosestPointAndMass) {
  const Json hit = answer({{"op", "raycast"}, {"target", kFloor}, {"origin", {2, 3}}, {"direction", {0, -1}}});
  ASSERT_TRUE(hit["hit"].get<bool>());
  EXPECT_NEAR(num(hit["t"]), 3.0, 1e-6);
  EXPECT_EQ(hit["part"]["segment"], 1);
  EXPECT_FALSE(
      answer({{"op", "raycast"}, {"target", kFloor}, {"origin", {2, -3}}, {"direction", {0, 1}}})["hit"].get<bool>());
  EXPECT_TRUE(
      answer({{"op", "contains"}, {"target", placed(kBox, 1, 1, 0)}, {"point", {1.5, 2.5}}})["inside"].get<bool>());
  const Json cp = answer({{"op", "closest_point"}, {"target", kCircle}, {"point", {3, 0}}});
  EXPECT_NEAR(num(cp["distance"]), 2.0, 1e-6);
  const Json mass = answer({{"op", "mass"}, {"target", placed(kBox, 1, 2, 0)}, {"density", 2}});
  EXPECT_NEAR(num(mass["mass"]), 16.0, 1e-5);
  EXPECT_NEAR(num(mass["centroid"][1]), 2.0, 1e-6);
  EXPECT_NEAR(num(mass["inertia"]), 16.0 * (4 + 16) / 12.0, 1e-4);
}

TEST(Query2d, ToiTurnsByTheAnglesDifferenceAndCastsMoveA) {
  // The paddle of the library's analytic test: half a turn, asked as pose_end.angle = pi.
  const Json paddle = {{"type", "capsule2d"}, {"vertices", {{-2, 0}, {2, 0}}}, {"radius", 0.1}};
  const Json toi = answer({{"op", "toi"},
                           {"a", {{"shape", paddle}, {"pose_end", {{"angle", M_PI}}}}},
                           {"b", placed({{"type", "circle"}, {"radius", 0.2}}, -1, 1, 0)}});
  ASSERT_TRUE(toi["hit"].get<bool>());
  const double phi = 3 * M_PI / 4 - std::asin(0.3 / std::sqrt(2.0));
  EXPECT_NEAR(num(toi["toi"]), phi / M_PI, 2e-4);
  // Two full turns of a box next to a wall: the corner sweeps it in the first quarter.
  const Json spin = answer({{"op", "toi"},
                            {"a", {{"shape", kBox}, {"pose_end", {{"angle", 4 * M_PI}}}}},
                            {"b", placed({{"type", "segment2d"}, {"vertices", {{0, -5}, {0, 5}}}}, 2.1, 0, 0)}});
  ASSERT_TRUE(spin["hit"].get<bool>());
  EXPECT_LT(num(spin["toi"]), 0.125);
  const Json cast = answer({{"op", "cast"},
                            {"a", placed({{"type", "circle"}, {"radius", 0.05}}, 2, 10, 0)},
                            {"translation", {0, -100}},
                            {"b", kFloor}});
  ASSERT_TRUE(cast["hit"].get<bool>());
  EXPECT_NEAR(num(cast["t"]), 0.0995, 1e-5);
  EXPECT_EQ(cast["part_b"]["segment"], 1);
}

TEST(Query2d, BadInputNamesTheField) {
  const auto field = [](const Json& request) { return answer(request, false)["field"].get<std::string>(); };
  EXPECT_EQ(field({{"op", "distance"}, {"a", {{"type", "circle"}, {"radius", -1}}}, {"b", kCircle}}), "a.radius");
  EXPECT_EQ(field({{"op", "distance"}, {"a", {{"type", "polygon"}, {"points", {{0, 0}, {1, 1}}}}}, {"b", kCircle}}),
            "a.points");
  EXPECT_EQ(field({{"op", "intersect"}, {"a", kCircle}, {"b", {{"type", "sphere"}, {"radius", 1}}}}), "b.type");
  EXPECT_EQ(field({{"op", "distance"},
                   {"a", placed(kCircle, 0, 0, 0)},
                   {"b", {{"shape", kCircle}, {"pose", {{"position", {1, 2, 3}}}}}}}),
            "b.pose.position");
  EXPECT_EQ(field({{"op", "collide"}, {"a", kCircle}, {"b", kCircle}, {"contact_distance", -1}}), "contact_distance");
  EXPECT_EQ(field({{"op", "cast"}, {"a", kCircle}, {"translation", {1, 2, 3}}, {"b", kCircle}}), "translation");
  EXPECT_EQ(field({{"op", "toi"}, {"a", kCircle}, {"b", kCircle}, {"tolerance", -1}}), "tolerance");
  EXPECT_EQ(field({{"op", "mass"}, {"target", kFloor}}), "target.shape");
  // Past the number range (density times size^4 overflows): refused on the density.
  const double huge_density = double(std::numeric_limits<Real>::max()) / 10;
  EXPECT_EQ(field({{"op", "mass"},
                   {"target", {{"type", "box2d"}, {"half_extents", {double(kMaxCoordinate), double(kMaxCoordinate)}}}},
                   {"density", huge_density}}),
            "density");
  EXPECT_EQ(field({{"op", "distance"}, {"a", {{"type", "chain"}, {"points", {{0, 0}, {0, 0}}}}}, {"b", kCircle}}),
            "a.points[1]");
}

}  // namespace
}  // namespace proxima::test
