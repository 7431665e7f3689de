// `proxima mesh-info`.
//
// Steps: load the file (assimp, mesh_io), analyse the mesh as given, repair it (unless told
// not to), build the TriangleMesh from the result without a second repair (its BVH is timed),
// then print the report, the bounds, the volume and area, and the BVH statistics. A large
// mesh's three stages after loading advance a progress bar.
#include "mesh_info.hpp"

#include <proxima/shapes/triangle_mesh.hpp>

#include <chrono>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>

#include "mesh_io.hpp"
#include "progress_bar.hpp"

namespace proxima::tool {
namespace {

void put_analysis(Json& j, const MeshReport& r) {
  j["triangles_with_zero_area"] = r.degenerate_triangles;
  j["boundary_edges"] = r.boundary_edges;
  j["non_manifold_edges"] = r.non_manifold_edges;
  j["inconsistent_edges"] = r.inconsistent_edges;
  j["components"] = r.components;
  j["closed"] = r.closed;
  j["oriented"] = r.oriented;
  j["volume"] = to_json(r.volume);
  j["surface_area"] = to_json(r.surface_area);
}

Json vec_json(const Vec3& v) { return to_json(v); }

std::string number(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.9g", x);
  return buffer;
}

std::string vec_text(const Json& v) {
  std::string text = "[";
  for (std::size_t i = 0; i < 3; ++i) {
    if (i > 0) text += ", ";
    text += number(v[i].get<double>());
  }
  text += "]";
  return text;
}

std::string yes_no(const Json& b) { return b.get<bool>() ? "yes" : "no"; }

void print_analysis(std::ostream& out, const std::string& title, const Json& a, std::size_t vertices,
                    std::size_t triangles) {
  out << title << ": " << vertices << " vertices, " << triangles << " triangles, " << a["components"].get<std::size_t>()
      << " component(s)\n";
  out << "  edges: " << a["boundary_edges"].get<std::size_t>() << " boundary, "
      << a["non_manifold_edges"].get<std::size_t>() << " non-manifold, " << a["inconsistent_edges"].get<std::size_t>()
      << " inconsistently oriented\n";
  out << "  zero-area triangles: " << a["triangles_with_zero_area"].get<std::size_t>() << "\n";
  out << "  closed: " << yes_no(a["closed"]) << ", consistently oriented: " << yes_no(a["oriented"]) << "\n";
  out << "  volume: " << number(a["volume"].get<double>())
      << (a["closed"].get<bool>() ? "" : " (not closed: not meaningful)") << "\n";
  out << "  surface area: " << number(a["surface_area"].get<double>()) << "\n";
}

}  // namespace

Json mesh_info(const MeshInfoOptions& options, std::ostream* progress_out) {
  Result<IndexedMesh> loaded = load_mesh(options.path);
  if (!loaded.ok()) throw_library_error("", loaded.error());
  const IndexedMesh& input = loaded.value();
  std::ostringstream silent;
  ProgressBar progress(progress_out ? *progress_out : silent,
                       options.progress && progress_out && input.triangles.size() >= options.progress_triangles, 3,
                       "stages (analysis, repair, hierarchy)");
  Result<MeshReport> input_report = analyse_mesh(input);
  if (!input_report.ok()) throw_library_error("file", input_report.error());
  progress.update(1);

  Json info;
  info["file"] = options.path;
  Json in = Json::object();
  in["vertices"] = input.vertices.size();
  in["triangles"] = input.triangles.size();
  put_analysis(in, *input_report);
  info["input"] = std::move(in);

  IndexedMesh mesh = input;
  MeshReport report = *input_report;
  if (options.repair) {
    MeshRepairOptions repair_options;
    repair_options.weld_distance = static_cast<Real>(options.weld_distance);
    const auto repair_start = std::chrono::steady_clock::now();
    Result<RepairedMesh> repaired = repair_mesh(input, repair_options);
    const double repair_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - repair_start).count();
    if (!repaired.ok()) throw_library_error("", repaired.error());
    mesh = repaired->mesh;
    report = repaired->report;
    info["repair"] = {{"welded_vertices", report.welded_vertices},
                      {"unused_vertices_removed", report.unused_vertices_removed},
                      {"degenerate_triangles_removed", report.degenerate_triangles_removed},
                      {"duplicate_triangles_removed", report.duplicate_triangles_removed},
                      {"flipped_triangles", report.flipped_triangles},
                      {"repair_ms", repair_ms}};
  }
  progress.update(2);
  Json after = Json::object();
  after["vertices"] = mesh.vertices.size();
  after["triangles"] = mesh.triangles.size();
  put_analysis(after, report);
  info["mesh"] = std::move(after);

