// JSON records of the capture format (capture_json.hpp, docs/capture-format.md).
#include "debug/capture_json.hpp"

#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <ostream>
#include <type_traits>
#include <variant>

#include "debug/json_text.hpp"

namespace proxima::debug::json {

namespace {

void real_member(std::string& out, std::string_view name, Real value) {
  key(out, name);
  real(out, value);
}

void vec3_member(std::string& out, std::string_view name, const Vec3& value) {
  key(out, name);
  vec3(out, value);
}

void tag(std::string& out, const DrawTag& t, Rgba c) {
  key(out, "color");
  color(out, c);
  key(out, "layer");
  string(out, to_string(t.layer));
  key(out, "level");
  integer(out, t.level);
}

template <class T, class Write>
void array(std::string& out, std::string_view name, std::span<const T> items, Write&& write, bool first = false) {
  key(out, name, first);
  out += '[';
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += ',';
    out += '{';
    write(items[i]);
    out += '}';
  }
  out += ']';
}

void handle(std::string& out, ObjectHandle h) { integer(out, h.to_integer()); }

void pairs(std::string& out, std::string_view name, std::span<const ContactEvent> list) {
  key(out, name, name == "begin");
  out += '[';
  for (std::size_t i = 0; i < list.size(); ++i) {
    out += i ? ",[" : "[";
    handle(out, list[i].pair.a);
    out += ',';
    handle(out, list[i].pair.b);
    out += ']';
  }
  out += ']';
}

void sensor_pairs(std::string& out, std::string_view name, std::span<const SensorEvent> list) {
  key(out, name);
  out += '[';
  for (std::size_t i = 0; i < list.size(); ++i) {
    out += i ? ",[" : "[";
    handle(out, list[i].sensor);
    out += ',';
    handle(out, list[i].other);
    out += ']';
  }
  out += ']';
}

Vec3 lifted(const Vec3& p) { return p; }
Vec3 lifted(const Vec2& p) { return Vec3(p.x, p.y, Real(0)); }

/// The events of a 3D or 2D step (the same members; 2D points at z = 0).
template <class Impact, class Events>
void any_events(std::string& out, const Events& e) {
  out += '{';
  pairs(out, "begin", e.begin);
  pairs(out, "persist", e.persist);
  pairs(out, "end", e.end);
  sensor_pairs(out, "sensor_enter", e.sensor_enter);
  sensor_pairs(out, "sensor_exit", e.sensor_exit);
  array<Impact>(out, "impacts", e.impacts, [&](const Impact& i) {
    key(out, "a", true);
    handle(out, i.a);
    key(out, "b");
    handle(out, i.b);
    real_member(out, "toi", i.toi);
    vec3_member(out, "point", lifted(i.point));
    vec3_member(out, "normal", lifted(i.normal));
  });
  out += '}';
}

void compound_children(std::string& out, const Compound& compound) {
  key(out, "children");
  out += '[';
  bool first = true;
  for (const CompoundChild& child : compound.children()) {
    if (!first) out += ',';
    first = false;
    out += "{\"type\":";
    string(out, to_string(shape_type(child.shape)));
    vec3_member(out, "position", child.pose.position);
    key(out, "rotation");
    quat(out, child.pose.rotation);
    out += '}';
  }
  out += ']';
}

void dimensions(std::string& out, ShapeRef shape) {
  switch (shape.type()) {
    case ShapeType::Segment:
      vec3_member(out, "a", shape.as<Segment>().a());
      vec3_member(out, "b", shape.as<Segment>().b());
      break;
    case ShapeType::Triangle:
      for (int i = 0; i < 3; ++i)
        vec3_member(out, std::string_view("abc").substr(std::size_t(i), 1), shape.as<Triangle>().vertex(i));
      break;
    case ShapeType::Sphere: real_member(out, "radius", shape.as<Sphere>().radius()); break;
    case ShapeType::Capsule:
      real_member(out, "radius", shape.as<Capsule>().radius());
      real_member(out, "half_length", shape.as<Capsule>().half_length());
      break;
    case ShapeType::Box: vec3_member(out, "half_extents", shape.as<Box>().half_extents()); break;
    case ShapeType::Cylinder:
      real_member(out, "radius", shape.as<Cylinder>().radius());
      real_member(out, "half_length", shape.as<Cylinder>().half_length());
      break;
    case ShapeType::Cone:
      real_member(out, "radius", shape.as<Cone>().radius());
      real_member(out, "half_length", shape.as<Cone>().half_length());
      break;
    case ShapeType::Ellipsoid: vec3_member(out, "radii", shape.as<Ellipsoid>().radii()); break;
    case ShapeType::ConvexHull:
      key(out, "vertex_count");
      integer(out, shape.as<ConvexHull>().vertices().size());
      key(out, "face_count");
      integer(out, shape.as<ConvexHull>().faces().size());
      break;
    case ShapeType::HalfSpace:
      vec3_member(out, "normal", shape.as<HalfSpace>().normal());
      real_member(out, "offset", shape.as<HalfSpace>().offset());
      break;
    case ShapeType::TriangleMesh:
      key(out, "vertex_count");
      integer(out, shape.as<TriangleMesh>().vertices().size());
      key(out, "triangle_count");
      integer(out, shape.as<TriangleMesh>().triangle_count());
      key(out, "closed");
      out += shape.as<TriangleMesh>().is_closed() ? "true" : "false";
      break;
    case ShapeType::Compound: compound_children(out, shape.as<Compound>()); break;
    default: break;
  }
}

}  // namespace

