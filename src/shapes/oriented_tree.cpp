// Oriented boxes over a mesh's Bvh topology, and TriangleMesh::oriented_tree (lazy build).
//
// Steps (the covariance fit of Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996, over the
// subtrees of an existing hierarchy instead of a top-down split):
//  1. Copy the triangle corners into BVH leaf order, so every subtree's corners are one
//     contiguous range (the builder partitions the primitives in place).
//  2. Moments of each leaf's corners (count, sum, sum of outer products, in double); an
//     inner node's moments are its children's summed (children follow their parent in the
//     node array, so one reverse pass does it).
//  3. Per node: axes = eigenvectors of the covariance (Jacobi, bounds/fit_util); for a leaf
//     (a nearly flat patch of a few triangles) its summed normal and longest edge instead;
//     extents = minimum and maximum of the range's corners projected on the axes.
// Cost: O(1) per node for steps 2 and the eigen solve, O(corners) per tree level for the
// projections: O(n log n) in all, built once per mesh on the first mesh-mesh query.
#include "shapes/oriented_tree.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>

#include "geometry/eigen_frame.hpp"
#include "shapes/triangle_mesh_derived.hpp"

namespace proxima {
namespace detail {
namespace {

/// Count, sum and sum of outer products of a set of points (double).
struct Moments {
  double n = 0.0;
  glm::dvec3 s{0.0};
  double xx = 0.0, xy = 0.0, xz = 0.0, yy = 0.0, yz = 0.0, zz = 0.0;

  void add(const Vec3& p) {
    const glm::dvec3 d(p);
    n += 1.0;
    s += d;
    xx += d.x * d.x;
    xy += d.x * d.y;
    xz += d.x * d.z;
    yy += d.y * d.y;
    yz += d.y * d.z;
    zz += d.z * d.z;
  }
  void add(const Moments& o) {
    n += o.n;
    s += o.s;
    xx += o.xx;
    xy += o.xy;
    xz += o.xz;
    yy += o.yy;
    yz += o.yz;
    zz += o.zz;
  }
  /// Covariance about the mean.
  glm::dmat3 covariance() const {
    const glm::dvec3 m = s / n;
    glm::dmat3 c;
    c[0][0] = xx / n - m.x * m.x;
    c[1][1] = yy / n - m.y * m.y;
    c[2][2] = zz / n - m.z * m.z;
    c[1][0] = c[0][1] = xy / n - m.x * m.y;
    c[2][0] = c[0][2] = xz / n - m.x * m.z;
    c[2][1] = c[1][2] = yz / n - m.y * m.z;
    return c;
  }
};

/// Axes of a leaf from its triangles: the summed (area-weighted) normal as the third axis,
/// the longest edge of the leaf made orthogonal to it as the first. False when the normal
/// or the edge vanishes (the covariance decides then). Leaves are nearly flat patches, for
/// which this frame is as tight as the covariance one and far cheaper.
bool leaf_frame(std::span<const Vec3> corners, OrientedNode& o) {
  Vec3 normal(Real(0));
  Vec3 edge(Real(0));
  Real edge2 = Real(0);
  for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
    normal += glm::cross(corners[t + 1] - corners[t], corners[t + 2] - corners[t]);
    for (std::size_t c = 0; c < 3; ++c) {
      const Vec3 e = corners[t + (c + 1) % 3] - corners[t + c];
      const Real l2 = glm::dot(e, e);
      if (l2 > edge2) {
        edge2 = l2;
        edge = e;
      }
    }
  }
  const Real n2 = glm::dot(normal, normal);
  if (!(n2 > Real(0)) || !(edge2 > Real(0))) return false;
  const Vec3 z = normal / std::sqrt(n2);
  Vec3 x = edge - glm::dot(edge, z) * z;
  const Real x2 = glm::dot(x, x);
  if (!(x2 > Real(1e-4) * edge2)) return false;
  x /= std::sqrt(x2);
  o.axis[0] = x;
  o.axis[1] = glm::cross(z, x);
  o.axis[2] = z;
  return true;
}

}  // namespace

OrientedTree build_oriented_tree(const Bvh& bvh, std::span<const Vec3> vertices,
                                 std::span<const TriangleIndices> triangles) {
  OrientedTree out;
  const std::span<const BvhNode> nodes = bvh.nodes();
  if (nodes.empty()) return out;
  const std::span<const std::uint32_t> prims = bvh.primitives();
  std::vector<Vec3> corners(3 * prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) {
    const TriangleIndices& t = triangles[prims[i]];
    for (std::size_t c = 0; c < 3; ++c) corners[3 * i + c] = vertices[t[c]];
  }

  const std::size_t n = nodes.size();
  std::vector<Moments> moments(n);
  std::vector<std::uint32_t> begin(n);  // range of primitive slots of each subtree
  std::vector<std::uint32_t> end(n);
  for (std::size_t k = n; k-- > 0;) {
    const BvhNode& node = nodes[k];
    if (node.is_leaf()) {
      begin[k] = node.first;
      end[k] = node.first + node.count;
      for (std::uint32_t c = 3 * begin[k]; c != 3 * end[k]; ++c) moments[k].add(corners[c]);
    } else {
      moments[k] = moments[node.first];
      moments[k].add(moments[node.first + 1]);
      begin[k] = std::min(begin[node.first], begin[node.first + 1]);
      end[k] = std::max(end[node.first], end[node.first + 1]);
    }
  }

  out.nodes.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    OrientedNode& o = out.nodes[k];
    if (!(nodes[k].is_leaf() && leaf_frame(std::span(corners).subspan(3 * begin[k], 3 * (end[k] - begin[k])), o))) {
      glm::dvec3 values;
      const glm::dmat3 frame = detail::symmetric_eigen(moments[k].covariance(), values);
      for (int i = 0; i < 3; ++i) o.axis[i] = Vec3(frame[i]);
    }
    Vec3 lo(std::numeric_limits<Real>::max());
    Vec3 hi(std::numeric_limits<Real>::lowest());
    for (std::uint32_t c = 3 * begin[k]; c != 3 * end[k]; ++c) {
      const Vec3& p = corners[c];
      const Vec3 q(glm::dot(o.axis[0], p), glm::dot(o.axis[1], p), glm::dot(o.axis[2], p));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    const Vec3 mid = (lo + hi) * Real(0.5);
    o.center = o.axis[0] * mid.x + o.axis[1] * mid.y + o.axis[2] * mid.z;
    o.half = (hi - lo) * Real(0.5);
  }
  return out;
}

}  // namespace detail

const detail::OrientedTree& TriangleMesh::oriented_tree() const {
  const Data& d = *data_;
  return d.derived->oriented.get(
      [&d] { return detail::build_oriented_tree(d.bvh, d.mesh.vertices, d.mesh.triangles); });
}

}  // namespace proxima
