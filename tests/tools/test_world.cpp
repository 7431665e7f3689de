// The world protocol (`proxima world`, docs/world-protocol.md), in process: every operation
// answered; rejected requests naming their field and leaving the world's hash unchanged;
// a scene's begin / persist / end, sensor and impact events against the library driven
// directly; queries against the library's own answers; contacts; handles after reuse; thread
// counts; and the save / load round trip.
#include <gtest/gtest.h>

#include <proxima/world/collision_world.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <unistd.h>
#include <vector>

#include "cli_run.hpp"
#include "world_json.hpp"
#include "world_session.hpp"
#include "world_test_util.hpp"

namespace proxima {
namespace test_world {

using test::WorldSessionFixture;
using tool::Json;

std::string scratch_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("proxima_world_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

Json pairs(std::initializer_list<std::pair<std::uint64_t, std::uint64_t>> list) {
  Json out = Json::array();
  for (const auto& [a, b] : list) out.push_back(Json::array({a, b}));
  return out;
}

TEST(WorldProtocol, EveryOperationIsAnswered) {
  WorldSessionFixture w;
  std::set<std::string> asked;
  const auto ask = [&](const std::string& request) {
    asked.insert(Json::parse(request)["op"].get<std::string>());
    return w.ask(request);
  };
  EXPECT_EQ(ask(R"({"id":"a","op":"add","geometry":{"type":"sphere","radius":1}})"),
            Json::parse(R"({"id":"a","object":0})"));
  EXPECT_EQ(ask(R"({"op":"add","geometry":{"type":"box","half_extents":[1,1,1]},"pose":{"position":[1.5,0,0]},
                   "kind":"static","filter":{"layer":3,"mask":1,"group":-2},"sensor":false,"ccd":"bullet",
                   "user_data":18446744073709551615})")["object"],
            1);
  EXPECT_EQ(ask(R"({"op":"add","geometry":{"type":"sphere","radius":0.5},"parent":0,
                   "local_pose":{"position":[0,3,0]}})")["object"],
            2);
  const Json ok = Json::parse(R"({"ok":true})");
  EXPECT_EQ(ask(R"({"op":"move","object":0,"pose":{"position":[0,0,0.5]}})"), ok);
  EXPECT_EQ(ask(R"({"op":"move","objects":[{"object":0,"pose":{"position":[0,0,0]}}]})"), ok);
  EXPECT_EQ(ask(R"({"op":"set_geometry","object":2,"geometry":{"type":"capsule","radius":0.5,"half_length":1}})"), ok);
  EXPECT_EQ(ask(R"({"op":"set_filter","object":2,"filter":{"mask":2}})"), ok);
  EXPECT_EQ(ask(R"({"op":"set_kind","object":0,"kind":"moving"})"), ok);
  EXPECT_EQ(ask(R"({"op":"set_ccd","object":0,"ccd":"off"})"), ok);
  EXPECT_EQ(ask(R"({"op":"set_user_data","object":0,"user_data":5})"), ok);
  EXPECT_EQ(ask(R"({"op":"attach","object":2,"parent":null})"), ok);
  EXPECT_EQ(ask(R"({"op":"attach","object":2,"parent":0,"local_pose":{"position":[0,3,0]}})"), ok);
  EXPECT_EQ(ask(R"({"op":"exclude","a":0,"b":1,"excluded":false})"), ok);
  const Json step = ask(R"({"op":"step","dt":0.5,"contacts":true})");
  EXPECT_EQ(step["begin"], pairs({{0, 1}}));
  for (const char* key : {"persist", "end", "sensor_enter", "sensor_exit", "impacts"})
    EXPECT_EQ(step[key], Json::array());
  ASSERT_EQ(step["contacts"].size(), 1u);
  EXPECT_EQ(ask(R"({"op":"raycast","origin":[-5,0,0],"direction":[1,0,0]})")["hits"][0]["object"], 0);
  EXPECT_EQ(ask(R"({"op":"line_of_sight","from":[-5,0,0],"to":[5,0,0]})")["clear"], false);
  EXPECT_EQ(ask(R"({"op":"overlap","point":[0,0,0]})")["objects"], Json::parse("[0]"));
  EXPECT_EQ(ask(R"({"op":"sweep","geometry":{"type":"sphere","radius":0.1},"pose":{"position":[-5,0,0]},
                   "translation":[10,0,0]})")["hits"][0]["object"],
            0);
  EXPECT_EQ(ask(R"({"op":"closest","point":[-3,0,0],"max_distance":5})")["object"], 0);
  const std::string hash = ask(R"({"op":"hash"})")["hash"].get<std::string>();
  EXPECT_EQ(hash.size(), 16u);
  const std::string file = scratch_file("every_op.pxw");
  EXPECT_EQ(ask(R"({"op":"save","file":")" + file + R"("})"), ok);
  EXPECT_EQ(ask(R"({"op":"load","file":")" + file + R"("})")["objects"], 3);
  EXPECT_EQ(w.hash(), hash);
  EXPECT_EQ(ask(R"({"op":"remove","object":0})")["removed"], Json::parse("[0,2]"));

