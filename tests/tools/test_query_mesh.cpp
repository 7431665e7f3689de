// Query protocol with meshes and compounds: a 12-triangle mesh of a box answers raycast,
// intersect, distance, collide, bound, mass, contains and closest_point like the convex box
// (the protocol's convex path, which does not touch the mesh code) and like the test's own
// slab ray cast; a compound answers like the minimum / union over its children queried one
// by one; a mesh file answers like the same mesh given inline; errors name their field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "json_expect.hpp"
#include "query_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_query_mesh {

using test::answer;
using test::d3;
using test::D3;
using test::Json;

constexpr bool kFloat = sizeof(Real) == 4;
const double kTol = kFloat ? 2e-4 : 1e-9;

std::string data_file(const std::string& name) { return std::string(PROXIMA_TOOLS_TEST_DATA) + "/" + name; }

/// The box [-h, h] as 8 vertices and 12 outward triangles.
Json box_mesh(const D3& h) {
  Json vertices = Json::array();
  for (int i = 0; i < 8; ++i) {
    vertices.push_back({(i & 1) ? h[0] : -h[0], (i & 2) ? h[1] : -h[1], (i & 4) ? h[2] : -h[2]});
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  Json triangles = Json::array();
  for (const auto& q : quads) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  }
  return Json{{"type", "mesh"}, {"vertices", vertices}, {"triangles", triangles}};
}

Json box_shape(const D3& h) { return Json{{"type", "box"}, {"half_extents", test::js(h)}}; }

Json pose_json(test::Random& rng, double extent) {
  const Quat q = rng.rotation();
  const Vec3 p = rng.vec3(Real(-extent), Real(extent));
  return Json{{"position", {p.x, p.y, p.z}}, {"rotation", {q.x, q.y, q.z, q.w}}};
}

