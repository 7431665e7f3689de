// Object records shared by the capture recorders (capture_objects.hpp).
#include "debug/capture_objects.hpp"

#include <set>

#include "debug/json_text.hpp"

namespace proxima::debug::detail {

namespace {

std::string filter_record(const CollisionFilter& filter) {
  // 64-bit masks as decimal strings: JavaScript numbers hold integers exactly only to 2^53.
  std::string out = "{\"layer\":\"";
  out.append(std::to_string(filter.layer)).append("\",\"mask\":\"").append(std::to_string(filter.mask));
  out.append("\",\"group\":").append(std::to_string(filter.group)).append("}");
  return out;
}

bool same_pose(const Transform& a, const Transform& b) { return a.position == b.position && a.rotation == b.rotation; }

bool same_but_pose(const CaptureObjectState& a, const CaptureObjectState& b) {
  return a.kind == b.kind && a.sensor == b.sensor && a.filter == b.filter && a.user_data == b.user_data &&
         a.ccd == b.ccd;
}

}  // namespace

void object_members(std::string& out, std::uint64_t id, const CaptureObjectState& state, Rgba color) {
  out += "\"id\":";
  json::integer(out, id);
  json::key(out, "kind");
  json::string(out, to_string(state.kind));
  out += state.sensor ? ",\"sensor\":true" : ",\"sensor\":false";
  out.append(",\"filter\":").append(filter_record(state.filter));
  out.append(",\"user_data\":\"").append(std::to_string(state.user_data)).append("\"");
  json::key(out, "ccd");
  json::string(out, to_string(state.ccd));
  json::key(out, "color");
  json::color(out, color);
}

void pose_members(std::string& out, const Transform& pose) {
  json::key(out, "position");
  json::vec3(out, pose.position);
  json::key(out, "rotation");
  json::quat(out, pose.rotation);
}

std::string object_changes(CaptureObjectLog& written, std::span<const LiveObject> live,
                           const std::function<std::string(std::size_t)>& record) {
  std::string poses, added, removed;
  std::set<std::uint64_t> ids;
  for (std::size_t i = 0; i < live.size(); ++i) {
    const LiveObject& object = live[i];
    ids.insert(object.id);
    const auto it = written.find(object.id);
    if (it == written.end() || it->second.stale || !same_but_pose(it->second, object.state)) {
      if (!added.empty()) added += ',';
      added += record(i);
    } else if (!same_pose(it->second.pose, object.state.pose)) {
      poses += poses.empty() ? "{\"id\":" : ",{\"id\":";
      json::integer(poses, object.id);
      pose_members(poses, object.state.pose);
      poses += '}';
    }
    written[object.id] = object.state;
  }
  for (auto it = written.begin(); it != written.end();) {
    if (ids.count(it->first)) {
      ++it;
      continue;
    }
    if (!removed.empty()) removed += ',';
    json::integer(removed, it->first);
    it = written.erase(it);
  }
  std::string out = ",\"poses\":[";
  out.append(poses).append("],\"added\":[").append(added).append("],\"removed\":[").append(removed).append("]");
  return out;
}

}  // namespace proxima::debug::detail