  std::set<std::string> table;
  for (const tool::WorldOperation& op : tool::world_operations()) table.insert(std::string(op.name));
  EXPECT_EQ(asked, table);
}

TEST(WorldProtocol, RejectedRequestsNameTheFieldAndChangeNothing) {
  WorldSessionFixture w;
  w.add(R"("geometry":{"type":"sphere","radius":1})");                                                       // 0
  w.add(R"("geometry":{"type":"box","half_extents":[1,1,1]},"kind":"static","pose":{"position":[3,0,0]})");  // 1
  w.add(R"("geometry":{"type":"sphere","radius":0.5},"parent":0,"local_pose":{"position":[0,2,0]})");        // 2
  w.ask(R"({"op":"step"})");
  struct Case {
    const char* request;
    const char* field;
    const char* code;
  };
  const Case cases[] = {
      {R"({"op":"add"})", "geometry", "missing"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":-1}})", "geometry.radius", "non_positive"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"pose":{"rotation":[0,0,0,2]}})", "pose.rotation",
       "invalid_argument"},
      {R"({"op":"add","geometry":{"type":"halfspace","normal":[0,0,1],"offset":0}})", "geometry", "invalid_argument"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"filter":{"layer":0}})", "filter.layer",
       "invalid_argument"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"filter":{"group":3000000000}})", "filter.group",
       "out_of_range"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"filter":{"mask":1.5}})", "filter.mask", "wrong_type"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"kind":"frozen"})", "kind", "unknown_kind"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"ccd":"fast"})", "ccd", "unknown_ccd"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"sensor":1})", "sensor", "wrong_type"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"parent":99})", "parent", "unknown_object"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"parent":0,"pose":{}})", "pose", "invalid_argument"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"local_pose":{}})", "local_pose", "invalid_argument"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"user_data":-1})", "user_data", "wrong_type"},
      {R"({"op":"add","geometry":{"type":"sphere","radius":1},"colour":"red"})", "colour", "unknown_field"},
      {R"({"op":"remove"})", "object", "missing"},
      {R"({"op":"remove","object":"0"})", "object", "wrong_type"},
      {R"({"op":"remove","object":4294967296})", "object", "unknown_object"},
      {R"({"op":"move","object":0,"pose":{"position":[1,0]}})", "pose.position", "wrong_type"},
      {R"({"op":"move","object":0})", "pose", "missing"},
      {R"({"op":"move","objects":[{"object":0,"pose":{"position":[1,0,0]}},{"object":7,"pose":{}}]})",
       "objects[1].object", "unknown_object"},
      {R"({"op":"move","objects":[{"object":0,"pose":{"position":[1,0,0]}},{"object":1,"pose":{"position":[1e200,0,0]}}]})",
       "objects[1].pose.position.x", "out_of_range"},
      {R"({"op":"move","objects":[],"object":0})", "objects", "invalid_argument"},
      {R"({"op":"move","objects":[],"teleport":true})", "teleport", "invalid_argument"},
      {R"({"op":"move","object":0,"pose":{},"teleport":1})", "teleport", "wrong_type"},
      {R"({"op":"set_geometry","object":0,"geometry":{"type":"halfspace","normal":[0,0,1],"offset":0}})", "geometry",
       "invalid_argument"},
      {R"({"op":"set_filter","object":0,"filter":{"mask":0}})", "filter.mask", "invalid_argument"},
      {R"({"op":"set_filter","object":0})", "filter", "missing"},
      {R"({"op":"set_kind","object":2,"kind":"static"})", "kind", "invalid_argument"},
      {R"({"op":"set_kind","object":0,"kind":"x"})", "kind", "unknown_kind"},
      {R"({"op":"set_ccd","object":0,"ccd":"x"})", "ccd", "unknown_ccd"},
      {R"({"op":"set_user_data","object":0})", "user_data", "missing"},
      {R"({"op":"attach","object":0,"parent":2})", "parent", "invalid_argument"},
      {R"({"op":"attach","object":2,"parent":null,"local_pose":{}})", "local_pose", "invalid_argument"},
      {R"({"op":"attach","object":1,"parent":0,"local_pose":{"rotation":[0,0,0,3]}})", "local_pose.rotation",
       "invalid_argument"},
      {R"({"op":"exclude","a":0,"b":0})", "b", "invalid_argument"},
      {R"({"op":"exclude","a":0,"b":1,"excluded":"yes"})", "excluded", "wrong_type"},
      {R"({"op":"step","dt":0})", "dt", "non_positive"},
      {R"({"op":"step","contacts":1})", "contacts", "wrong_type"},
      {R"({"op":"raycast","origin":[0,0,5],"direction":[0,0,0]})", "direction", "invalid_argument"},
      {R"({"op":"raycast","origin":[0,0,5],"direction":[0,0,1],"max_t":-1})", "max_t", "negative"},
      {R"({"op":"raycast","origin":[0,0,5],"direction":[0,0,1],"mode":"nearest"})", "mode", "unknown_mode"},
      {R"({"op":"raycast","origin":[0,0,5],"direction":[0,0,1],"filter":{"ignore":-1}})", "filter.ignore",
       "wrong_type"},
      {R"({"op":"raycast","origin":[0,0,5],"direction":[0,0,1],"filter":{"layer":1}})", "filter.layer",
       "unknown_field"},
      {R"({"op":"line_of_sight","to":[0,0,0]})", "from", "missing"},
      {R"({"op":"line_of_sight","from":[0,0,0],"to":[1,0,0],"mode":"any"})", "mode", "unknown_field"},
      {R"({"op":"overlap"})", "geometry", "missing"},
      {R"({"op":"overlap","box":{"min":[1,1,1],"max":[0,0,0]}})", "box", "invalid_argument"},
      {R"({"op":"overlap","point":[0,0,0],"pose":{}})", "pose", "invalid_argument"},
      {R"({"op":"sweep","geometry":{"type":"mesh","vertices":[[0,0,0],[1,0,0],[0,1,0]],"triangles":[[0,1,2]]},
          "translation":[1,0,0]})",
       "geometry.type", "unsupported_geometry"},
      {R"({"op":"sweep","geometry":{"type":"sphere","radius":1}})", "translation", "missing"},
      {R"({"op":"closest","point":[0,0,0],"max_distance":-1})", "max_distance", "negative"},
      {R"({"op":"closest","point":[0,0,0]})", "max_distance", "missing"},
      {R"({"op":"closest","max_distance":1})", "point", "missing"},
      {R"({"op":"hash","x":1})", "x", "unknown_field"},
      {R"({"op":"save"})", "file", "missing"},
      {R"({"op":"save","file":"/no/such/dir/x.pxw"})", "file", "invalid_argument"},
      {R"({"op":"load","file":"/no/such/file.pxw"})", "file", "invalid_argument"},
      {R"({"op":"teleport"})", "op", "unknown_op"},
      {R"({"id":3})", "op", "missing"},
  };
  for (const Case& c : cases) {
    const std::string before = w.hash();
    const std::uint64_t state = w.session.world().state_hash();
    const Json answer = w.ask(c.request, false);
    EXPECT_EQ(answer.value("field", "?"), c.field) << c.request << " -> " << answer.dump();
    EXPECT_EQ(answer.value("code", "?"), c.code) << c.request << " -> " << answer.dump();
    EXPECT_EQ(answer.value("error", "").rfind(std::string(c.field) + ": ", 0), 0u) << answer.dump();
    EXPECT_EQ(w.hash(), before) << c.request;
    EXPECT_EQ(w.session.world().state_hash(), state) << c.request;
  }
  // A file that is not a snapshot: the library's reason, under "file".
  const std::string junk = scratch_file("junk.pxw");
  { std::ofstream(junk) << "not a snapshot"; }
  const std::string before = w.hash();
  const Json answer = w.ask(R"({"op":"load","file":")" + junk + R"("})", false);
  EXPECT_EQ(answer["field"], "file");
  EXPECT_EQ(w.hash(), before);
}