void geometry(std::string& out, ShapeRef shape) {
  out += "{\"type\":";
  string(out, to_string(shape.type()));
  dimensions(out, shape);
  out += '}';
}

void geometry(std::string& out, const d2::Shape& shape) {
  const auto point = [](const Vec2& p) { return Vec3(p.x, p.y, Real(0)); };
  // The 2D protocol's names (docs/query-protocol.md, "2D").
  constexpr const char* kNames[] = {"point2d", "circle", "segment2d", "capsule2d", "polygon", "chain"};
  out += "{\"type\":";
  string(out, kNames[static_cast<int>(shape.type())]);
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, d2::Point>) {
          vec3_member(out, "position", point(s.position()));
        } else if constexpr (std::is_same_v<S, d2::Circle>) {
          vec3_member(out, "center", point(s.center()));
          real_member(out, "radius", s.radius());
        } else if constexpr (std::is_same_v<S, d2::Segment> || std::is_same_v<S, d2::Capsule>) {
          vec3_member(out, "a", point(s.a()));
          vec3_member(out, "b", point(s.b()));
          if constexpr (std::is_same_v<S, d2::Capsule>) real_member(out, "radius", s.radius());
        } else if constexpr (std::is_same_v<S, d2::Polygon>) {
          key(out, "vertices");
          out += '[';
          for (int i = 0; i < s.count(); ++i) {
            if (i) out += ',';
            vec3(out, point(s.core().vertices[static_cast<std::size_t>(i)]));
          }
          out += ']';
          real_member(out, "radius", s.radius());
        } else {
          key(out, "point_count");
          integer(out, s.points().size());
          out += s.loop() ? ",\"loop\":true" : ",\"loop\":false";
        }
      },
      shape.variant());
  out += '}';
}

void mesh(std::string& out, const DrawMesh& m) {
  out += "{\"positions\":[";
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    if (i) out += ',';
    real(out, m.positions[i].x);
    out += ',';
    real(out, m.positions[i].y);
    out += ',';
    real(out, m.positions[i].z);
  }
  out += "],\"indices\":[";
  for (std::size_t i = 0; i < m.indices.size(); ++i) {
    if (i) out += ',';
    integer(out, m.indices[i]);
  }
  out += "]}";
}

