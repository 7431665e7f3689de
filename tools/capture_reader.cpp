// Reading and validating captures (capture_reader.hpp).
#include "capture_reader.hpp"

#include <istream>
#include <map>
#include <set>

#include "json_values.hpp"

namespace proxima::tool {

namespace {

const Json& member(const Json& object, const std::string& path, std::string_view key) {
  require_object(object, path);
  return require_member(object, path, key);
}

std::uint64_t read_uint(const Json& value, const std::string& path) {
  if (!value.is_number_unsigned()) throw FieldError(path, "wrong_type", "expected an unsigned integer");
  return value.get<std::uint64_t>();
}

bool read_bool(const Json& value, const std::string& path) {
  if (!value.is_boolean()) throw FieldError(path, "wrong_type", "expected true or false");
  return value.get<bool>();
}

const Json& read_array(const Json& object, const std::string& path, std::string_view key) {
  const Json& value = member(object, path, key);
  if (!value.is_array()) throw FieldError(join_path(path, key), "wrong_type", "expected an array");
  return value;
}

Rgba read_color(const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 4) throw FieldError(path, "wrong_type", "expected [r, g, b, a]");
  std::uint8_t c[4];
  for (std::size_t i = 0; i < 4; ++i) {
    const std::uint64_t v = read_uint(value[i], index_path(path, i));
    if (v > 255) throw FieldError(index_path(path, i), "out_of_range", "expected 0..255");
    c[i] = static_cast<std::uint8_t>(v);
  }
  return Rgba{c[0], c[1], c[2], c[3]};
}

Transform read_pose(const Json& object, const std::string& path) {
  return Transform{read_vec3(member(object, path, "position"), join_path(path, "position")),
                   read_quat_xyzw(member(object, path, "rotation"), join_path(path, "rotation"))};
}

CaptureObject read_object(const Json& j, const std::string& path) {
  CaptureObject o;
  o.id = read_uint(member(j, path, "id"), join_path(path, "id"));
  o.kind = read_string(member(j, path, "kind"), join_path(path, "kind"));
  o.sensor = read_bool(member(j, path, "sensor"), join_path(path, "sensor"));
  o.color = read_color(member(j, path, "color"), join_path(path, "color"));
  const std::string geometry = join_path(path, "geometry");
  o.geometry_type = read_string(member(member(j, path, "geometry"), geometry, "type"), join_path(geometry, "type"));
  o.pose = read_pose(j, path);
  const std::string mesh = join_path(path, "mesh");
  const Json& m = member(j, path, "mesh");
  const Json& positions = read_array(m, mesh, "positions");
  if (positions.size() % 3 != 0)
    throw FieldError(join_path(mesh, "positions"), "wrong_size", "expected x, y, z triples");
  for (std::size_t i = 0; i < positions.size(); i += 3) {
    Vec3 p;
    for (int k = 0; k < 3; ++k)
      p[k] = read_real(positions[i + std::size_t(k)], index_path(join_path(mesh, "positions"), i + std::size_t(k)));
    o.positions.push_back(p);
  }
  const Json& indices = read_array(m, mesh, "indices");
  if (indices.size() % 3 != 0)
    throw FieldError(join_path(mesh, "indices"), "wrong_size", "expected three per triangle");
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const std::uint64_t v = read_uint(indices[i], index_path(join_path(mesh, "indices"), i));
    if (v >= o.positions.size()) {
      throw FieldError(index_path(join_path(mesh, "indices"), i), "out_of_range", "index past the last position");
    }
    o.indices.push_back(static_cast<std::uint32_t>(v));
  }
  return o;
}

DrawTag read_tag(const Json& j, const std::string& path) {
  const std::string layer = read_string(member(j, path, "layer"), join_path(path, "layer"));
  for (int i = 0; i < kDrawLayerCount; ++i) {
    if (to_string(static_cast<DrawLayer>(i)) == layer) {
      const std::uint64_t level = read_uint(member(j, path, "level"), join_path(path, "level"));
      return DrawTag{static_cast<DrawLayer>(i), static_cast<std::uint16_t>(std::min<std::uint64_t>(level, 65535))};
    }
  }
  throw FieldError(join_path(path, "layer"), "unknown", "unknown layer \"" + layer + "\"");
}