// A ball rolls along x through a sensor and into a resting ball, then on past it; every step
// is answered as the library, driven directly with the same calls, reports it.
TEST(WorldProtocol, StepEventsAreTheLibrarysEvents) {
  WorldSessionFixture w;
  CollisionWorld direct = CollisionWorld::create().value();
  const auto both_add = [&](const std::string& members, const ObjectDesc& desc) {
    const std::uint64_t h = w.add(members);
    EXPECT_EQ(direct.add(desc).value().to_integer(), h);
  };
  ObjectDesc a;
  a.geometry = *Sphere::create(Real(0.5));
  a.pose = *Transform::create(Vec3(-3, 0, 0), kIdentityQuat);
  a.ccd = CcdMode::Off;
  both_add(R"("geometry":{"type":"sphere","radius":0.5},"pose":{"position":[-3,0,0]},"ccd":"off")", a);
  ObjectDesc b;
  b.geometry = *Sphere::create(Real(1));
  b.pose = *Transform::create(Vec3(3, 0, 0), kIdentityQuat);
  both_add(R"("geometry":{"type":"sphere","radius":1},"pose":{"position":[3,0,0]})", b);
  ObjectDesc s;
  s.geometry = *Box::create(Vec3(Real(0.6)));
  s.kind = ObjectKind::Static;
  s.sensor = true;
  both_add(R"("geometry":{"type":"box","half_extents":[0.6,0.6,0.6]},"kind":"static","sensor":true)", s);

  std::vector<Json> begins, ends, enters, exits;
  int persists = 0;
  for (int k = 0; k <= 17; ++k) {
    const double x = -3 + 0.5 * k;
    const Json answer = w.ask(R"({"op":"move","object":0,"pose":{"position":[)" + std::to_string(x) + R"(,0,0]}})");
    ASSERT_FALSE(direct.move(ObjectHandle::from_integer(0), *Transform::create(Vec3(Real(x), 0, 0), kIdentityQuat)));
    const Json step = w.ask(R"({"op":"step","dt":0.1})");
    ASSERT_FALSE(direct.step(Real(0.1)));
    const StepEvents& e = direct.events();
    const auto contact_list = [](const std::vector<ContactEvent>& list) {
      Json out = Json::array();
      for (const ContactEvent& c : list) out.push_back(Json::array({c.pair.a.to_integer(), c.pair.b.to_integer()}));
      return out;
    };
    const auto sensor_list = [](const std::vector<SensorEvent>& list) {
      Json out = Json::array();
      for (const SensorEvent& c : list) out.push_back(Json::array({c.sensor.to_integer(), c.other.to_integer()}));
      return out;
    };
    EXPECT_EQ(step["begin"], contact_list(e.begin)) << k;
    EXPECT_EQ(step["persist"], contact_list(e.persist)) << k;
    EXPECT_EQ(step["end"], contact_list(e.end)) << k;
    EXPECT_EQ(step["sensor_enter"], sensor_list(e.sensor_enter)) << k;
    EXPECT_EQ(step["sensor_exit"], sensor_list(e.sensor_exit)) << k;
    EXPECT_EQ(step["impacts"], Json::array()) << k;
    if (!step["begin"].empty()) begins.push_back(Json::array({k, step["begin"]}));
    if (!step["end"].empty()) ends.push_back(Json::array({k, step["end"]}));
    if (!step["sensor_enter"].empty()) enters.push_back(Json::array({k, step["sensor_enter"]}));
    if (!step["sensor_exit"].empty()) exits.push_back(Json::array({k, step["sensor_exit"]}));
    persists += static_cast<int>(step["persist"].size());
  }
  EXPECT_EQ(w.session.world().state_hash(), direct.state_hash());
  // Touching counts (contact distance 0): the balls touch from x = 1.5 (k = 9) to 4.5 (k = 15).
  EXPECT_EQ(Json(begins), Json::parse(R"([[9,[[0,1]]]])"));
  EXPECT_EQ(Json(ends), Json::parse(R"([[16,[[0,1]]]])"));
  EXPECT_EQ(persists, 6);
  // The sensor box spans x in [-0.6, 0.6]: the ball overlaps it from x = -1 to 1.
  EXPECT_EQ(Json(enters), Json::parse(R"([[4,[[2,0]]]])"));
  EXPECT_EQ(Json(exits), Json::parse(R"([[9,[[2,0]]]])"));
}

