#!/usr/bin/env python3
"""Turns proxima_bench_broadphase JSON output into the tables of bench/RESULTS.md and the
data file of bench/plot_broadphase.gp (time per frame against N, uniform workloads).

usage: broadphase_results.py RESULTS.json|CONSOLE.txt|LARGE.log [MORE ...] OUT_DIR
(several inputs are merged, e.g. the Google Benchmark JSON of the shared files and the
--large-out JSON of the 1M runs; a later input replaces an earlier row of the same name)
writes OUT_DIR/broadphase_tables.md and OUT_DIR/broadphase_vs_n.dat
"""
import json
import sys
from collections import defaultdict

def read_console(path):
    """The console output of --benchmark_counters_tabular=true (for a run cut short)."""
    benchmarks = []
    columns = []
    for line in open(path):
        fields = line.split()
        if not fields:
            continue
        if fields[0] == "Benchmark":
            columns = fields[4:]  # after Time, CPU, Iterations
            continue
        if not fields[0].startswith("BroadPhase/"):
            continue
        b = {"name": fields[0], "real_time": float(fields[1]), "cpu_time": float(fields[3]),
             "label": fields[-1] if fields[-1] in ("peer", "proxima") else ""}
        values = fields[6:]
        for name, value in zip(columns, values):
            scale = 1.0
            if value.endswith("k"):
                value, scale = value[:-1], 1e3
            elif value.endswith("M"):
                value, scale = value[:-1], 1e6
            try:
                b[name] = float(value) * scale
            except ValueError:
                pass
        benchmarks.append(b)
    return {"benchmarks": benchmarks}


data = {"benchmarks": []}
def read_lines(path):
    """The stdout of a --large run (one JSON object a line; usable while it is running)."""
    return {"benchmarks": [json.loads(l) for l in open(path) if l.startswith("{")]}


for path in sys.argv[1:-1]:
    if path.endswith(".txt"):
        part = read_console(path)
    elif path.endswith(".log"):
        part = read_lines(path)
    else:
        part = json.load(open(path))
    data["benchmarks"] += part["benchmarks"]
out_dir = sys.argv[-1]
rows = {}
for b in data["benchmarks"]:
    parts = b["name"].split("/")
    if len(parts) < 4 or parts[2] == "floor":
        continue
    # BroadPhase/<workload>/<mode>/<structure>[/threads:2]/iterations:N/real_time
    workload, mode, structure = parts[1], parts[2], parts[3]
    threads = 2 if "threads:2" in b["name"] else 1
    rows[(workload, mode, structure, threads)] = b

workloads = [w for w in ["uniform_10k", "uniform_100k", "clustered_100k", "uniform_1000k"]
             if any(k[0] == w for k in rows)]
structures = []
for k in rows:
    if k[2] not in structures:
        structures.append(k[2])
peers = {k[2] for k, b in rows.items() if b.get("label") == "peer"}
check_text = {1: "exact", 2: "rounded", 0: "**differs**"}


def ms(b):
    # CPU time of the benchmark thread (ms): on a shared, loaded machine the wall time
    # mostly measures waiting for a core. Two-thread runs are compared by wall time.
    return b["cpu_time"]


def wall(b):
    return b["real_time"]


def cell(b):
    if not b:
        return "-"
    if b.get("over_budget"):
        # Stopped by the per-run budget of the --large runs.
        if not b.get("build_done", 1):
            return "build not done, stopped at %.3g s CPU (%.0f s wall)" % (
                b.get("build_cpu_ms", b["build_ms"]) / 1e3, b["build_ms"] / 1e3)
        if b.get("frames_done", 0) == 0:
            return "> %.3g s/frame (stopped)" % (ms(b) / 1e3)
        return "%.3g (%d frames in budget)" % (ms(b), b["frames_done"])
    return "%.3g" % ms(b)


lines = []
floors = {}
for b in data["benchmarks"]:
    parts = b["name"].split("/")
    if len(parts) >= 3 and parts[2].startswith("floor") and "_" not in parts[2]:
        floors[parts[1]] = b
