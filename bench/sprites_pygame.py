"""Times pygame's Mask.overlap_area on the translation-only W9 sprite queries and, given
proxima_bench_sprites, Proxima's sprite_overlap on the same queries, and prints the ratio.

Usage (Debian's interpreter, which has python3-pygame):
  /usr/bin/python3 bench/sprites_pygame.py [--data DIR] [--proxima build/release/bench/proxima_bench_sprites]

The workload is shared/bench/FORMATS.md's W9: the count x repeat queries of sprites.txt in
order (100,000), of which the translation-only ones are timed (the turned ones have no
pygame counterpart). pygame's time includes the Python loop around each call, as a pygame
program pays it. Both sides are timed in CPU time of the process (Google Benchmark's default,
time.process_time here), so that a loaded machine does not skew the ratio; the best of
--repeats runs is reported, per query.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import pygame.mask
import pygame.version

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'support', 'python'))
from w9_sprite_masks import read_masks  # noqa: E402


def translation_queries(path, masks):
    """The translation-only queries of the whole workload (count x repeat, in order) as
    (mask A, mask B, offset of B from A)."""
    with open(path) as f:
        lines = f.read().split("\n")
    repeat = int(dict(kv.split("=") for kv in lines[0].split()[2:])["repeat"])
    out = []
    for line in lines[1:]:
        t = line.split()
        if len(t) == 6:
            ma, xa, ya, mb, xb, yb = (int(v) for v in t)
            out.append((masks[ma], masks[mb], (xb - xa, yb - ya)))
    return out * repeat


def time_pygame(queries, repeats):
    best, total = float("inf"), 0
    for _ in range(repeats):
        start = time.process_time()
        total = 0
        for a, b, offset in queries:
            total += a.overlap_area(b, offset)
        best = min(best, time.process_time() - start)
    return best / len(queries), total


def time_proxima(exe, data):
    out = subprocess.run([exe, "--workloads=" + data, "--benchmark_filter=W9_sprites/count/translation",
                          "--benchmark_format=json", "--benchmark_min_time=0.5"],
                         capture_output=True, text=True, check=True).stdout
    bench = json.loads(out)["benchmarks"][0]
    return bench["per_query"], int(bench["pixels"])


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser()
    parser.add_argument("--data", default=os.environ.get("PROXIMA_WORKLOADS",
                                                          os.path.join(here, "..", "..", "shared", "bench", "data")))
    parser.add_argument("--proxima", help="proxima_bench_sprites, to time Proxima and print the ratio")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    masks = read_masks(os.path.join(args.data, "sprite_masks.txt"), pygame)
    queries = translation_queries(os.path.join(args.data, "sprites.txt"), masks)
    per_query, pixels = time_pygame(queries, args.repeats)
    print("pygame %s Mask.overlap_area: %d translation-only queries, %.1f ns/query, %d pixels"
          % (pygame.version.ver, len(queries), per_query * 1e9, pixels))
    if args.proxima:
        ours, our_pixels = time_proxima(args.proxima, args.data)
        print("proxima sprite_overlap:        %d translation-only queries, %.1f ns/query, %d pixels"
              % (len(queries), ours * 1e9, our_pixels))
        print("ratio pygame / proxima: %.1fx%s" % (per_query / ours, "" if pixels == our_pixels else
                                                   " (pixel totals differ!)"))


if __name__ == "__main__":
    main()
