#!/usr/bin/python3
"""Side-by-side speed of two builds of Proxima (an old commit and the new one) on the same
Google Benchmark programs, in one run.

Steps:
1. List the benchmarks of each program in both build folders and keep the Proxima rows that
   both have (peer libraries' rows are left out: they are the same code on both sides).
2. For each round, run the old and the new program one after the other (the order alternates
   between rounds so that a slow spell on the shared machine hits both alike), with JSON
   output, and collect each benchmark's CPU time per iteration.
3. Print a Markdown table: the median CPU time of each side over the rounds and the ratio
   new / old, with the rows outside the tolerance marked.

Usage:
  /usr/bin/python3 bench/compare_revisions.py --old /work/base/build/release \
      --new build/release --rounds 5 [--program proxima_bench_shapes ...] [--filter REGEX]
"""
import argparse
import json
import re
import statistics
import subprocess
import sys
from pathlib import Path

PEERS = re.compile(r"fcl|bullet|libccd|ccd_|_ccd|ode|embree|box2d|reference|peers|qhull|/naive", re.I)
PROGRAMS = ["proxima_bench_shapes", "proxima_bench_narrowphase", "proxima_bench_broadphase",
            "proxima_bench_mesh", "proxima_bench_mesh_mesh", "proxima_bench_mesh_queries",
            "proxima_bench_bounds_fitting", "proxima_bench_floor"]


def list_benchmarks(exe: Path) -> list[str]:
    out = subprocess.run([str(exe), "--benchmark_list_tests=true"], capture_output=True, text=True, check=True)
    return [line for line in out.stdout.splitlines() if line and not line.startswith(" ")]


def run(exe: Path, names: list[str], min_time: float, extra: list[str]) -> dict[str, float]:
    pattern = "^(" + "|".join(re.escape(n) for n in names) + ")$"
    cmd = [str(exe), f"--benchmark_filter={pattern}", "--benchmark_format=json",
           f"--benchmark_min_time={min_time}", *extra]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    result = {}
    for b in json.loads(out.stdout)["benchmarks"]:
        if b.get("run_type") == "iteration":
            result[b["name"]] = b["cpu_time"] * {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
    return result


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--old", required=True, type=Path, help="build folder of the old commit")
    ap.add_argument("--new", required=True, type=Path, help="build folder of the new commit")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--min-time", type=float, default=0.05, help="seconds per benchmark and run")
    ap.add_argument("--program", action="append", help="benchmark program (default: all)")
    ap.add_argument("--filter", default="", help="keep benchmark names matching this regex")
    ap.add_argument("--tolerance", type=float, default=0.03, help="mark ratios beyond 1 +- this")
    ap.add_argument("--workloads", default="", help="workload folder passed to both programs")
    args = ap.parse_args()
    extra = [f"--workloads={args.workloads}"] if args.workloads else []

    print("| program | benchmark | old CPU ns | new CPU ns | new / old |")
    print("|---|---|---:|---:|---:|")
    for program in args.program or PROGRAMS:
        old_exe, new_exe = args.old / "bench" / program, args.new / "bench" / program
        if not old_exe.exists() or not new_exe.exists():
            print(f"skipped {program}: not built on both sides", file=sys.stderr)
            continue
        common = [n for n in list_benchmarks(new_exe) if n in set(list_benchmarks(old_exe))
                  and not PEERS.search(n) and re.search(args.filter, n)]
        if not common:
            continue
        samples: dict[str, tuple[list[float], list[float]]] = {n: ([], []) for n in common}
        for r in range(args.rounds):
            sides = [(0, old_exe), (1, new_exe)]
            for side, exe in (sides if r % 2 == 0 else sides[::-1]):
                for name, ns in run(exe, common, args.min_time, extra).items():
                    if name in samples:
                        samples[name][side].append(ns)
        for name in common:
            old, new = samples[name]
            if not old or not new:
                continue
            a, b = statistics.median(old), statistics.median(new)
            ratio = b / a
            mark = " **" if abs(ratio - 1) > args.tolerance else ""
            print(f"| {program.removeprefix('proxima_bench_')} | `{name}` | {a:,.1f} | {b:,.1f} | {ratio:.3f}{mark} |",
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
