// The W8 collision worlds (shared/bench/FORMATS.md: world_mixed_10k, world_terrain,
// world_bullets, world_level_40k) through Proxima's CollisionWorld and, in the same run, the
// peers' collision worlds. One iteration runs frames 1..F of a scene (frames= of the file; the
// environment variable PROXIMA_WORLD_FRAMES caps it, for profiling) on a world built at
// frame 0 and stepped there twice before timing (PROXIMA_WORLD_SCENES, a comma-separated list
// of scene names, loads only those); the poses of every frame are computed by
// the W8 motion rule and converted to each library's pose type before timing. Timed per
// frame: set every moving object's pose, run the library's detection, read the results.
//
//   World/<scene>/proxima/<broadphase>   CollisionWorld, default settings but the broad phase
//                      (continuous detection on: every object CcdMode::Auto); move(batch),
//                      step(dt), then the event arrays and the contact manifolds are read
//   World/<scene>/proxima/tree_discrete  the same with WorldSettings::continuous = false
//   World/<scene>/bullet   Bullet btCollisionWorld, btDbvtBroadphase,
//                      btDefaultCollisionConfiguration, btCollisionDispatcher: setWorldTransform
//                      per moving object, performDiscreteCollisionDetection, then the manifolds
//                      are counted. Static objects: CF_STATIC_OBJECT, StaticFilter, sleeping
//                      (their boxes are not recomputed: setForceUpdateAllAabbs(false)).
//   World/bullets/bullet_ccd  the same plus Bullet's swept-sphere continuous test as
//                      btDiscreteDynamicsWorld runs it for a body whose motion exceeds its
//                      ccd motion threshold: btCollisionWorld::convexSweepTest of a sphere of
//                      the swept-sphere radius (here the sphere's own radius) from the pose of
//                      the previous frame to the new one, against the static objects
//   World/<scene>/fcl      FCL: moving objects in a fcl::DynamicAABBTreeCollisionManagerd
//                      (setTransform + computeAABB per moving object, update()), finite static
//                      objects in a second one; self-collide of the moving manager, moving
//                      against static, and each half-space against the moving manager (FCL's
//                      tree build crashes on half-spaces' unbounded boxes), a callback running
//                      fcl::collide (boolean, default request) per candidate pair
//   World/<scene>/fcl_contacts  the same with the contacts asked for (CollisionRequestd(4, true):
//                      up to 4 contacts with normal and depth, as Proxima's manifolds)
//   World/level_40k_no_city/...  world_level_40k without its 40,000 static boxes (the moving
//                      objects and the ground half-space only)
//
// Shapes: sphere (btSphereShape, fcl::Sphered), box (btBoxShape margin 0, fcl::Boxd of the
// side lengths), capsule (btCapsuleShapeZ(r, 2 hl), fcl::Capsuled(r, 2 hl)), hull (the W2
// points' hull, built once per hull id and shared: btConvexHullShape margin 0, fcl::Convexd
// with qhull's faces), mesh (btBvhTriangleMeshShape, fcl::BVHModel<OBBRSS>), half-space
// (btStaticPlaneShape, fcl::Halfspaced). Margins are 0 so that every library tests the
// written shapes (Bullet's default 0.04 would grow a hull by 0.04, and a plate of world_bullets
// is thinner than twice that).
//
// Counters: per_frame (CPU time per frame); pairs_f0 / pairs_last (touching pairs after the setup step at frame 0
// and after the last frame; MANIFEST.txt gives the exact values of frames 0 and F) and
// pairs_mean (per frame over 1..F); Bullet also bt_manifolds_last (manifolds with at least one
// point: Bullet keeps points up to its contact breaking threshold, 0.02) beside pairs_last
// (manifolds with a point at distance <= 0). world_bullets: impacts (spheres with a first
// impact), impacts_matched (same frame interval and plate as world_bullets_expected.txt),
// impacts_s_1e3 (also s within 1e-3), impacts_extra (impacts the file does not have);
// discrete libraries: spheres touching a plate at some frame (seen_discrete).
//
// Before the benchmarks run, the heap growth of building each world (mallinfo2) is printed
// per object, shared geometry (hulls, meshes, the Bullet and FCL shapes) built beforehand.
#include <benchmark/benchmark.h>

#include <proxima/world/collision_world.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <malloc.h>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "support/ccd_peers.hpp"
#include "support/workloads.hpp"
#include "support/world_workloads.hpp"

#if PROXIMA_HAVE_BULLET
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#endif
#if PROXIMA_HAVE_FCL
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#endif

