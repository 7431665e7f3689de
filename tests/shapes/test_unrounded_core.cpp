// UnroundedCore: the shapes that derive from it still satisfy ConvexShape, keep the size of
// their own members (the base is empty), and answer core_support with support and a zero
// core radius.
#include <gtest/gtest.h>

#include <proxima/shapes/box.hpp>
#include <proxima/shapes/cone.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/cylinder.hpp>
#include <proxima/shapes/ellipsoid.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/point.hpp>
#include <proxima/shapes/segment.hpp>
#include <proxima/shapes/triangle.hpp>

#include <memory>
#include <type_traits>

namespace proxima {
namespace test_unrounded_core {

static_assert(std::is_empty_v<UnroundedCore<Box>>);
static_assert(FiniteConvexShape<Box> && FiniteConvexShape<Cone> && FiniteConvexShape<Cylinder>);
static_assert(FiniteConvexShape<Ellipsoid> && FiniteConvexShape<Segment> && FiniteConvexShape<Triangle>);
static_assert(FiniteConvexShape<Point> && FiniteConvexShape<ConvexHull> && ConvexShape<HalfSpace>);

// Each shape is exactly as large as its own data members.
static_assert(sizeof(Box) == sizeof(Vec3));
static_assert(sizeof(Cone) == 2 * sizeof(Real));
static_assert(sizeof(Cylinder) == 2 * sizeof(Real));
static_assert(sizeof(Ellipsoid) == sizeof(Vec3));
static_assert(sizeof(Point) == 1);
static_assert(sizeof(HalfSpace) == sizeof(Vec3) + sizeof(Real));
static_assert(sizeof(Segment) == 2 * sizeof(Vec3) + sizeof(Real));
static_assert(sizeof(Triangle) == 4 * sizeof(Vec3) + sizeof(Real));

TEST(UnroundedCore, CoreIsTheShape) {
  const Box box = Box::create(Vec3(Real(1), Real(2), Real(3))).value();
  const Vec3 d(Real(1), Real(-1), Real(0.5));
  EXPECT_EQ(box.core_support(d), box.support(d));
  EXPECT_EQ(box.core_radius(), Real(0));
  const Cone cone = Cone::create(Real(1), Real(2)).value();
  EXPECT_EQ(cone.core_support(d), cone.support(d));
  EXPECT_EQ(cone.core_radius(), Real(0));
}

}  // namespace test_unrounded_core
}  // namespace proxima