  if (mesh.triangles.empty()) {
    info["bounds"] = nullptr;
    info["bvh"] = nullptr;
    return info;
  }
  Aabb box = Aabb::empty();
  for (const TriangleIndices& t : mesh.triangles) {
    for (std::uint32_t k : t) box.grow(mesh.vertices[k]);
  }
  info["bounds"] = {{"min", vec_json(box.min)}, {"max", vec_json(box.max)}, {"size", vec_json(box.max - box.min)}};

  MeshCreateOptions create;
  create.repair = false;  // already repaired (or deliberately left as given)
  const auto start = std::chrono::steady_clock::now();
  Result<TriangleMesh> shape = TriangleMesh::create(std::move(mesh), create);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!shape.ok()) throw_library_error("", shape.error());
  progress.update(3);
  const BvhStats stats = shape->bvh().stats();
  info["bvh"] = {{"nodes", stats.node_count},           {"leaves", stats.leaf_count},    {"depth", stats.depth},
                 {"sah_cost", to_json(stats.sah_cost)}, {"node_bytes", sizeof(BvhNode)}, {"create_ms", ms}};
  return info;
}

int run_mesh_info(const MeshInfoOptions& options, std::ostream& out, std::ostream& err) {
  Json info;
  try {
    info = mesh_info(options, &err);
  } catch (const FieldError& e) {
    err << "proxima mesh-info: " << e.what() << "\n";
    return 1;
  }
  if (options.json) {
    out << info.dump() << "\n";
    return 0;
  }
  out << "file: " << options.path << "\n";
  print_analysis(out, "input", info["input"], info["input"]["vertices"].get<std::size_t>(),
                 info["input"]["triangles"].get<std::size_t>());
  if (info.contains("repair")) {
    const Json& r = info["repair"];
    out << "repair: " << r["welded_vertices"].get<std::size_t>() << " vertices welded, "
        << r["unused_vertices_removed"].get<std::size_t>() << " unused vertices removed, "
        << r["degenerate_triangles_removed"].get<std::size_t>() << " zero-area triangles removed, "
        << r["duplicate_triangles_removed"].get<std::size_t>() << " duplicate triangles removed, "
        << r["flipped_triangles"].get<std::size_t>() << " triangles flipped (in "
        << number(r["repair_ms"].get<double>()) << " ms)\n";
    print_analysis(out, "repaired", info["mesh"], info["mesh"]["vertices"].get<std::size_t>(),
                   info["mesh"]["triangles"].get<std::size_t>());
  } else {
    out << "repair: not run (--no-repair)\n";
  }
  if (info["bounds"].is_null()) {
    out << "bounds: none (no triangle left)\n";
    return 0;
  }
  out << "bounds: min " << vec_text(info["bounds"]["min"]) << ", max " << vec_text(info["bounds"]["max"]) << ", size "
      << vec_text(info["bounds"]["size"]) << "\n";
  const Json& b = info["bvh"];
  out << "bvh: " << b["nodes"].get<std::size_t>() << " nodes (" << b["node_bytes"].get<std::size_t>()
      << " bytes each), " << b["leaves"].get<std::size_t>() << " leaves, depth " << b["depth"].get<std::size_t>()
      << ", SAH cost " << number(b["sah_cost"].get<double>()) << ", mesh shape built in "
      << number(b["create_ms"].get<double>()) << " ms\n";
  return 0;
}

}  // namespace proxima::tool