if floors:
    lines.append("#### Floor: read every box, one key each, radix sort (CPU ms per frame)\n")
    lines.append("| | " + " | ".join(workloads) + " |")
    lines.append("|" + "---|" * (len(workloads) + 1))
    lines.append("| floor | " + " | ".join(cell(floors.get(w)) for w in workloads) + " |")
    lines.append("")
for mode, title in [("frame", "Time per frame (ms): update every box + all pairs"),
                    ("moving10", "Time per frame (ms), every 10th box moving"),
                    ("oneshot", "One-shot (ms): build from scratch + all pairs")]:
    lines.append("#### " + title + "\n")
    header = "| structure | " + " | ".join(workloads) + " |"
    lines.append(header)
    lines.append("|" + "---|" * (len(workloads) + 1))
    best = {}
    for w in workloads:
        times = [ms(b) for k, b in rows.items() if k[0] == w and k[1] == mode and k[3] == 1 and k[2] not in peers]
        best[w] = min(times) if times else None
    for s in structures:
        cells = []
        for w in workloads:
            b = rows.get((w, mode, s, 1))
            if not b:
                cells.append("-")
                continue
            text = cell(b)
            if s in peers and best[w] and not b.get("over_budget"):
                text += " (%.1fx)" % (ms(b) / best[w])
            b2 = rows.get((w, mode, s, 2))
            if b2:
                text += " [wall 1t %.3g, 2t %.3g]" % (wall(b), wall(b2))
            cells.append(text)
        name = s + (" (peer)" if s in peers else "")
        if all(c == "-" for c in cells):
            continue
        lines.append("| " + name + " | " + " | ".join(cells) + " |")
    if mode == "frame":
        lines.append("| brute | " + " | ".join("skipped, O(n^2)" for w in workloads) + " |")
    lines.append("")

lines.append("#### Frame mode details: pairs per frame, checksum, build time (ms), peak heap (MB)\n")
lines.append("| structure | " + " | ".join(workloads) + " |")
lines.append("|" + "---|" * (len(workloads) + 1))
for s in structures:
    cells = []
    for w in workloads:
        b = rows.get((w, "frame", s, 1))
        if not b:
            cells.append("-")
            continue
        c = int(b.get("check", -1))
        if not b.get("build_done", 1):
            cells.append("build not done, stopped at %.3g s CPU (%.0f s wall)" % (
                b.get("build_cpu_ms", b["build_ms"]) / 1e3, b["build_ms"] / 1e3))
            continue
        text = "%.0f, %s, %.3g, %.3g" % (b.get("pairs", 0), check_text.get(c, "?"), b.get("build_cpu_ms", b.get("build_ms", 0)), b.get("mem_MB", 0))
        if b.get("over_budget"):
            text += ", %d frames" % b.get("frames_done", 0)
        if b.get("missing", 0) > 0.001:
            text += ", misses %.2f/frame" % b["missing"]
        cells.append(text)
    if all(c == "-" for c in cells):
        continue
    lines.append("| " + s + (" (peer)" if s in peers else "") + " | " + " | ".join(cells) + " |")
lines.append("")
open(out_dir + "/broadphase_tables.md", "w").write("\n".join(lines) + "\n")

# Time per frame against N for the uniform workloads, one column per structure.
sizes = [("uniform_10k", 10000), ("uniform_100k", 100000), ("uniform_1000k", 1000000)]
cols = [s for s in structures if any(rows.get((w, "frame", s, 1)) for w, _ in sizes)]
with open(out_dir + "/broadphase_vs_n.dat", "w") as f:
    f.write("N " + " ".join(cols) + "\n")
    for w, n in sizes:
        vals = []
        for s in cols:
            b = rows.get((w, "frame", s, 1))
            ok = b and not (b.get("over_budget") and b.get("frames_done", 0) == 0)
            vals.append("%.6g" % ms(b) if ok else "NaN")
        f.write(str(n) + " " + " ".join(vals) + "\n")
print("columns:", " ".join(cols))