TEST(WorldProtocol, FastObjectsReportImpactsAndCrossSensors) {
  WorldSessionFixture w;
  w.add(R"("geometry":{"type":"box","half_extents":[0.05,2,2]},"kind":"static")");  // 0 wall
  w.add(
      R"("geometry":{"type":"box","half_extents":[0.5,0.5,0.5]},"kind":"static","sensor":true,"pose":{"position":[0,5,0]})");  // 1
  w.add(R"("geometry":{"type":"sphere","radius":0.1},"pose":{"position":[-5,0,0]})");              // 2
  w.add(R"("geometry":{"type":"sphere","radius":0.1},"pose":{"position":[-5,5,0]})");              // 3
  w.add(R"("geometry":{"type":"sphere","radius":0.1},"pose":{"position":[-5,0,1]},"ccd":"off")");  // 4
  w.ask(R"({"op":"step"})");
  w.ask(R"({"op":"move","objects":[{"object":2,"pose":{"position":[5,0,0]}},{"object":3,"pose":{"position":[5,5,0]}},
            {"object":4,"pose":{"position":[5,0,1]}}]})");
  const Json step = w.ask(R"({"op":"step"})");
  ASSERT_EQ(step["impacts"].size(), 1u) << step.dump();
  const Json& impact = step["impacts"][0];
  EXPECT_EQ(impact["a"], 2);
  EXPECT_EQ(impact["b"], 0);
  // The centre reaches x = -0.15 (the wall's face less the radius) after 4.85 of 10.
  EXPECT_NEAR(impact["toi"].get<double>(), 0.485, 1e-3);
  EXPECT_NEAR(impact["normal"][0].get<double>(), 1.0, 1e-4);
  EXPECT_NEAR(impact["point"][0].get<double>(), -0.05, 1e-3);
  EXPECT_EQ(step["sensor_enter"], pairs({{1, 3}}));
  EXPECT_EQ(step["sensor_exit"], pairs({{1, 3}}));
  EXPECT_EQ(step["begin"], Json::array());
}