/// Slab ray cast against the box [-h, h] placed at `pose`: the entry t, or -1 on a miss
/// (origins outside the box only).
double slab_ray(const D3& h, const Json& pose, const D3& origin, const D3& dir) {
  const auto& r = pose["rotation"];
  const test::Rot rot =
      test::Rot::from_xyzw(r[0].get<double>(), r[1].get<double>(), r[2].get<double>(), r[3].get<double>());
  const D3 o = rot.apply_inverse(test::sub(origin, d3(pose["position"])));
  const D3 d = rot.apply_inverse(dir);
  double t0 = 0, t1 = 1e30;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-300) {
      if (std::abs(o[a]) > h[a]) return -1;
      continue;
    }
    double ta = (-h[a] - o[a]) / d[a];
    double tb = (h[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 ? t0 : -1;
}

TEST(QueryMesh, RaycastMatchesSlabsAndTheConvexBox) {
  test::Random rng(501);
  int hits = 0;
  for (int i = 0; i < 300; ++i) {
    const D3 h{rng.uniform(Real(0.2), Real(2)), rng.uniform(Real(0.2), Real(2)), rng.uniform(Real(0.2), Real(2))};
    const Json pose = pose_json(rng, 3);
    const Vec3 o = rng.unit_vector() * Real(8);
    const Vec3 aim =
        rng.vec3(Real(-1.5), Real(1.5)) +
        Vec3(pose["position"][0].get<Real>(), pose["position"][1].get<Real>(), pose["position"][2].get<Real>());
    const Vec3 dir = glm::normalize(aim - o);
    const D3 origin{o.x, o.y, o.z};
    const D3 direction{dir.x, dir.y, dir.z};
    Json request{{"op", "raycast"}, {"origin", test::js(origin)}, {"direction", test::js(direction)}};
    request["target"] = Json{{"shape", box_mesh(h)}, {"pose", pose}};
    const Json mesh = answer(request);
    request["target"] = Json{{"shape", box_shape(h)}, {"pose", pose}};
    const Json convex = answer(request);
    const double t = slab_ray(h, pose, origin, direction);
    // Grazing rays (entry and exit within tolerance) may go either way.
    if (mesh["hit"] != convex["hit"]) {
      EXPECT_LT(std::abs(t), 1e-2) << i;
      continue;
    }
    ASSERT_EQ(mesh["hit"].get<bool>(), t >= 0) << i;
    if (!mesh["hit"].get<bool>()) continue;
    ++hits;
    EXPECT_NEAR(mesh["t"].get<double>(), t, 8 * kTol) << i;
    EXPECT_NEAR(mesh["t"].get<double>(), convex["t"].get<double>(), 8 * kTol) << i;
    EXPECT_LT(mesh["triangle"].get<int>(), 12);
    EXPECT_NEAR(test::dot(d3(mesh["normal"]), d3(convex["normal"])), 1.0, 1e-3) << i;
  }
  EXPECT_GT(hits, 150);
}

TEST(QueryMesh, PairsMatchTheConvexBox) {
  test::Random rng(502);
  for (int i = 0; i < 200; ++i) {
    const D3 h{rng.uniform(Real(0.3), Real(1.5)), rng.uniform(Real(0.3), Real(1.5)), rng.uniform(Real(0.3), Real(1.5))};
    const Json pose = pose_json(rng, 1);
    const double radius = rng.uniform(Real(0.1), Real(1));
    const Json sphere{{"shape", {{"type", "sphere"}, {"radius", radius}}}, {"pose", pose_json(rng, 3)}};
    // Only spheres whose centre is outside the box: the mesh is a surface, the box a solid.
    Json contains{{"op", "contains"},
                  {"target", {{"shape", box_shape(h)}, {"pose", pose}}},
                  {"point", sphere["pose"]["position"]}};
    if (answer(contains)["inside"].get<bool>()) continue;
    for (const char* op : {"intersect", "distance", "collide"}) {
      Json request{{"op", op}, {"b", sphere}};
      request["a"] = Json{{"shape", box_mesh(h)}, {"pose", pose}};
      const Json mesh = answer(request);
      request["a"] = Json{{"shape", box_shape(h)}, {"pose", pose}};
      const Json convex = answer(request);
      if (std::string(op) == "distance") {
        const double d = convex["distance"].get<double>();
        EXPECT_NEAR(mesh["distance"].get<double>(), d, 1e-3 + 1e-3 * std::abs(d)) << i;
        if (d > 1e-3) {
          EXPECT_LT(test::norm(test::sub(d3(mesh["point_a"]), d3(convex["point_a"]))), 2e-3) << i;
          EXPECT_TRUE(mesh.contains("part_a"));
        }
      } else if (std::abs(
                     answer(Json{{"op", "distance"}, {"a", request["a"]}, {"b", sphere}})["distance"].get<double>()) >
                 1e-3) {
        EXPECT_EQ(mesh["hit"], convex["hit"]) << op << " " << i;
      }
    }
  }
}

TEST(QueryMesh, BoundMassContainsClosestPoint) {
  test::Random rng(503);
  for (int i = 0; i < 50; ++i) {
    const D3 h{rng.uniform(Real(0.3), Real(1.5)), rng.uniform(Real(0.3), Real(1.5)), rng.uniform(Real(0.3), Real(1.5))};
    const Json pose = pose_json(rng, 2);
    const Json mesh_target{{"shape", box_mesh(h)}, {"pose", pose}};
    const Json box_target{{"shape", box_shape(h)}, {"pose", pose}};
    for (const char* volume : {"aabb", "obb", "kdop14"}) {
      const Json m = answer(Json{{"op", "bound"}, {"target", mesh_target}, {"volume", volume}});
      const Json c = answer(Json{{"op", "bound"}, {"target", box_target}, {"volume", volume}});
      if (std::string(volume) == "aabb") {
        for (const char* k : {"min", "max"}) {
          for (int a = 0; a < 3; ++a) EXPECT_NEAR(m[k][a].get<double>(), c[k][a].get<double>(), 1e-3) << i;
        }
      } else if (std::string(volume) == "obb") {
        EXPECT_NEAR(m["half_extents"][0].get<double>() * m["half_extents"][1].get<double>() *
                        m["half_extents"][2].get<double>(),
                    h[0] * h[1] * h[2], 1e-2 * h[0] * h[1] * h[2])
            << i;
      }
    }
    const Json mm = answer(Json{{"op", "mass"}, {"target", mesh_target}});
    const Json mc = answer(Json{{"op", "mass"}, {"target", box_target}});
    EXPECT_NEAR(mm["volume"].get<double>(), 8 * h[0] * h[1] * h[2], 1e-4);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(mm["inertia"][r][c].get<double>(), mc["inertia"][r][c].get<double>(), 1e-3);
    }
    const Vec3 p = rng.vec3(Real(-4), Real(4));
    const Json point = {p.x, p.y, p.z};
    const Json in_m = answer(Json{{"op", "contains"}, {"target", mesh_target}, {"point", point}});
    const Json in_c = answer(Json{{"op", "contains"}, {"target", box_target}, {"point", point}});
    const Json cp_m = answer(Json{{"op", "closest_point"}, {"target", mesh_target}, {"point", point}});
    const Json cp_c = answer(Json{{"op", "closest_point"}, {"target", box_target}, {"point", point}});
    if (std::abs(cp_c["distance"].get<double>()) > 1e-3) {
      EXPECT_EQ(in_m, in_c) << i;
      EXPECT_NEAR(cp_m["distance"].get<double>(), cp_c["distance"].get<double>(), 1e-3) << i;
    }
  }
}