namespace {

namespace pb = proxima::bench;
using proxima::CollisionWorld;
using proxima::ObjectHandle;
using proxima::ObjectMove;
using proxima::Real;

/// A W8 scene prepared for every library.
struct Scene {
  std::string name;                    ///< benchmark name part ("mixed_10k")
  pb::WorldWorkload workload;          ///< the files
  std::vector<proxima::Shape> shapes;  ///< Proxima shapes by object id (hulls and meshes shared)
  std::vector<std::uint32_t> ids;      ///< the objects of the scene (a subset for level_40k_no_city)
  std::vector<std::uint32_t> moving;   ///< the moving ones among them
  int frames = 0;                      ///< frames timed: 1..frames
  /// poses[k][m]: pose of moving[m] at frame k (W8 motion rule, double).
  std::vector<std::vector<pb::Pose>> poses;
  std::optional<pb::BulletsExpected> expected;  ///< world_bullets only
  pb::CcdHulls hulls;                           ///< vertices and faces for the peers
};

std::vector<std::unique_ptr<Scene>> g_scenes;

const pb::World& world_of(const Scene& s) { return s.workload.world; }

/// Pair counts of a run.
struct PairCounts {
  std::uint64_t f0 = 0, last = 0, sum = 0;
  std::uint64_t extra_last = 0;  ///< Bullet: manifolds with any point after the last frame
};

/// First impact per sphere: frame interval, fraction, plate (world_bullets).
struct Impact {
  int interval = -1;
  double s = -1;
  std::uint32_t plate = 0;
};

void set_common_counters(benchmark::State& state, const Scene& scene, const PairCounts& c) {
  state.counters["per_frame"] = pb::time_per_item(static_cast<std::uint64_t>(scene.frames));
  state.counters["pairs_f0"] = static_cast<double>(c.f0);
  state.counters["pairs_last"] = static_cast<double>(c.last);
  state.counters["pairs_mean"] = static_cast<double>(c.sum) / static_cast<double>(scene.frames);
}

/// Impact counters of world_bullets: found / matched against the file.
void set_impact_counters(benchmark::State& state, const Scene& scene, const std::vector<std::optional<Impact>>& first) {
  if (!scene.expected) return;
  std::uint64_t impacts = 0, matched = 0, close = 0, extra = 0;
  for (const pb::BulletContact& e : scene.expected->contacts) {
    const std::optional<Impact>& f = first[e.sphere];
    impacts += f ? 1u : 0u;
    if (!f) continue;
    if (!e.hit) {
      ++extra;
      continue;
    }
    if (f->interval == e.interval && f->plate == e.plate) {
      ++matched;
      close += std::abs(f->s - e.s) <= 1e-3 ? 1u : 0u;
    }
  }
  state.counters["impacts"] = static_cast<double>(impacts);
  state.counters["impacts_matched"] = static_cast<double>(matched);
  state.counters["impacts_s_1e3"] = static_cast<double>(close);
  state.counters["impacts_extra"] = static_cast<double>(extra);
}

/// Frames to time: the file's, capped by PROXIMA_WORLD_FRAMES.
int frames_to_run(int file_frames) {
  if (const char* cap = std::getenv("PROXIMA_WORLD_FRAMES")) {
    const int n = std::atoi(cap);
    if (n > 0) return std::min(n, file_frames);
  }
  return file_frames;
}

std::size_t heap_in_use() { return mallinfo2().uordblks; }

// -------------------------------------------------------------------------------------
// Proxima
// -------------------------------------------------------------------------------------

/// A CollisionWorld with every object of the scene at its frame-0 pose (object id = handle
/// index for the full scenes; the order of `ids` otherwise).
CollisionWorld make_proxima_world(const Scene& scene, const proxima::WorldSettings& settings,
                                  std::vector<ObjectHandle>& handles) {
  CollisionWorld world = std::move(CollisionWorld::create(settings)).value();
  const pb::World& w = world_of(scene);
  handles.assign(w.objects.size(), ObjectHandle{});
  for (const std::uint32_t id : scene.ids) {
    const pb::WorldObject& o = w.objects[id];
    proxima::ObjectDesc d;
    d.geometry = scene.shapes[id];
    d.pose = pb::world_transform(o, pb::pose_at_frame(w, id, 0));
    d.kind = o.is_static ? proxima::ObjectKind::Static : proxima::ObjectKind::Moving;
    handles[id] = world.add(d).value();
  }
  return world;
}

/// Proxima's world on `broadphase`; `threads` > 0 steps it on a ThreadPool of that many
/// threads (0: the serial executor, the default of step()).
void proxima_world(benchmark::State& state, const Scene* scene, std::string broadphase, bool continuous,
                   std::size_t threads) {
  std::unique_ptr<proxima::ThreadPool> pool;
  if (threads > 0) pool = std::make_unique<proxima::ThreadPool>(threads);
  proxima::Executor& executor = pool ? static_cast<proxima::Executor&>(*pool) : proxima::serial_executor();
  const pb::World& w = world_of(*scene);
  proxima::WorldSettings settings;
  settings.broadphase = broadphase;
  settings.continuous = continuous;
  std::vector<ObjectHandle> handles;
  CollisionWorld world = make_proxima_world(*scene, settings, handles);
  std::vector<std::vector<ObjectMove>> moves(static_cast<std::size_t>(scene->frames) + 1);
  for (int k = 0; k <= scene->frames; ++k) {
    for (std::size_t m = 0; m < scene->moving.size(); ++m) {
      const std::uint32_t id = scene->moving[m];
      moves[k].push_back({handles[id], pb::world_transform(w.objects[id], scene->poses[k][m])});
    }
  }
  const Real dt = static_cast<Real>(w.dt);
  PairCounts counts;
  for (int r = 0; r < 2; ++r) {
    if (world.move(moves[0]) || world.step(dt, executor)) {
      state.SkipWithError("move or step failed at frame 0");
      return;
    }
  }
  counts.f0 = world.contacts().size();
  std::vector<std::optional<Impact>> first(w.objects.size());
  std::uint64_t points = 0, events = 0;
  for (auto _ : state) {
    counts.sum = 0;
    for (int k = 1; k <= scene->frames; ++k) {
      world.move(moves[k], executor);
      world.step(dt, executor);
      const proxima::StepEvents& ev = world.events();
      events += ev.begin.size() + ev.persist.size() + ev.end.size();
      for (const proxima::WorldManifold& m : world.contacts()) points += static_cast<std::uint64_t>(m.count);
      for (const proxima::ImpactEvent& e : ev.impacts) {
        if (!first[e.a.index]) first[e.a.index] = Impact{k - 1, static_cast<double>(e.toi), e.b.index};
      }
      counts.sum += world.contacts().size();
    }
    benchmark::DoNotOptimize(points);
    benchmark::DoNotOptimize(events);
  }
  counts.last = world.contacts().size();
  set_common_counters(state, *scene, counts);
  set_impact_counters(state, *scene, first);
}

// -------------------------------------------------------------------------------------
// Bullet
// -------------------------------------------------------------------------------------

#if PROXIMA_HAVE_BULLET
btVector3 bt_vec(const pb::Vec3d& v) {
  return btVector3(static_cast<btScalar>(v.x), static_cast<btScalar>(v.y), static_cast<btScalar>(v.z));
}

btTransform bt_transform(const pb::Pose& p) {
  return btTransform(btQuaternion(static_cast<btScalar>(p.rotation.x), static_cast<btScalar>(p.rotation.y),
                                  static_cast<btScalar>(p.rotation.z), static_cast<btScalar>(p.rotation.w)),
                     bt_vec(p.position));
}

/// Bullet shapes of a scene: one per object (hulls and meshes shared by id / file).
struct BulletShapes {
  std::vector<std::unique_ptr<btCollisionShape>> own;
  std::vector<std::unique_ptr<btConvexHullShape>> hulls;
  struct Mesh {
    std::vector<int> indices;
    std::vector<btScalar> vertices;
    std::unique_ptr<btTriangleIndexVertexArray> array;
    std::unique_ptr<btBvhTriangleMeshShape> shape;
  };
  std::vector<std::unique_ptr<Mesh>> meshes;
  std::vector<btCollisionShape*> by_object;

