// proxima.BroadPhase: any registered broad-phase structure by name ("tree", "sap", "grid",
// ...; proxima.broadphase_names() lists them) over caller ids and boxes, with batched
// insert/update from numpy arrays and the overlapping pairs as an (M, 2) array.
#include <proxima/broadphase/any_broadphase.hpp>

#include <algorithm>
#include <pybind11/stl.h>

#include "batch_arrays.hpp"
#include "module_parts.hpp"

namespace proxima::python {
namespace {

void check_status(BroadPhaseStatus status, const std::string& field) {
  if (status == BroadPhaseStatus::Ok) return;
  const ErrorCode code = status == BroadPhaseStatus::NotFinite    ? ErrorCode::NotFinite
                         : status == BroadPhaseStatus::InvalidBox ? ErrorCode::OutOfRange
                                                                  : ErrorCode::InvalidArgument;
  raise_error(make_error(code, field, to_string(status)));
}

/// Boxes of an (N, 6) array (min x, y, z, max x, y, z).
std::vector<Aabb> read_boxes(py::handle boxes) {
  const RowReader r(boxes, 6, "boxes", false);
  std::vector<Aabb> list(static_cast<std::size_t>(r.rows()));
  r.find_rejected(0, r.rows(), [&](py::ssize_t i, const auto& number) {
    list[static_cast<std::size_t>(i)] = {{number(0), number(1), number(2)}, {number(3), number(4), number(5)}};
    return true;  // the broad phase names a bad box
  });
  return list;
}

std::vector<ProxyId> read_ids(py::handle ids, std::size_t n) {
  const auto a = py::array_t<std::int64_t, py::array::forcecast>::ensure(ids);
  if (!a || a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != n) {
    raise_argument_error("ids", "expected one id per box");
  }
  std::vector<ProxyId> list(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t v = a.at(static_cast<py::ssize_t>(i));
    if (v < 0 || v > std::int64_t(0xffffffff)) raise_argument_error("ids[" + std::to_string(i) + "]", "out of range");
    list[i] = static_cast<ProxyId>(v);
  }
  return list;
}

py::array_t<std::uint32_t> pair_array(const std::vector<ProxyPair>& pairs) {
  py::array_t<std::uint32_t> out({static_cast<py::ssize_t>(pairs.size()), py::ssize_t(2)});
  std::uint32_t* d = out.mutable_data();
  for (const ProxyPair& p : pairs) *d++ = p.lo, *d++ = p.hi;
  return out;
}

}  // namespace

void bind_broadphase(py::module_& m) {
  py::enum_<ProxyKind>(m, "ProxyKind", "Static proxies are never paired with each other.")
      .value("Static", ProxyKind::Static)
      .value("Moving", ProxyKind::Moving);
  m.def(
      "broadphase_names",
      [] {
        std::vector<std::string> names;
        for (std::string_view n : broadphase_names()) names.emplace_back(n);
        return names;
      },
      "Names of the registered broad-phase structures.");
  py::class_<AnyBroadPhase, std::unique_ptr<AnyBroadPhase>>(
      m, "BroadPhase", "A broad-phase structure over boxes (world frame) with caller-chosen integer ids.")
      .def(py::init([](const std::string& name) { return take(make_broadphase(name)); }), py::arg("name") = "tree")
      .def_property_readonly("name", [](const AnyBroadPhase& b) { return std::string(b.name()); })
      .def(
          "insert",
          [](AnyBroadPhase& b, py::handle ids, py::handle boxes, ProxyKind kind) {
            const std::vector<Aabb> list = read_boxes(boxes);
            const std::vector<ProxyId> id = read_ids(ids, list.size());
            for (std::size_t i = 0; i < list.size(); ++i) {  // validate all first: nothing inserted on an error
              const Aabb& a = list[i];
              if (!(a.is_valid()) || !std::isfinite(a.min.x + a.min.y + a.min.z + a.max.x + a.max.y + a.max.z))
                raise_argument_error("boxes[" + std::to_string(i) + "]", "must be finite with min <= max");
            }
            std::vector<ProxyId> sorted = id;
            std::sort(sorted.begin(), sorted.end());
            if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
              raise_argument_error("ids", "repeated id");
            for (std::size_t i = 0; i < list.size(); ++i)
              check_status(b.insert(id[i], list[i], kind), "ids[" + std::to_string(i) + "]");
          },
          py::arg("ids"), py::arg("boxes"), py::arg("kind") = ProxyKind::Moving,
          "Inserts proxies: ids (N,) and boxes (N, 6): min x, y, z, max x, y, z.")
      .def(
          "update",
          [](AnyBroadPhase& b, py::handle ids, py::handle boxes) {
            const std::vector<Aabb> list = read_boxes(boxes);
            const std::vector<ProxyId> id = read_ids(ids, list.size());
            std::vector<ProxyUpdate> updates(list.size());
            for (std::size_t i = 0; i < list.size(); ++i) updates[i] = {id[i], list[i]};
            check_status(b.update(updates), "boxes");
          },
          py::arg("ids"), py::arg("boxes"), "Moves proxies to new boxes (all validated first).")
      .def(
          "remove", [](AnyBroadPhase& b, std::uint32_t id) { check_status(b.remove(id), "id"); }, py::arg("id"))
      .def(
          "pairs",
          [](AnyBroadPhase& b, long threads) {
            std::vector<ProxyPair> pairs;
            const std::size_t count = resolve_threads(threads);
            {
              py::gil_scoped_release release;
              if (count <= 1)
                b.find_pairs(pairs);
              else
                b.find_pairs(pairs, thread_pool(count));
            }
            return pair_array(pairs);
          },
          py::kw_only(), py::arg("threads") = 1, "Every overlapping pair (lo < hi), sorted: a uint32 array (M, 2).")
      .def(
          "query_box",
          [](const AnyBroadPhase& b, const Aabb& box) {
            std::vector<ProxyId> found;
            b.query_aabb(box, [&](ProxyId id) {
              found.push_back(id);
              return true;
            });
            std::sort(found.begin(), found.end());
            return found;
          },
          py::arg("box"), "Ids of the proxies whose boxes meet the box, ascending.")
      .def("__len__", [](const AnyBroadPhase& b) { return b.size(); });
}

}  // namespace proxima::python