TEST(WorldProtocol, ContactsAreTheWorldsManifolds) {
  WorldSessionFixture w;
  w.add(R"("geometry":{"type":"box","half_extents":[5,5,0.5]},"kind":"static","pose":{"position":[0,0,-0.5]})");
  w.add(R"("geometry":{"type":"box","half_extents":[0.5,0.5,0.5]},"pose":{"position":[0,0,0.45]})");
  w.add(R"("geometry":{"type":"sphere","radius":0.5},"pose":{"position":[3,0,0.4]})");
  for (int step = 0; step < 2; ++step) {
    const Json answer = w.ask(R"({"op":"step","contacts":true})");
    const auto contacts = w.session.world().contacts();
    ASSERT_EQ(answer["contacts"].size(), contacts.size());
    ASSERT_EQ(contacts.size(), 2u);
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      const WorldManifold& m = contacts[i];
      const Json& j = answer["contacts"][i];
      EXPECT_EQ(j["a"], m.pair.a.to_integer());
      EXPECT_EQ(j["b"], m.pair.b.to_integer());
      EXPECT_EQ(j["normal"], tool::to_json(m.normal));
      ASSERT_EQ(j["points"].size(), static_cast<std::size_t>(m.count));
      for (int p = 0; p < m.count; ++p) {
        const Json& point = j["points"][static_cast<std::size_t>(p)];
        const WorldContactPoint& wp = m.points[static_cast<std::size_t>(p)];
        EXPECT_EQ(point["id"], wp.id);
        EXPECT_EQ(point["point_a"], tool::to_json(wp.contact.point_a));
        EXPECT_EQ(point["point_b"], tool::to_json(wp.contact.point_b));
        EXPECT_EQ(point["depth"], tool::to_json(wp.contact.depth));
        EXPECT_EQ(point["persisted"], step == 1);
      }
    }
    EXPECT_EQ(answer["contacts"][0]["points"].size(), 4u);  // the box rests on its face
    EXPECT_NEAR(answer["contacts"][0]["points"][0]["depth"].get<double>(), 0.05, 1e-5);
  }
  EXPECT_FALSE(w.ask(R"({"op":"step"})").contains("contacts"));
}