  explicit BulletShapes(const Scene& scene) {
    const pb::World& w = world_of(scene);
    for (const auto& verts : scene.hulls.vertices) {
      auto h = std::make_unique<btConvexHullShape>();
      for (const pb::Vec3d& v : verts) h->addPoint(bt_vec(v), false);
      h->recalcLocalAabb();
      h->setMargin(0);
      hulls.push_back(std::move(h));
    }
    std::map<std::string, btCollisionShape*> mesh_by_file;
    by_object.assign(w.objects.size(), nullptr);
    for (const std::uint32_t id : scene.ids) {
      const pb::WorldShape& s = w.objects[id].shape;
      switch (s.kind) {
        case pb::WorldShapeKind::Sphere:
          own.push_back(std::make_unique<btSphereShape>(static_cast<btScalar>(s.radius)));
          break;
        case pb::WorldShapeKind::Box:
          own.push_back(std::make_unique<btBoxShape>(bt_vec(s.half_extents)));
          own.back()->setMargin(0);  // btBoxShape keeps its full half extents
          break;
        case pb::WorldShapeKind::Capsule:
          own.push_back(std::make_unique<btCapsuleShapeZ>(static_cast<btScalar>(s.radius),
                                                          static_cast<btScalar>(2 * s.half_length)));
          break;
        case pb::WorldShapeKind::Hull: by_object[id] = hulls[s.hull].get(); continue;
        case pb::WorldShapeKind::Mesh: {
          auto it = mesh_by_file.find(s.mesh);
          if (it == mesh_by_file.end()) {
            const pb::ObjMesh& obj = scene.workload.meshes.at(s.mesh);
            auto m = std::make_unique<Mesh>();
            for (const auto& t : obj.triangles)
              for (std::uint32_t v : t) m->indices.push_back(static_cast<int>(v));
            for (const pb::Vec3d& v : obj.vertices) {
              m->vertices.push_back(static_cast<btScalar>(v.x));
              m->vertices.push_back(static_cast<btScalar>(v.y));
              m->vertices.push_back(static_cast<btScalar>(v.z));
            }
            m->array = std::make_unique<btTriangleIndexVertexArray>(
                static_cast<int>(obj.triangles.size()), m->indices.data(), static_cast<int>(3 * sizeof(int)),
                static_cast<int>(obj.vertices.size()), m->vertices.data(), static_cast<int>(3 * sizeof(btScalar)));
            m->shape = std::make_unique<btBvhTriangleMeshShape>(m->array.get(), true);
            it = mesh_by_file.emplace(s.mesh, m->shape.get()).first;
            meshes.push_back(std::move(m));
          }
          by_object[id] = it->second;
          continue;
        }
        case pb::WorldShapeKind::HalfSpace:
          own.push_back(std::make_unique<btStaticPlaneShape>(bt_vec(s.normal), static_cast<btScalar>(s.offset)));
          break;
      }
      by_object[id] = own.back().get();
    }
  }
};

/// A btCollisionWorld of the scene at frame 0.
struct BulletWorld {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  std::vector<std::unique_ptr<btCollisionObject>> objects;  // destroyed after the world
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  std::vector<btCollisionObject*> moving;  ///< scene.moving order