TEST(QueryMesh, CompoundIsTheUnionOfItsChildren) {
  test::Random rng(504);
  for (int i = 0; i < 100; ++i) {
    const D3 h{0.5, 0.7, 0.3};
    const Json p1 = pose_json(rng, 2);
    const Json p2 = pose_json(rng, 2);
    const Json p3 = pose_json(rng, 1);
    const Json child1{{"shape", box_shape(h)}, {"pose", p1}};
    const Json child2{{"shape", {{"type", "capsule"}, {"radius", 0.3}, {"half_length", 0.6}}}, {"pose", p2}};
    // Nested: a compound holding a mesh box, at the identity inside the outer compound.
    const Json child3{{"shape", {{"type", "compound"}, {"children", {{{"shape", box_mesh(h)}, {"pose", p3}}}}}}};
    const Json compound{{"type", "compound"}, {"children", {child1, child2, child3}}};
    const Json parts[3] = {child1, child2, Json{{"shape", box_mesh(h)}, {"pose", p3}}};
    const Json sphere{{"shape", {{"type", "sphere"}, {"radius", 0.4}}}, {"pose", pose_json(rng, 4)}};

    double best = 1e30;
    bool any = false;
    double tmin = 1e30;
    const Vec3 o = rng.unit_vector() * Real(9);
    const Vec3 dir = glm::normalize(rng.vec3(Real(-1), Real(1)) - o);
    const Json origin = {o.x, o.y, o.z};
    const Json direction = {dir.x, dir.y, dir.z};
    bool outside = true;
    for (const Json& part : parts) {
      const Json d = answer(Json{{"op", "distance"}, {"a", part}, {"b", sphere}});
      best = std::min(best, d["distance"].get<double>());
      any = any || answer(Json{{"op", "intersect"}, {"a", part}, {"b", sphere}})["hit"].get<bool>();
      const Json r = answer(Json{{"op", "raycast"}, {"target", part}, {"origin", origin}, {"direction", direction}});
      if (r["hit"].get<bool>()) tmin = std::min(tmin, r["t"].get<double>());
      if (answer(Json{{"op", "contains"}, {"target", part}, {"point", sphere["pose"]["position"]}})["inside"]
              .get<bool>()) {
        outside = false;
      }
    }
    const Json d = answer(Json{{"op", "distance"}, {"a", compound}, {"b", sphere}});
    if (outside && best > -0.05) {
      EXPECT_NEAR(d["distance"].get<double>(), best, 1e-3) << i;
    }
    if (std::abs(best) > 1e-3 && outside) {
      EXPECT_EQ(answer(Json{{"op", "intersect"}, {"a", compound}, {"b", sphere}})["hit"].get<bool>(), any) << i;
    }
    const Json r = answer(Json{{"op", "raycast"}, {"target", compound}, {"origin", origin}, {"direction", direction}});
    EXPECT_EQ(r["hit"].get<bool>(), tmin < 1e30) << i;
    if (r["hit"].get<bool>() && tmin < 1e30) {
      EXPECT_NEAR(r["t"].get<double>(), tmin, 1e-3) << i;
      EXPECT_TRUE(r.contains("child"));
    }
    // Box of the compound: the union of the children's boxes.
    const Json box = answer(Json{{"op", "bound"}, {"target", compound}, {"volume", "aabb"}});
    D3 lo{1e30, 1e30, 1e30}, hi{-1e30, -1e30, -1e30};
    for (const Json& part : parts) {
      const Json b = answer(Json{{"op", "bound"}, {"target", part}, {"volume", "aabb"}});
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], b["min"][a].get<double>());
        hi[a] = std::max(hi[a], b["max"][a].get<double>());
      }
    }
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(box["min"][a].get<double>(), lo[a], 1e-3);
      EXPECT_NEAR(box["max"][a].get<double>(), hi[a], 1e-3);
    }
  }
}