TEST(WorldProtocol, QueriesAreTheLibrarysAnswers) {
  WorldSessionFixture w;
  w.add(R"("geometry":{"type":"halfspace","normal":[0,0,1],"offset":0},"kind":"static")");
  w.add(R"("geometry":{"type":"box","half_extents":[1,1,1]},"pose":{"position":[0,0,1]},"filter":{"layer":2})");
  w.add(R"("geometry":{"type":"sphere","radius":1},"pose":{"position":[4,0,1]},"filter":{"layer":4,"group":3})");
  w.add(R"("geometry":{"type":"capsule","radius":0.5,"half_length":1},"pose":{"position":[8,0,1.5]})");
  const CollisionWorld& world = w.session.world();
  const auto hits_json = [](const std::vector<WorldHit>& hits) {
    Json out = Json::array();
    for (const WorldHit& h : hits) {
      Json hit = Json::object();
      hit["object"] = h.object.to_integer();
      hit["t"] = tool::to_json(h.t);
      hit["point"] = tool::to_json(h.point);
      hit["normal"] = tool::to_json(h.normal);
      out.push_back(hit);
    }
    return out;
  };
  const auto objects_json = [](const std::vector<WorldOverlap>& list) {
    Json out = Json::array();
    for (const WorldOverlap& o : list) out.push_back(o.object.to_integer());
    return out;
  };
  const Ray ray{Vec3(-5, 0, 1.5f), Vec3(1, 0, 0)};
  for (const char* mode : {"closest", "any", "all"}) {
    const QueryMode m = tool::read_query_mode(Json(mode), "mode");
    EXPECT_EQ(w.ask(std::string(R"({"op":"raycast","origin":[-5,0,1.5],"direction":[1,0,0],"mode":")") + mode +
                    "\"}")["hits"],
              hits_json(world.raycast(ray, kRealMax, {}, m).value()))
        << mode;
  }
  QueryFilter not_box;
  not_box.ignore = ObjectHandle::from_integer(1);
  EXPECT_EQ(w.ask(R"({"op":"raycast","origin":[-5,0,1.5],"direction":[1,0,0],"max_t":12,"mode":"all",
                     "filter":{"ignore":1}})")["hits"],
            hits_json(world.raycast(ray, 12, not_box, QueryMode::All).value()));
  QueryFilter group3;
  group3.group = 3;
  group3.mask = 6;
  const Json grouped = w.ask(R"({"op":"raycast","origin":[-5,0,1.5],"direction":[1,0,0],"mode":"all",
                                 "filter":{"mask":6,"group":3}})")["hits"];
  EXPECT_EQ(grouped, hits_json(world.raycast(ray, kRealMax, group3, QueryMode::All).value()));
  ASSERT_EQ(grouped.size(), 1u);
  EXPECT_EQ(grouped[0]["object"], 1);

  EXPECT_EQ(w.ask(R"({"op":"line_of_sight","from":[-5,0,1.5],"to":[12,0,1.5],"filter":{"mask":1}})")["clear"],
            world.line_of_sight(Vec3(-5, 0, 1.5f), Vec3(12, 0, 1.5f), QueryFilter{1, 0, {}}).value());
  EXPECT_EQ(w.ask(R"({"op":"line_of_sight","from":[-5,0,1.5],"to":[12,0,1.5]})")["clear"], false);

  const Shape probe = *Capsule::create(Real(0.5), Real(3));
  const Transform probe_pose = *Transform::create(Vec3(4, 0, 1), Quat(Real(0.7071068), 0, Real(0.7071068), 0));
  EXPECT_EQ(w.ask(R"({"op":"overlap","geometry":{"type":"capsule","radius":0.5,"half_length":3},
                     "pose":{"position":[4,0,1],"rotation":[0,0.7071068,0,0.7071068]}})")["objects"],
            objects_json(world.overlap(probe, probe_pose).value()));
  EXPECT_EQ(w.ask(R"({"op":"overlap","box":{"min":[-1,-1,0.5],"max":[9,1,1]},"mode":"closest"})")["objects"],
            objects_json(world.overlap_box(Aabb{Vec3(-1, -1, 0.5f), Vec3(9, 1, 1)}, {}, QueryMode::Closest).value()));
  EXPECT_EQ(w.ask(R"({"op":"overlap","point":[4,0,0]})")["objects"],
            objects_json(world.overlap_point(Vec3(4, 0, 0)).value()));

  const Shape ball = *Sphere::create(Real(0.25));
  const Transform start = *Transform::create(Vec3(-5, 0, 1.5f), kIdentityQuat);
  EXPECT_EQ(w.ask(R"({"op":"sweep","geometry":{"type":"sphere","radius":0.25},"pose":{"position":[-5,0,1.5]},
                     "translation":[20,0,0],"mode":"all"})")["hits"],
            hits_json(world.sweep(ball, start, Vec3(20, 0, 0), {}, QueryMode::All).value()));

  const auto closest = world.closest_point(Vec3(6, 0, 3), 5).value();
  ASSERT_TRUE(closest.has_value());
  const Json near = w.ask(R"({"op":"closest","point":[6,0,3],"max_distance":5})");
  EXPECT_EQ(near["object"], closest->object.to_integer());
  EXPECT_EQ(near["distance"], tool::to_json(closest->signed_distance));
  EXPECT_EQ(near["point"], tool::to_json(closest->point_object));
  EXPECT_EQ(near["normal"], tool::to_json(closest->normal));
  const auto closest_ball = world.closest(ball, *Transform::create(Vec3(2, 0, 5), kIdentityQuat), 10).value();
  ASSERT_TRUE(closest_ball.has_value());
  const Json near_ball = w.ask(
      R"({"op":"closest","geometry":{"type":"sphere","radius":0.25},"pose":{"position":[2,0,5]},"max_distance":10})");
  EXPECT_EQ(near_ball["object"], closest_ball->object.to_integer());
  EXPECT_EQ(near_ball["point_query"], tool::to_json(closest_ball->point_query));
  EXPECT_EQ(w.ask(R"({"op":"closest","point":[0,0,30],"max_distance":1})"), Json::parse(R"({"object":null})"));
}