  BulletWorld(const Scene& scene, const BulletShapes& shapes) {
    const pb::World& w = world_of(scene);
    world.setForceUpdateAllAabbs(false);
    for (const std::uint32_t id : scene.ids) {
      const pb::WorldObject& o = w.objects[id];
      auto obj = std::make_unique<btCollisionObject>();
      obj->setCollisionShape(shapes.by_object[id]);
      obj->setUserIndex(static_cast<int>(id));
      if (o.shape.kind == pb::WorldShapeKind::HalfSpace)
        obj->setWorldTransform(btTransform::getIdentity());
      else
        obj->setWorldTransform(bt_transform(pb::pose_at_frame(w, id, 0)));
      if (o.is_static) {
        obj->setCollisionFlags(obj->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
        obj->setActivationState(ISLAND_SLEEPING);
        world.addCollisionObject(obj.get(), btBroadphaseProxy::StaticFilter,
                                 btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
      } else {
        obj->setActivationState(DISABLE_DEACTIVATION);
        world.addCollisionObject(obj.get(), btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter);
      }
      objects.push_back(std::move(obj));
    }
    std::vector<btCollisionObject*> by_id(w.objects.size(), nullptr);
    for (auto& o : objects) by_id[static_cast<std::size_t>(o->getUserIndex())] = o.get();
    for (const std::uint32_t id : scene.moving) moving.push_back(by_id[id]);
  }

  /// Manifolds with a point at distance <= 0 (touching) and with any point.
  std::pair<std::uint64_t, std::uint64_t> count() {
    std::uint64_t touching = 0, any = 0;
    const int n = dispatcher.getNumManifolds();
    for (int i = 0; i < n; ++i) {
      const btPersistentManifold* m = dispatcher.getInternalManifoldPointer()[i];
      const int c = m->getNumContacts();
      any += c > 0 ? 1u : 0u;
      for (int p = 0; p < c; ++p) {
        if (m->getContactPoint(p).getDistance() <= 0) {
          ++touching;
          break;
        }
      }
    }
    return {touching, any};
  }
};

std::map<std::string, std::unique_ptr<BulletShapes>> g_bullet_shapes;

void bullet_world(benchmark::State& state, const Scene* scene, bool ccd) {
  const pb::World& w = world_of(*scene);
  const BulletShapes& shapes = *g_bullet_shapes.at(scene->name);
  BulletWorld bw(*scene, shapes);
  std::vector<std::vector<btTransform>> poses(static_cast<std::size_t>(scene->frames) + 1);
  for (int k = 0; k <= scene->frames; ++k)
    for (const pb::Pose& p : scene->poses[k]) poses[k].push_back(bt_transform(p));
  const std::size_t n = bw.moving.size();
  for (int r = 0; r < 2; ++r) {
    for (std::size_t m = 0; m < n; ++m) bw.moving[m]->setWorldTransform(poses[0][m]);
    bw.world.performDiscreteCollisionDetection();
  }
  PairCounts counts;
  counts.f0 = bw.count().first;
  std::vector<std::optional<Impact>> first(w.objects.size());
  std::vector<char> seen(w.objects.size(), 0);
  for (auto _ : state) {
    counts.sum = 0;
    for (int k = 1; k <= scene->frames; ++k) {
      for (std::size_t m = 0; m < n; ++m) bw.moving[m]->setWorldTransform(poses[k][m]);
      bw.world.performDiscreteCollisionDetection();
      if (ccd) {
        // btDiscreteDynamicsWorld's continuous step for a body whose motion exceeds its ccd
        // motion threshold (set to the radius): a sphere of the swept-sphere radius swept
        // from the previous pose to the new one against the static objects.
        for (std::size_t m = 0; m < n; ++m) {
          const btTransform& from = poses[k - 1][m];
          const btTransform& to = poses[k][m];
          const auto* sphere = static_cast<const btSphereShape*>(bw.moving[m]->getCollisionShape());
          const btScalar threshold = sphere->getRadius();
          if ((to.getOrigin() - from.getOrigin()).length2() <= threshold * threshold) continue;
          btCollisionWorld::ClosestConvexResultCallback result(from.getOrigin(), to.getOrigin());
          result.m_collisionFilterGroup = btBroadphaseProxy::DefaultFilter;
          result.m_collisionFilterMask = btBroadphaseProxy::StaticFilter;
          bw.world.convexSweepTest(sphere, from, to, result);
          const auto id = static_cast<std::size_t>(bw.moving[m]->getUserIndex());
          if (result.hasHit() && !first[id])
            first[id] = Impact{k - 1, static_cast<double>(result.m_closestHitFraction),
                               static_cast<std::uint32_t>(result.m_hitCollisionObject->getUserIndex())};
        }
      }
      const auto [touching, any] = bw.count();
      counts.sum += touching;
      counts.extra_last = any;
      if (scene->expected) {
        const int nm = bw.dispatcher.getNumManifolds();
        for (int i = 0; i < nm; ++i) {
          const btPersistentManifold* pm = bw.dispatcher.getInternalManifoldPointer()[i];
          for (int p = 0; p < pm->getNumContacts(); ++p) {
            if (pm->getContactPoint(p).getDistance() > 0) continue;
            seen[static_cast<std::size_t>(pm->getBody0()->getUserIndex())] = 1;
            seen[static_cast<std::size_t>(pm->getBody1()->getUserIndex())] = 1;
          }
        }
      }
    }
  }
  counts.last = bw.count().first;
  set_common_counters(state, *scene, counts);
  state.counters["bt_manifolds_last"] = static_cast<double>(counts.extra_last);
  if (ccd) set_impact_counters(state, *scene, first);
  if (scene->expected) {
    std::uint64_t spheres = 0;
    for (const std::uint32_t id : scene->moving) spheres += seen[id] ? 1u : 0u;
    state.counters["seen_discrete"] = static_cast<double>(spheres);
  }
}
#endif

// -------------------------------------------------------------------------------------
// FCL
// -------------------------------------------------------------------------------------

#if PROXIMA_HAVE_FCL
/// FCL geometries of a scene: one per object (hulls and meshes shared by id / file).
struct FclShapes {
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> by_object;

  explicit FclShapes(const Scene& scene) {
    const pb::World& w = world_of(scene);
    std::vector<std::shared_ptr<fcl::Convexd>> hulls;
    for (std::size_t s = 0; s < scene.hulls.vertices.size(); ++s) {
      auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
      for (const pb::Vec3d& v : scene.hulls.vertices[s]) verts->emplace_back(v.x, v.y, v.z);
      auto faces = std::make_shared<std::vector<int>>(scene.hulls.faces[s]);
      hulls.push_back(std::make_shared<fcl::Convexd>(verts, scene.hulls.face_count[s], faces));
    }
    std::map<std::string, std::shared_ptr<fcl::CollisionGeometryd>> meshes;
    by_object.assign(w.objects.size(), nullptr);
    for (const std::uint32_t id : scene.ids) {
      const pb::WorldShape& s = w.objects[id].shape;
      switch (s.kind) {
        case pb::WorldShapeKind::Sphere: by_object[id] = std::make_shared<fcl::Sphered>(s.radius); break;
        case pb::WorldShapeKind::Box:
          by_object[id] = std::make_shared<fcl::Boxd>(2 * s.half_extents.x, 2 * s.half_extents.y, 2 * s.half_extents.z);
          break;
        case pb::WorldShapeKind::Capsule:
          by_object[id] = std::make_shared<fcl::Capsuled>(s.radius, 2 * s.half_length);
          break;
        case pb::WorldShapeKind::Hull: by_object[id] = hulls[s.hull]; break;
        case pb::WorldShapeKind::Mesh: {
          auto it = meshes.find(s.mesh);
          if (it == meshes.end()) {
            const pb::ObjMesh& obj = scene.workload.meshes.at(s.mesh);
            auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
            std::vector<fcl::Vector3d> verts;
            for (const pb::Vec3d& v : obj.vertices) verts.emplace_back(v.x, v.y, v.z);
            std::vector<fcl::Triangle> tris;
            for (const auto& t : obj.triangles) tris.emplace_back(t[0], t[1], t[2]);
            model->beginModel();
            model->addSubModel(verts, tris);
            model->endModel();
            it = meshes.emplace(s.mesh, model).first;
          }
          by_object[id] = it->second;
          break;
        }
        case pb::WorldShapeKind::HalfSpace:
          by_object[id] =
              std::make_shared<fcl::Halfspaced>(fcl::Vector3d(s.normal.x, s.normal.y, s.normal.z), s.offset);
          break;
      }
    }
  }
};

fcl::Matrix3d fcl_rotation(const pb::Pose& p) {
  return fcl::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
}
fcl::Vector3d fcl_position(const pb::Pose& p) { return {p.position.x, p.position.y, p.position.z}; }

/// FCL's world: two managers (moving, finite static) and the half-spaces.
struct FclWorld {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<fcl::CollisionObjectd*> moving;  ///< scene.moving order
  fcl::DynamicAABBTreeCollisionManagerd moving_manager, static_manager;
  std::vector<fcl::CollisionObjectd*> halfspaces;  ///< each tested against the moving manager
  bool has_static = false;

  FclWorld(const Scene& scene, const FclShapes& shapes) {
    const pb::World& w = world_of(scene);
    std::vector<fcl::CollisionObjectd*> by_id(w.objects.size(), nullptr), statics;
    for (const std::uint32_t id : scene.ids) {
      const pb::WorldObject& o = w.objects[id];
      auto obj = std::make_unique<fcl::CollisionObjectd>(shapes.by_object[id]);
      if (o.shape.kind != pb::WorldShapeKind::HalfSpace) {
        const pb::Pose p = pb::pose_at_frame(w, id, 0);
        obj->setTransform(fcl_rotation(p), fcl_position(p));
      }
      obj->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(id)));
      obj->computeAABB();
      by_id[id] = obj.get();
      if (o.shape.kind == pb::WorldShapeKind::HalfSpace)
        halfspaces.push_back(obj.get());
      else if (o.is_static)
        statics.push_back(obj.get());
      objects.push_back(std::move(obj));
    }
    for (const std::uint32_t id : scene.moving) moving.push_back(by_id[id]);
    moving_manager.registerObjects(moving);
    moving_manager.setup();
    has_static = !statics.empty();
    if (has_static) {
      static_manager.registerObjects(statics);
      static_manager.setup();
    }
  }