Vec3 vec3_of(const Json& j, const std::string& path, std::string_view key) {
  return read_vec3(member(j, path, key), join_path(path, key));
}

template <class Read>
void each(const Json& object, const std::string& path, std::string_view key, Read&& read) {
  const Json& list = read_array(object, path, key);
  for (std::size_t i = 0; i < list.size(); ++i) read(list[i], index_path(join_path(path, key), i));
}

DrawBuffer read_draw(const Json& d, const std::string& path) {
  DrawBuffer draw;
  const auto color = [](const Json& j, const std::string& p) {
    return read_color(member(j, p, "color"), join_path(p, "color"));
  };
  each(d, path, "lines", [&](const Json& j, const std::string& p) {
    draw.lines.push_back({vec3_of(j, p, "from"), vec3_of(j, p, "to"), color(j, p), read_tag(j, p)});
  });
  each(d, path, "triangles", [&](const Json& j, const std::string& p) {
    draw.triangles.push_back({vec3_of(j, p, "a"), vec3_of(j, p, "b"), vec3_of(j, p, "c"), color(j, p), read_tag(j, p)});
  });
  each(d, path, "points", [&](const Json& j, const std::string& p) {
    draw.points.push_back({vec3_of(j, p, "position"), read_real(member(j, p, "size"), join_path(p, "size")),
                           color(j, p), read_tag(j, p)});
  });
  each(d, path, "boxes", [&](const Json& j, const std::string& p) {
    draw.boxes.push_back({vec3_of(j, p, "center"), vec3_of(j, p, "half_extents"),
                          read_quat_xyzw(member(j, p, "rotation"), join_path(p, "rotation")), color(j, p),
                          read_tag(j, p)});
  });
  each(d, path, "texts", [&](const Json& j, const std::string& p) {
    draw.texts.push_back({vec3_of(j, p, "position"), read_string(member(j, p, "text"), join_path(p, "text")),
                          color(j, p), read_tag(j, p)});
  });
  return draw;
}

CaptureStep read_step(const Json& j, std::uint64_t expected_index, std::set<std::uint64_t>& live) {
  CaptureStep s;
  s.index = read_uint(member(j, "", "index"), "index");
  if (s.index != expected_index) {
    throw FieldError("index", "out_of_sequence", "expected step " + std::to_string(expected_index));
  }
  s.dt = read_real(member(j, "", "dt"), "dt");
  each(j, "", "removed", [&](const Json& v, const std::string& p) {
    s.removed.push_back(read_uint(v, p));
    live.erase(s.removed.back());
  });
  each(j, "", "added", [&](const Json& v, const std::string& p) {
    s.added.push_back(read_object(v, p));
    live.insert(s.added.back().id);
  });
  each(j, "", "poses", [&](const Json& v, const std::string& p) {
    const std::uint64_t id = read_uint(member(v, p, "id"), join_path(p, "id"));
    if (!live.count(id)) throw FieldError(join_path(p, "id"), "unknown_object", "no object " + std::to_string(id));
    s.poses.emplace_back(id, read_pose(v, p));
  });
  require_object(member(j, "", "events"), "events");
  each(j, "", "contacts", [&](const Json& v, const std::string& p) {
    CaptureManifold m{read_uint(member(v, p, "a"), join_path(p, "a")),
                      read_uint(member(v, p, "b"), join_path(p, "b")),
                      vec3_of(v, p, "normal"),
                      {}};
    each(v, p, "points", [&](const Json& q, const std::string& qp) {
      m.points.push_back(
          {vec3_of(q, qp, "a"), vec3_of(q, qp, "b"), read_real(member(q, qp, "depth"), join_path(qp, "depth"))});
    });
    s.contacts.push_back(std::move(m));
  });
  s.query_count = read_array(j, "", "queries").size();
  s.draw = read_draw(member(j, "", "draw"), "draw");
  return s;
}