void draw_stream(std::string& out, const DrawBuffer& draw) {
  out += '{';
  array<DrawLine>(
      out, "lines", draw.lines,
      [&](const DrawLine& l) {
        key(out, "from", true);
        vec3(out, l.from);
        vec3_member(out, "to", l.to);
        tag(out, l.tag, l.color);
      },
      true);
  array<DrawTriangle>(out, "triangles", draw.triangles, [&](const DrawTriangle& t) {
    key(out, "a", true);
    vec3(out, t.a);
    vec3_member(out, "b", t.b);
    vec3_member(out, "c", t.c);
    tag(out, t.tag, t.color);
  });
  array<DrawPoint>(out, "points", draw.points, [&](const DrawPoint& p) {
    key(out, "position", true);
    vec3(out, p.position);
    real_member(out, "size", p.size);
    tag(out, p.tag, p.color);
  });
  array<DrawBox>(out, "boxes", draw.boxes, [&](const DrawBox& b) {
    key(out, "center", true);
    vec3(out, b.center);
    vec3_member(out, "half_extents", b.half_extents);
    key(out, "rotation");
    quat(out, b.rotation);
    tag(out, b.tag, b.color);
  });
  array<DrawText>(out, "texts", draw.texts, [&](const DrawText& t) {
    key(out, "position", true);
    vec3(out, t.position);
    key(out, "text");
    string(out, t.text);
    tag(out, t.tag, t.color);
  });
  out += '}';
}

bool write_line(std::ostream& out, const std::string& line, bool& failed) {
  if (failed) return false;
  out << line << '\n';
  out.flush();
  failed = !out;
  return !failed;
}

void header(std::string& out, const CaptureOptions& options, int dimension) {
  out += "{\"format\":\"proxima-capture\",\"version\":";
  integer(out, kCaptureVersion);
  key(out, "dimension");
  integer(out, static_cast<std::uint64_t>(dimension));
  key(out, "units");
  string(out, options.units);
  key(out, "precision");
  string(out, sizeof(Real) == 4 ? "float" : "double");
  if (options.camera) {
    const CaptureCamera& c = *options.camera;
    key(out, "camera");
    out += '{';
    key(out, "position", true);
    vec3(out, c.position);
    vec3_member(out, "target", c.target);
    vec3_member(out, "up", c.up);
    real_member(out, "fov_degrees", c.fov_degrees);
    real_member(out, "ortho_height", c.ortho_height);
    out += '}';
  }
  out += '}';
}

void events(std::string& out, const StepEvents& e) { any_events<ImpactEvent>(out, e); }

void manifolds(std::string& out, std::span<const WorldManifold> list) {
  out += '[';
  for (std::size_t m = 0; m < list.size(); ++m) {
    const WorldManifold& manifold = list[m];
    out += m ? ",{" : "{";
    key(out, "a", true);
    handle(out, manifold.pair.a);
    key(out, "b");
    handle(out, manifold.pair.b);
    vec3_member(out, "normal", manifold.normal);
    const auto count = static_cast<std::size_t>(std::clamp(manifold.count, 0, kMaxContactPoints));
    array<WorldContactPoint>(out, "points", std::span(manifold.points).first(count), [&](const WorldContactPoint& p) {
      key(out, "a", true);
      vec3(out, p.contact.point_a);
      vec3_member(out, "b", p.contact.point_b);
      real_member(out, "depth", p.contact.depth);
      key(out, "id");
      integer(out, p.id);
    });
    out += '}';
  }
  out += ']';
}

void events(std::string& out, const d2::StepEvents& e) { any_events<d2::ImpactEvent>(out, e); }

void manifolds(std::string& out, std::span<const d2::WorldManifold> list) {
  out += '[';
  for (std::size_t m = 0; m < list.size(); ++m) {
    const d2::Manifold& manifold = list[m].manifold;
    out += m ? ",{" : "{";
    key(out, "a", true);
    handle(out, list[m].pair.a);
    key(out, "b");
    handle(out, list[m].pair.b);
    vec3_member(out, "normal", lifted(manifold.normal));
    const auto count = static_cast<std::size_t>(std::clamp(manifold.count, 0, d2::kMaxManifoldPoints));
    array<d2::ContactPoint>(out, "points", std::span(manifold.points).first(count), [&](const d2::ContactPoint& p) {
      key(out, "a", true);
      vec3(out, lifted(p.point_a));
      vec3_member(out, "b", lifted(p.point_b));
      real_member(out, "depth", p.depth);
      key(out, "id");
      integer(out, p.feature_id);
    });
    out += '}';
  }
  out += ']';
}

}  // namespace proxima::debug::json