  struct Data {
    fcl::CollisionRequestd request;
    std::uint64_t pairs = 0;
    std::vector<char>* seen = nullptr;  ///< world_bullets: objects touching at some frame
  };

  static bool callback(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* raw) {
    auto* data = static_cast<Data*>(raw);
    fcl::CollisionResultd result;
    if (fcl::collide(a, b, data->request, result) > 0) {
      ++data->pairs;
      if (data->seen) {
        (*data->seen)[reinterpret_cast<std::uintptr_t>(a->getUserData())] = 1;
        (*data->seen)[reinterpret_cast<std::uintptr_t>(b->getUserData())] = 1;
      }
    }
    return false;  // all pairs
  }

  /// One frame's detection after the moving objects' poses were set: the touching pairs.
  std::uint64_t detect(bool contacts, std::vector<char>* seen = nullptr) {
    moving_manager.update();
    Data data;
    if (contacts) data.request = fcl::CollisionRequestd(4, true);
    data.seen = seen;
    moving_manager.collide(&data, callback);
    if (has_static) moving_manager.collide(&static_manager, &data, callback);
    for (fcl::CollisionObjectd* h : halfspaces) moving_manager.collide(h, &data, callback);
    return data.pairs;
  }
};

std::map<std::string, std::unique_ptr<FclShapes>> g_fcl_shapes;

void fcl_world(benchmark::State& state, const Scene* scene, bool contacts) {
  const pb::World& w = world_of(*scene);
  FclWorld fw(*scene, *g_fcl_shapes.at(scene->name));
  std::vector<std::vector<std::pair<fcl::Matrix3d, fcl::Vector3d>>> poses(static_cast<std::size_t>(scene->frames) + 1);
  for (int k = 0; k <= scene->frames; ++k)
    for (const pb::Pose& p : scene->poses[k]) poses[k].emplace_back(fcl_rotation(p), fcl_position(p));
  const std::size_t n = fw.moving.size();
  auto set_frame = [&](int k) {
    for (std::size_t m = 0; m < n; ++m) {
      fw.moving[m]->setTransform(poses[k][m].first, poses[k][m].second);
      fw.moving[m]->computeAABB();
    }
  };
  PairCounts counts;
  for (int r = 0; r < 2; ++r) {
    set_frame(0);
    counts.f0 = fw.detect(contacts);
  }
  std::vector<char> seen(w.objects.size(), 0);
  for (auto _ : state) {
    counts.sum = 0;
    for (int k = 1; k <= scene->frames; ++k) {
      set_frame(k);
      counts.last = fw.detect(contacts, scene->expected ? &seen : nullptr);
      counts.sum += counts.last;
    }
  }
  set_common_counters(state, *scene, counts);
  if (scene->expected) {
    std::uint64_t spheres = 0;
    for (const std::uint32_t id : scene->moving) spheres += seen[id] ? 1u : 0u;
    state.counters["seen_discrete"] = static_cast<double>(spheres);
  }
}
#endif

// -------------------------------------------------------------------------------------
// Loading, memory, registration
// -------------------------------------------------------------------------------------

/// Loads a scene; `keep_statics` false drops the finite static objects (level_40k_no_city).
std::unique_ptr<Scene> load_scene(const std::string& dir, const std::string& file, const std::string& name,
                                  bool keep_statics) {
  auto scene = std::make_unique<Scene>();
  scene->name = name;
  auto loaded = pb::read_world_workload(dir, file);
  if (!loaded) {
    pb::report_load_error(loaded.error());
    return nullptr;
  }
  scene->workload = std::move(*loaded);
  auto shapes = pb::to_shapes(scene->workload);
  if (!shapes) {
    pb::report_load_error(shapes.error());
    return nullptr;
  }
  scene->shapes = std::move(*shapes);
  auto hulls = pb::build_ccd_hulls(scene->workload.hulls);
  if (!hulls) {
    pb::report_load_error(hulls.error());
    return nullptr;
  }
  scene->hulls = std::move(*hulls);
  const pb::World& w = scene->workload.world;
  for (std::uint32_t i = 0; i < w.objects.size(); ++i) {
    const pb::WorldObject& o = w.objects[i];
    if (o.is_static && !keep_statics && o.shape.kind != pb::WorldShapeKind::HalfSpace) continue;
    scene->ids.push_back(i);
    if (!o.is_static) scene->moving.push_back(i);
  }
  scene->frames = frames_to_run(w.frames);
  scene->poses.resize(static_cast<std::size_t>(scene->frames) + 1);
  for (int k = 0; k <= scene->frames; ++k)
    for (const std::uint32_t id : scene->moving) scene->poses[k].push_back(pb::pose_at_frame(w, id, k));
  if (name == "bullets") {
    auto e = pb::read_bullets_expected(pb::workload_path(dir, "world_bullets_expected.txt"));
    if (!e) {
      pb::report_load_error(e.error());
      return nullptr;
    }
    scene->expected = std::move(*e);
  }
  return scene;
}

/// Heap growth per object of building each library's world of the scene (shapes built
/// before), printed to stderr.
void report_memory(const Scene& scene) {
  const double n = static_cast<double>(scene.ids.size());
  std::vector<ObjectHandle> handles;
  const std::size_t h0 = heap_in_use();
  {
    CollisionWorld world = make_proxima_world(scene, proxima::WorldSettings{}, handles);
    const std::size_t h1 = heap_in_use();
    (void)world.step(static_cast<Real>(scene.workload.world.dt));
    const std::size_t h2 = heap_in_use();
    std::fprintf(stderr,
                 "memory %s: %zu objects; proxima (tree) %.1f bytes/object after add, %.1f after the first step "
                 "(pair table and manifolds, %zu touching pairs)",
                 scene.name.c_str(), scene.ids.size(), static_cast<double>(h1 - h0) / n,
                 static_cast<double>(h2 - h0) / n, world.contacts().size());
  }
  for (const char* bp : {"sap", "mbp"}) {
    proxima::WorldSettings settings;
    settings.broadphase = bp;
    const std::size_t a = heap_in_use();
    CollisionWorld world = make_proxima_world(scene, settings, handles);
    std::fprintf(stderr, "; %s %.1f after add", bp, static_cast<double>(heap_in_use() - a) / n);
  }
#if PROXIMA_HAVE_BULLET
  {
    const std::size_t a = heap_in_use();
    BulletWorld bw(scene, *g_bullet_shapes.at(scene.name));
    const std::size_t b = heap_in_use();
    bw.world.performDiscreteCollisionDetection();
    std::fprintf(stderr, "; bullet %.1f after add, %.1f after the first step", static_cast<double>(b - a) / n,
                 static_cast<double>(heap_in_use() - a) / n);
  }
#endif
#if PROXIMA_HAVE_FCL
  {
    const std::size_t a = heap_in_use();
    FclWorld fw(scene, *g_fcl_shapes.at(scene.name));
    std::fprintf(stderr, "; fcl %.1f after add", static_cast<double>(heap_in_use() - a) / n);
  }
#endif
  std::fprintf(stderr, "\n");
}

bool register_world(const std::string& dir) {
  struct File {
    const char* file;
    const char* name;
  };
  // PROXIMA_WORLD_SCENES: a comma-separated list of the scenes to load (default: all).
  const char* only = std::getenv("PROXIMA_WORLD_SCENES");
  auto wanted = [&](const std::string& name) {
    if (only == nullptr || *only == 0) return true;
    return ("," + std::string(only) + ",").find("," + name + ",") != std::string::npos;
  };
  for (const File f : {File{"world_mixed_10k.txt", "mixed_10k"}, File{"world_terrain.txt", "terrain"},
                       File{"world_bullets.txt", "bullets"}, File{"world_level_40k.txt", "level_40k"},
                       File{"world_level_40k.txt", "level_40k_no_city"}}) {
    if (!wanted(f.name)) continue;
    auto scene = load_scene(dir, f.file, f.name, std::string(f.name) != "level_40k_no_city");
    if (!scene) return false;
    g_scenes.push_back(std::move(scene));
  }

  std::string peers;
#if PROXIMA_HAVE_BULLET
  peers += " bullet";
#endif
#if PROXIMA_HAVE_FCL
  peers += " fcl";
#endif
  benchmark::AddCustomContext("peers", peers.empty() ? "none" : peers.substr(1));
  for (const auto& s : g_scenes) {
    const Scene* scene = s.get();
#if PROXIMA_HAVE_BULLET
    g_bullet_shapes[scene->name] = std::make_unique<BulletShapes>(*scene);
#endif
#if PROXIMA_HAVE_FCL
    g_fcl_shapes[scene->name] = std::make_unique<FclShapes>(*scene);
#endif
    report_memory(*scene);
    const std::string prefix = "World/" + scene->name + "/";
    for (const char* bp : {"tree", "sap", "mbp"}) {
      benchmark::RegisterBenchmark((prefix + "proxima/" + bp).c_str(), proxima_world, scene, std::string(bp), true,
                                   std::size_t(0))
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark((prefix + "proxima/tree_discrete").c_str(), proxima_world, scene, std::string("tree"),
                                 false, std::size_t(0))
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
    // The step on a ThreadPool of 1 and 2 threads (wall-clock time: the work of the other
    // threads is not in the calling thread's CPU time).
    for (std::size_t threads : {1u, 2u}) {
      benchmark::RegisterBenchmark((prefix + "proxima/tree_threads:" + std::to_string(threads)).c_str(), proxima_world,
                                   scene, std::string("tree"), true, threads)
          ->Iterations(1)
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond);
    }
#if PROXIMA_HAVE_BULLET
    benchmark::RegisterBenchmark((prefix + "bullet").c_str(), bullet_world, scene, false)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
    if (scene->expected) {
      benchmark::RegisterBenchmark((prefix + "bullet_ccd").c_str(), bullet_world, scene, true)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
#endif
#if PROXIMA_HAVE_FCL
    benchmark::RegisterBenchmark((prefix + "fcl").c_str(), fcl_world, scene, false)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((prefix + "fcl_contacts").c_str(), fcl_world, scene, true)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
#endif
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_world); }