// A reused slot gives a new handle; the old one is rejected everywhere, and pairs keep the
// library's order (by slot index first).
TEST(WorldProtocol, HandlesOfReusedSlots) {
  WorldSessionFixture w;
  w.add(R"("geometry":{"type":"sphere","radius":1})");
  w.add(R"("geometry":{"type":"sphere","radius":1},"pose":{"position":[1,0,0]})");
  EXPECT_EQ(w.ask(R"({"op":"remove","object":0})")["removed"], Json::parse("[0]"));
  const std::uint64_t reused = w.add(R"("geometry":{"type":"sphere","radius":1})");
  EXPECT_EQ(reused, (1ull << 32) | 0u);
  EXPECT_EQ(w.ask(R"({"op":"move","object":0,"pose":{}})", false)["code"], "unknown_object");
  // Pairs are ordered by the handles' integers: the reused slot 0 (generation 1) is the
  // larger integer, so it comes second although its index is lower.
  const Json step = w.ask(R"({"op":"step","contacts":true})");
  EXPECT_EQ(step["begin"], pairs({{1, reused}}));
  // The manifold turned round with the pair: its normal points from object 1 (at x = 1) to
  // the reused slot's sphere (at the origin).
  ASSERT_EQ(step["contacts"].size(), 1u);
  EXPECT_EQ(step["contacts"][0]["a"], 1u);
  EXPECT_LT(step["contacts"][0]["normal"][0].get<double>(), -0.99);
  // point_a is the deepest point of object 1 towards the other sphere (x = 1 - 1), point_b
  // the other sphere's deepest point towards object 1 (x = 0 + 1).
  EXPECT_NEAR(step["contacts"][0]["points"][0]["point_a"][0].get<double>(), 0.0, 1e-5);
  EXPECT_NEAR(step["contacts"][0]["points"][0]["point_b"][0].get<double>(), 1.0, 1e-5);
}

// The same session on a thread pool answers exactly as on the calling thread.
TEST(WorldProtocol, ThreadsDoNotChangeTheAnswers) {
  tool::WorldOptions pooled;
  pooled.threads = 3;
  WorldSessionFixture serial;
  WorldSessionFixture parallel(pooled);
  std::vector<std::string> requests;
  for (int i = 0; i < 24; ++i) {
    requests.push_back(R"({"op":"add","geometry":{"type":"box","half_extents":[0.6,0.6,0.6]},"pose":{"position":[)" +
                       std::to_string(i % 6) + "," + std::to_string(i / 6) + R"(,0]}})");
  }
  for (int k = 0; k < 3; ++k) {
    requests.push_back(R"({"op":"move","object":)" + std::to_string(k) + R"(,"pose":{"position":[2.5,1.5,0.5]}})");
    requests.push_back(R"({"op":"step","contacts":true})");
  }
  for (const std::string& r : requests) EXPECT_EQ(serial.ask(r).dump(), parallel.ask(r).dump()) << r;
  EXPECT_EQ(serial.hash(), parallel.hash());
}

