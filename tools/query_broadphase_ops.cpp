#include "query_broadphase_ops.hpp"

#include <proxima/broadphase/any_broadphase.hpp>

#include <string>
#include <vector>

namespace proxima::tool {

namespace {

constexpr std::string_view kAxisNames[] = {"x", "y", "z"};

Aabb read_box(const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 6) {
    throw FieldError(path, "wrong_type", "must be an array [minx, miny, minz, maxx, maxy, maxz]");
  }
  Aabb box;
  for (int k = 0; k < 3; ++k) {
    box.min[k] = read_real(value[static_cast<std::size_t>(k)], index_path(path, static_cast<std::size_t>(k)));
    box.max[k] = read_real(value[static_cast<std::size_t>(k + 3)], index_path(path, static_cast<std::size_t>(k + 3)));
  }
  for (int k = 0; k < 3; ++k) {
    if (box.min[k] > box.max[k]) {
      throw FieldError(path, "inverted",
                       "min " + std::string(kAxisNames[k]) + " is greater than max " + std::string(kAxisNames[k]));
    }
  }
  return box;
}

}  // namespace

std::string_view pairs_synopsis() {
  static const std::string text = [] {
    std::string s = "boxes [[minx,miny,minz,maxx,maxy,maxz], ...], structure? -> pairs [[i, j], ...] (structures: ";
    bool first = true;
    for (std::string_view name : broadphase_names()) {
      s += first ? "" : ", ";
      s += name;
      first = false;
    }
    return s + "; default brute)";
  }();
  return text;
}

Json op_pairs(const Json& request) {
  reject_unknown_fields(request, "", {"id", "op", "boxes", "structure"});
  const Json& boxes = require_member(request, "", "boxes");
  if (!boxes.is_array()) throw FieldError("boxes", "wrong_type", "must be an array of boxes");
  std::string name = "brute";
  if (const Json* s = find_member(request, "structure")) name = read_string(*s, "structure");
  std::unique_ptr<AnyBroadPhase> structure = unwrap(make_broadphase(name), "");
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const std::string path = index_path("boxes", i);
    const Aabb box = read_box(boxes[i], path);
    const BroadPhaseStatus status = structure->insert(static_cast<ProxyId>(i), box, ProxyKind::Moving);
    if (status != BroadPhaseStatus::Ok) throw FieldError(path, to_string(status), "rejected by the broad phase");
  }
  std::vector<ProxyPair> pairs;
  structure->find_pairs(pairs);
  Json list = Json::array();
  for (const ProxyPair& p : pairs) list.push_back(Json::array({p.lo, p.hi}));
  Json answer = Json::object();
  answer["pairs"] = std::move(list);
  return answer;
}

}  // namespace proxima::tool
