#pragma once
/// @file embree_scene.hpp
/// EmbreeScene: one TriangleMesh in an Embree 3 scene (float vertices, robust traversal,
/// high build quality, one thread), closest hits by rtcIntersect1. Header-only, shared by
/// the mesh benchmark and the Embree comparison test; include it only where
/// PROXIMA_HAVE_EMBREE is set (the target links Embree).

#include <proxima/shapes/triangle_mesh.hpp>

#include <cstddef>
#include <embree3/rtcore.h>
#include <optional>
#include <utility>

#include "support/workloads.hpp"

namespace proxima::bench {

/// An Embree scene holding one mesh. Embree's SIMD code computes with infinities and NaN
/// lanes: wrap construction and queries in a scope without floating-point traps in tests.
class EmbreeScene {
 public:
  /// Builds the scene over the mesh's vertices (rounded to float) and triangles.
  explicit EmbreeScene(const TriangleMesh& mesh) {
    device_ = rtcNewDevice("threads=1");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.vertices().size()));
    for (std::size_t i = 0; i < mesh.vertices().size(); ++i)
      for (int a = 0; a < 3; ++a) v[3 * i + std::size_t(a)] = static_cast<float>(mesh.vertices()[i][a]);
    auto* ix = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), mesh.triangle_count()));
    for (std::size_t i = 0; i < mesh.triangle_count(); ++i)
      for (std::size_t k = 0; k < 3; ++k) ix[3 * i + k] = mesh.triangles()[i][k];
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// Closest hit of a W5 query within [0, max_t]: (t, triangle index), or nothing.
  std::optional<std::pair<float, unsigned>> intersect(const RayQuery& q) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = float(q.origin.x);
    rh.ray.org_y = float(q.origin.y);
    rh.ray.org_z = float(q.origin.z);
    rh.ray.dir_x = float(q.direction.x);
    rh.ray.dir_y = float(q.direction.y);
    rh.ray.dir_z = float(q.direction.z);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = float(q.max_t);
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return std::make_pair(rh.ray.tfar, rh.hit.primID);
  }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace proxima::bench