TEST(QueryMesh, FileAndInlineMeshesAnswerAlike) {
  const Json inline_mesh{{"type", "mesh"},
                         {"vertices", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                         {"triangles", {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}}};
  for (const char* file : {"tetrahedron.obj", "tetrahedron.stl", "tetrahedron.ply"}) {
    const Json file_mesh{{"type", "mesh"}, {"file", data_file(file)}};
    const Json sphere{{"shape", {{"type", "sphere"}, {"radius", 0.25}}}, {"pose", {{"position", {1, 1, 1}}}}};
    for (const Json& request : {Json{{"op", "distance"}, {"b", sphere}}, Json{{"op", "collide"}, {"b", sphere}},
                                Json{{"op", "mass"}}, Json{{"op", "bound"}, {"volume", "sphere"}},
                                Json{{"op", "raycast"}, {"origin", {0.2, 0.2, 3}}, {"direction", {0, 0, -1}}}}) {
      Json a = request;
      Json b = request;
      const char* side = request.contains("b") ? "a" : "target";
      a[side] = file_mesh;
      b[side] = inline_mesh;
      test::expect_json_near(answer(a), answer(b), std::string(file) + " " + request.dump(), 1e-6);
    }
  }
}

TEST(QueryMesh, Errors) {
  struct Case {
    Json target;
    const char* field;
    const char* code;
  };
  const Json box = box_mesh({1, 1, 1});
  Json bad_index = box;
  bad_index["triangles"][4][2] = 8;
  Json bad_vertex = box;
  bad_vertex["vertices"][7][0] = "x";
  Json negative = box;
  negative["triangles"][1][0] = -1;
  Json short_triangle = box;
  short_triangle["triangles"][2] = {1, 2};
  Json both = box;
  both["file"] = data_file("tetrahedron.obj");
  Json repair = box;
  repair["repair"] = "yes";
  const Case cases[] = {
      {bad_index, "target.triangles[4][2]", "out_of_range"},
      {bad_vertex, "target.vertices[7].x", "wrong_type"},
      {negative, "target.triangles[1][0]", "wrong_type"},
      {short_triangle, "target.triangles[2]", "wrong_type"},
      {both, "target.file", "invalid_argument"},
      {repair, "target.repair", "wrong_type"},
      {Json{{"type", "mesh"}, {"vertices", {{0, 0, 0}}}, {"triangles", Json::array()}}, "target.triangles", "too_few"},
      {Json{{"type", "mesh"}, {"file", data_file("missing.obj")}}, "target.file", "invalid_argument"},
      {Json{{"type", "mesh"}, {"file", data_file("not_a_mesh.obj")}}, "target.file", ""},
      {Json{{"type", "mesh"}, {"vertices", {{0, 0, 0}}}}, "target.triangles", "missing"},
      {Json{{"type", "compound"}, {"children", Json::array()}}, "target.children", "too_few"},
      {Json{{"type", "compound"}}, "target.children", "missing"},
      {Json{{"type", "compound"}, {"children", {{{"shape", {{"type", "sphere"}, {"radius", -1}}}}}}},
       "target.children[0].shape.radius", "non_positive"},
      {Json{{"type", "compound"},
            {"children", {{{"shape", {{"type", "halfspace"}, {"normal", {0, 0, 1}}, {"offset", 0}}}}}}},
       "target.children[0].shape", "invalid_argument"},
      {Json{{"type", "compound"}, {"children", {{{"shape", box}, {"pose", {{"rotation", {0, 0, 0, 0}}}}}}}},
       "target.children[0].pose.rotation", ""},
  };
  for (const Case& c : cases) {
    const Json a =
        answer(Json{{"op", "raycast"}, {"target", c.target}, {"origin", {0, 0, 5}}, {"direction", {0, 0, -1}}}, false);
    EXPECT_EQ(a["field"], c.field) << a.dump();
    if (c.code[0] != '\0') {
      EXPECT_EQ(a["code"], c.code) << a.dump();
    }
  }
  // An open mesh has no mass; a compound no containment.
  Json open = box;
  open["triangles"].erase(open["triangles"].size() - 1);
  EXPECT_EQ(answer(Json{{"op", "mass"}, {"target", open}}, false)["code"], "open_mesh");
  const Json compound{{"type", "compound"}, {"children", {{{"shape", box}}}}};
  EXPECT_EQ(answer(Json{{"op", "contains"}, {"target", compound}, {"point", {0, 0, 0}}}, false)["code"],
            "unsupported_geometry");
  EXPECT_EQ(answer(Json{{"op", "bound"}, {"target", compound}, {"volume", "sphere"}}, false)["field"], "volume");
}

}  // namespace test_query_mesh
}  // namespace proxima
