#pragma once
/// @file fit_obb.hpp
/// Fitting an oriented bounding box to a point set: PCA of the convex hull's surface
/// (Gottschalk), DiTO (Larsson and Kallberg) and a minimum-volume search over the hull's
/// face normals and edge directions.
///
/// Every fitter returns a box containing every input point in the exact sense of
/// Obb::contains, with right-handed orthonormal axes. Errors (all fitters): TooFew for an
/// empty set ("points"), NotFinite / OutOfRange for a bad coordinate ("points[i].x" ...).
/// Flat, collinear and single-point sets give boxes with zero half extents.

#include <proxima/bounds/obb.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <cstddef>
#include <span>

namespace proxima {

/// OBB fitting methods.
enum class ObbFit {
  Pca,       ///< principal axes of the convex hull's surface. O(n log n)
  Dito14,    ///< DiTO with the 7 directions of a 14-DOP. O(n)
  Dito26,    ///< DiTO with the 13 directions of a 26-DOP. O(n)
  MinVolume  ///< best box with one axis on a hull face normal or edge direction. O(h^2 log h) up
             ///< to kObbExactHullVertices hull vertices, O(n log n) beyond (see fit_obb_min_volume)
};

/// Hull vertex count up to which fit_obb_min_volume searches every hull face normal and edge
/// direction (O(h^2 log h): about 0.2 s at this size); larger hulls are searched on a subset.
inline constexpr std::size_t kObbExactHullVertices = 1024;

/// Box on the principal axes of the convex hull's surface: the covariance of the hull's
/// triangles, area-weighted (S. Gottschalk, M. Lin, D. Manocha, "OBBTree", SIGGRAPH 1996,
/// eq. of the continuous covariance over triangles). Using the hull surface rather than the
/// raw points makes the axes independent of interior and clustered points. Sets whose hull
/// is flat or lower-dimensional fall back to the covariance of the points. O(n log n).
Result<Obb> fit_obb_pca(std::span<const Vec3> points);

/// DiTO (Ditetrahedron OBB): extremal points along the 7 (K = 14) or 13 (K = 26) k-DOP
/// directions, a large base triangle from them, the two points farthest from its plane,
/// and the 21 edge-aligned frames of the resulting ditetrahedron's 7 triangles; the frame
/// with the smallest box surface area over the extremal points wins and is fitted to all
/// points; the axis-aligned box is kept when it is better (T. Larsson, L. Kallberg, "Fast
/// Computation of Tight-Fitting Oriented Bounding Boxes", Game Engine Gems 2, 2011). O(n).
Result<Obb> fit_obb_dito(std::span<const Vec3> points, int k = 14);

/// Minimum-volume search over candidate axes: for every face normal and every edge
/// direction of the convex hull, the hull is projected on the plane orthogonal to that
/// axis and the minimum-area enclosing rectangle of the projection is found by rotating
/// calipers (H. Freeman, R. Shapira, CACM 1975; G. Toussaint, 1983); the smallest box wins.
/// The optimal box has a face flush with a hull face or an edge on a hull edge in most
/// cases (J. O'Rourke, "Finding minimal enclosing boxes", 1985, proves two faces flush
/// with hull edges), so this is exact for many inputs and close otherwise; never worse
/// than the axis-aligned box or the PCA box, which are also candidates. Falls back to the
/// plane/line fit for flat sets. O(h (h log h)) for h hull vertices, when h is at most
/// kObbExactHullVertices. Larger hulls would make this quadratic search take seconds to
/// minutes, so the same search runs on the hull of the at most 512 hull vertices extreme
/// along 512 directions spread over the sphere, and the frame it finds competes with the
/// axis-aligned and PCA frames on all hull vertices. Above 8,192 input points the exact hull
/// is not built (qhull's facet merging took minutes on 100,000 points of a sphere): the same
/// subset search runs on the points' own extremes. O(n log n), near-minimal in both cases
/// (the box still contains every point).
Result<Obb> fit_obb_min_volume(std::span<const Vec3> points);

/// Fits with the chosen method.
Result<Obb> fit_obb(std::span<const Vec3> points, ObbFit method = ObbFit::MinVolume);

}  // namespace proxima