TEST(WorldProtocol, SaveAndLoadRoundTrip) {
  WorldSessionFixture w;
  w.add(R"("geometry":{"type":"box","half_extents":[5,5,0.5]},"kind":"static","pose":{"position":[0,0,-0.5]})");
  w.add(R"("geometry":{"type":"sphere","radius":0.5},"pose":{"position":[0,0,0.45]},"user_data":9)");
  w.add(
      R"("geometry":{"type":"box","half_extents":[0.5,0.5,0.5]},"kind":"static","sensor":true,"pose":{"position":[3,0,0]})");
  w.add(R"("geometry":{"type":"compound","children":[{"shape":{"type":"sphere","radius":0.2}},
          {"shape":{"type":"box","half_extents":[0.1,0.1,0.1]},"pose":{"position":[0.5,0,0]}}]},
          "parent":1,"local_pose":{"position":[0,0,1]},"filter":{"layer":6,"mask":5,"group":2})");
  w.ask(R"({"op":"remove","object":0})");
  w.add(R"("geometry":{"type":"box","half_extents":[5,5,0.5]},"kind":"static","pose":{"position":[0,0,-0.5]})");
  w.ask(R"({"op":"exclude","a":1,"b":2})");
  w.ask(R"({"op":"step","contacts":true})");
  w.ask(R"({"op":"step"})");
  const std::string hash = w.hash();
  const std::string file = scratch_file("round_trip.pxw");
  w.ask(R"({"op":"save","file":")" + file + R"("})");

  WorldSessionFixture loaded;
  EXPECT_EQ(loaded.ask(R"({"op":"load","file":")" + file + R"("})")["objects"], 4);
  EXPECT_EQ(loaded.hash(), hash);
  const std::string script[] = {
      R"({"op":"step","contacts":true})",
      R"({"op":"move","object":1,"pose":{"position":[3,0,0.2]}})",
      R"({"op":"step","contacts":true})",
      R"({"op":"move","object":1,"pose":{"position":[0,0,3]}})",
      R"({"op":"step","contacts":true})",
      R"({"op":"raycast","origin":[0,0,10],"direction":[0,0,-1],"mode":"all"})",
      R"({"op":"hash"})",
  };
  for (const std::string& r : script) EXPECT_EQ(w.ask(r).dump(), loaded.ask(r).dump()) << r;
  // Loading over a changed world brings the saved one back.
  w.ask(R"({"op":"load","file":")" + file + R"("})");
  EXPECT_EQ(w.hash(), hash);
}

}  // namespace test_world
}  // namespace proxima

namespace proxima {
namespace test_world_cli {

// The built executable: options, one answer per line, exit status.
std::string write_requests(const std::string& name, const std::string& text) {
  const std::string path = test_world::scratch_file(name);
  std::ofstream(path) << text;
  return path;
}

TEST(WorldCli, AnswersEveryLineAndExitsAsQuery) {
  const std::string good = write_requests("good.jsonl",
                                          R"({"id":1,"op":"add","geometry":{"type":"sphere","radius":1}}
{"id":2,"op":"add","geometry":{"type":"sphere","radius":1},"pose":{"position":[2.3,0,0]}}

{"id":3,"op":"step"}
)");
  test::CliRun run = test::run_cli("world " + good);
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(
      run.output,
      "{\"id\":1,\"object\":0}\n{\"id\":2,\"object\":1}\n"
      "{\"id\":3,\"begin\":[],\"persist\":[],\"end\":[],\"sensor_enter\":[],\"sensor_exit\":[],\"impacts\":[]}\n");
  // Within the contact distance the pair touches; on 4 threads and another broad phase alike.
  run = test::run_cli("world --contact-distance 0.5 --threads 4 --broadphase sap - < " + good);
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("\"begin\":[[0,1]]"), std::string::npos) << run.output;

  const std::string bad =
      write_requests("bad.jsonl", "{\"op\":\"remove\",\"object\":0}\n{\"op\":\"hash\"}\nnot json\n");
  run = test::run_cli("world " + bad);
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 3);
  EXPECT_NE(run.output.find("\"code\":\"unknown_object\""), std::string::npos);
  EXPECT_NE(run.output.find("\"code\":\"bad_json\""), std::string::npos);

  EXPECT_EQ(test::run_cli("world no/such/requests.jsonl 2>/dev/null").status, 1);
  EXPECT_EQ(test::run_cli("world --broadphase nosuch " + good + " 2>/dev/null").status, 1);
}

TEST(WorldCli, SensorsSenseSensorsOnlyWhenAsked) {
  const std::string sensors =
      write_requests("sensors.jsonl", R"({"op":"add","geometry":{"type":"sphere","radius":1},"sensor":true}
{"op":"add","geometry":{"type":"sphere","radius":1},"sensor":true,"pose":{"position":[1,0,0]}}
{"op":"step"}
)");
  test::CliRun run = test::run_cli("world " + sensors);
  EXPECT_NE(run.output.find("\"sensor_enter\":[]"), std::string::npos) << run.output;
  run = test::run_cli("world --sensors-sense-sensors " + sensors);
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(run.output.find("\"sensor_enter\":[]"), std::string::npos) << run.output;
}

}  // namespace test_world_cli
}  // namespace proxima