void read_header(const Json& j, Capture& capture) {
  if (read_string(member(j, "", "format"), "format") != "proxima-capture") {
    throw FieldError("format", "wrong_format", "expected \"proxima-capture\"");
  }
  const std::uint64_t version = read_uint(member(j, "", "version"), "version");
  if (version != static_cast<std::uint64_t>(debug::kCaptureVersion)) {
    throw FieldError("version", "unsupported", "version " + std::to_string(version) + " is not supported (1 is)");
  }
  capture.version = static_cast<int>(version);
  const std::uint64_t dimension = read_uint(member(j, "", "dimension"), "dimension");
  if (dimension != 2 && dimension != 3) throw FieldError("dimension", "out_of_range", "expected 2 or 3");
  capture.dimension = static_cast<int>(dimension);
  capture.units = read_string(member(j, "", "units"), "units");
  if (const Json* c = find_member(j, "camera")) {
    debug::CaptureCamera camera;
    camera.position = vec3_of(*c, "camera", "position");
    camera.target = vec3_of(*c, "camera", "target");
    camera.up = vec3_of(*c, "camera", "up");
    camera.fov_degrees = read_real(member(*c, "camera", "fov_degrees"), "camera.fov_degrees");
    camera.ortho_height = read_real(member(*c, "camera", "ortho_height"), "camera.ortho_height");
    capture.camera = camera;
  }
}

void read_scene(const Json& j, Capture& capture, std::set<std::uint64_t>& live) {
  if (read_string(member(j, "", "type"), "type") != "scene")
    throw FieldError("type", "wrong_record", "expected \"scene\"");
  each(j, "", "objects", [&](const Json& v, const std::string& p) {
    capture.objects.push_back(read_object(v, p));
    live.insert(capture.objects.back().id);
  });
  if (const Json* s = find_member(j, "snapshot")) capture.snapshot = read_string(*s, "snapshot");
}

}  // namespace

Result<Capture> read_capture(std::istream& in) {
  Capture capture;
  std::set<std::uint64_t> live;
  std::string line;
  std::size_t number = 0;
  try {
    while (std::getline(in, line)) {
      ++number;
      if (line.empty()) continue;
      const Json j = Json::parse(line, nullptr, false);
      if (j.is_discarded() || !j.is_object()) {
        const bool last = in.peek() == std::char_traits<char>::eof();
        throw FieldError("", "bad_json", last ? "not a JSON object (the file may be truncated)" : "not a JSON object");
      }
      if (number == 1) {
        read_header(j, capture);
      } else if (number == 2) {
        read_scene(j, capture, live);
      } else {
        if (read_string(member(j, "", "type"), "type") != "step")
          throw FieldError("type", "wrong_record", "expected \"step\"");
        capture.steps.push_back(read_step(j, capture.steps.size(), live));
      }
    }
  } catch (const FieldError& e) {
    const std::string where = "line " + std::to_string(number) + (e.field().empty() ? "" : ": " + e.field());
    std::string message = e.what();
    if (!e.field().empty()) message = message.substr(e.field().size() + 2);
    return Error{ErrorCode::InvalidArgument, where, message};
  }
  if (number < 2) {
    return Error{ErrorCode::TooFew, "line " + std::to_string(number + 1),
                 number == 0 ? "empty capture: no header" : "no scene record (the file may be truncated)"};
  }
  return capture;
}

Result<std::vector<CaptureObject>> objects_at(const Capture& capture, std::size_t frame) {
  if (frame >= capture.steps.size()) {
    return Error{ErrorCode::OutOfRange, "frame",
                 "step " + std::to_string(frame) + " is not in the capture (" + std::to_string(capture.steps.size()) +
                     " steps)"};
  }
  std::map<std::uint64_t, CaptureObject> objects;
  for (const CaptureObject& o : capture.objects) objects[o.id] = o;
  for (std::size_t s = 0; s <= frame; ++s) {
    const CaptureStep& step = capture.steps[s];
    for (std::uint64_t id : step.removed) objects.erase(id);
    for (const CaptureObject& o : step.added) objects[o.id] = o;
    for (const auto& [id, pose] : step.poses) objects[id].pose = pose;
  }
  std::vector<CaptureObject> out;
  for (auto& [id, o] : objects) out.push_back(std::move(o));
  return out;
}

}  // namespace proxima::tool
