/// @file broadphase_registry.cpp
/// The table of broad-phase structures known by name (make_broadphase, the CLI, benchmarks).
/// To register a structure: include its header and add one line to kRegistry below.

#include <proxima/broadphase/any_broadphase.hpp>
#include <proxima/broadphase/brute_force.hpp>
#include <proxima/broadphase/bsp_tree.hpp>
#include <proxima/broadphase/dynamic_aabb_tree.hpp>
#include <proxima/broadphase/kd_tree.hpp>
#include <proxima/broadphase/loose_octree.hpp>
#include <proxima/broadphase/region_quadtree.hpp>
#include <proxima/broadphase/sweep_and_prune.hpp>
#include <proxima/broadphase/uniform_grid.hpp>

#include <array>
#include <string>

namespace proxima {

namespace {

template <class S>
std::unique_ptr<AnyBroadPhase> make_adapter(std::string_view name) {
  return std::make_unique<BroadPhaseAdapter<S>>(name);
}

// One line per structure: name, description, factory. Keep names short and lower-case.
const std::array kRegistry = {
    BroadPhaseEntry{"brute", "brute force over SoA bounds (the reference)",
                    [] { return make_adapter<BruteForceBroadPhase>("brute"); }},
    BroadPhaseEntry{"sap", "incremental sweep-and-prune (insertion sort, temporal coherence)",
                    [] { return make_adapter<SweepAndPrune>("sap"); }},
    BroadPhaseEntry{"sap_oneshot", "one-shot sorted sweep with radix sort",
                    [] { return make_adapter<SortedSweep>("sap_oneshot"); }},
    BroadPhaseEntry{"mbp", "box pruning over a grid of sweeps (flat or clustered worlds)",
                    [] { return make_adapter<MultiBoxPruning>("mbp"); }},
    BroadPhaseEntry{"tree", "dynamic AABB tree (SAH insertion, rotations, refit or rebuild)",
                    [] { return make_adapter<DynamicAabbTree>("tree"); }},
    BroadPhaseEntry{"kdtree", "kd-tree with two clip planes per node (refit or rebuild)",
                    [] { return make_adapter<KdTree>("kdtree"); }},
    BroadPhaseEntry{"bsp", "BSP tree with oblique planes (static geometry)",
                    [] { return make_adapter<BspTree>("bsp"); }},
    BroadPhaseEntry{"grid", "uniform grid over growing world bounds (similar sizes, bounded worlds)",
                    [] { return make_adapter<UniformGrid>("grid"); }},
    BroadPhaseEntry{"hash", "spatial hash of cells (unbounded worlds, similar sizes)",
                    [] { return make_adapter<SpatialHash>("hash"); }},
    BroadPhaseEntry{"hgrid", "hierarchical hash grid (sizes varying by orders of magnitude)",
                    [] { return make_adapter<HierarchicalGrid>("hgrid"); }},
    BroadPhaseEntry{"octree", "loose octree, looseness 2", [] { return make_adapter<LooseOctree>("octree"); }},
    BroadPhaseEntry{"quadtree", "loose quadtree on x and y (flat worlds)",
                    [] { return make_adapter<LooseQuadtree>("quadtree"); }},
    BroadPhaseEntry{"region_quadtree", "bucket region quadtree on x and y, boxes in every leaf they overlap",
                    [] { return make_adapter<RegionQuadtree>("region_quadtree"); }},
    // Further structures: add their line here.
};

}  // namespace

std::span<const BroadPhaseEntry> broadphase_registry() { return kRegistry; }

std::vector<std::string_view> broadphase_names() {
  std::vector<std::string_view> names;
  for (const BroadPhaseEntry& e : kRegistry) names.push_back(e.name);
  return names;
}

Result<std::unique_ptr<AnyBroadPhase>> make_broadphase(std::string_view name) {
  for (const BroadPhaseEntry& e : kRegistry) {
    if (e.name == name) return e.make();
  }
  std::string list;
  for (const BroadPhaseEntry& e : kRegistry) {
    if (!list.empty()) list += ", ";
    list += e.name;
  }
  return make_error(ErrorCode::InvalidArgument, "structure",
                    "unknown broad-phase structure '" + std::string(name) + "' (known: " + list + ")");
}

}  // namespace proxima
