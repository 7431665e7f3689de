// Prints Proxima's answers to the translation-only queries of the W9 sprite workload, one
// line per query after a first line `# folder <dir>`: `<query index> <count> <first x> <first y>` (first pixel -1 -1
// when count is 0), for the pygame comparison (pygame_sprites.py). Exit status 77 (a skip) when sprites.txt is absent
// from the workload folder (argv[1], else the default one).
#include <proxima/d2/sprite_overlap.hpp>

#include <cstdio>
#include <filesystem>

#include "support/sprite_workloads.hpp"
#include "support/workloads.hpp"

int main(int argc, char** argv) {
  using namespace proxima;
  const std::string dir = argc > 1 ? argv[1] : bench::workload_dir();
  const std::string path = bench::workload_path(dir, "sprites.txt");
  if (!std::filesystem::exists(path)) {
    std::fprintf(stderr, "sprites.txt not found in %s\n", dir.c_str());
    return 77;
  }
  const auto workload = bench::read_sprite_workload(path);
  if (!workload) {
    std::fprintf(stderr, "%s\n", workload.error().what().c_str());
    return 1;
  }
  std::printf("# folder %s\n", dir.c_str());
  for (std::size_t k = 0; k < workload->distinct.size(); ++k) {
    const bench::SpriteQuery& q = workload->distinct[k];
    if (q.turned) continue;
    const d2::SpriteOverlap r =
        d2::sprite_overlap(workload->masks[q.mask_a], {q.xa, q.ya}, workload->masks[q.mask_b], {q.xb, q.yb});
    const d2::PixelPoint first = r.first.value_or(d2::PixelPoint{-1, -1});
    std::printf("%zu %llu %lld %lld\n", k, static_cast<unsigned long long>(r.count), static_cast<long long>(first.x),
                static_cast<long long>(first.y));
  }
  return 0;
}
