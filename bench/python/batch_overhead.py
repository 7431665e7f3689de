#!/usr/bin/python3
"""Per-item cost of proxima's batched Python calls against the same loop in C++.

For each case the script draws (or reads) N rows, writes them to a temporary file that the C++
program `proxima_bench_python_loop` (bench/python_batch_loop.cpp) reads, so both sides run on
the same rows; then it alternates rounds of the C++ loop and of the batched call (threads=1,
once returning a new array and once filling `out=`), keeps the smallest time of each, checks
that every answer of Python equals the C++ one bit for bit, and prints ns per item and the
ratio Python / C++ (the issue's target: at most 1.10). Times are thread CPU time (the machine
may be shared); wall times are printed beside them.

Cases: distance_batch box-sphere and hull-hull at random poses; raycast_batch of the W5 rays
against the W4 torus knot; closest_point_batch of points around the W4 torus knot and
icosphere. The workload cases are skipped when the shared files are absent.

  PYTHONPATH=build/release/python /usr/bin/python3 bench/python/batch_overhead.py \
      [--n 100000] [--repeats 3] [--rounds 2] [--loop build/release/bench/proxima_bench_python_loop] \
      [--cases distance_box_sphere,...] [--json out.json]
"""

import argparse
import json
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import proxima

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python" / "examples"))
import example_data  # noqa: E402

DISTANCE, RAYCAST, CLOSEST_POINT = 1, 2, 3
TARGET_RATIO = 1.10


# ---- inputs ---------------------------------------------------------------------------------


def random_poses(rng, n, spread):
    """(n, 7) poses: positions uniform in [-spread, spread]^3, uniformly random rotations."""
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return np.hstack([rng.uniform(-spread, spread, size=(n, 3)), q])


def ellipsoid_points(rng, count, radii):
    """`count` points on an ellipsoid of semi-axes `radii` (all of them hull vertices)."""
    d = rng.normal(size=(count, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True) * np.asarray(radii)


def load_mesh(name):
    """A W4 mesh file as (vertices, triangles), or None when absent."""
    path = example_data.workload_file(name)
    return None if path is None else example_data.read_obj(path)


# ---- the C++ program's input file ---------------------------------------------------------


def shape_record(kind, values):
    """The bytes of one shape: ('sphere', r), ('box', h), ('hull', points), ('mesh', (v, t)), ('capsule', (r, hl))."""
    if kind == "sphere":
        return struct.pack("<Id", 1, values)
    if kind == "box":
        return struct.pack("<I3d", 2, *values)
    if kind == "hull":
        return struct.pack("<IQ", 3, len(values)) + np.ascontiguousarray(values, "<f8").tobytes()
    if kind == "mesh":
        vertices, triangles = values
        head = struct.pack("<IQQ", 4, len(vertices), len(triangles))
        return head + np.ascontiguousarray(vertices, "<f8").tobytes() + np.ascontiguousarray(triangles, "<u4").tobytes()
    if kind == "capsule":
        return struct.pack("<Idd", 5, *values)
    raise ValueError(kind)


def make_shape(kind, values):
    """The proxima shape of a shape record."""
    if kind == "sphere":
        return proxima.Sphere(values)
    if kind == "box":
        return proxima.Box(values)
    if kind == "hull":
        return proxima.ConvexHull(values)
    if kind == "mesh":
        return proxima.TriangleMesh(*values)
    return proxima.Capsule(*values)


def f64(array):
    return np.ascontiguousarray(array, "<f8").tobytes()


# ---- cases ------------------------------------------------------------------------------------
# Each case: name, query, the C++ input body (after the header), and a function that runs the
# batched call once and returns its answers in the C++ program's layout.


def distance_case(name, shape_a, shape_b, poses_a, poses_b):
    a, b = make_shape(*shape_a), make_shape(*shape_b)
    body = shape_record(*shape_a) + shape_record(*shape_b) + struct.pack("<Q", len(poses_a)) + f64(poses_a) + f64(poses_b)
    out = np.empty(len(poses_a), proxima.DISTANCE_DTYPE)

    def call(use_out):
        r = proxima.distance_batch(a, poses_a, b, poses_b, threads=1, out=out if use_out else None)
        return r["signed_distance"][:, None]

    return {"name": name, "query": DISTANCE, "n": len(poses_a), "body": body, "call": call}


def raycast_case(name, mesh, rays, max_t):
    shape = make_shape("mesh", mesh)
    pose = np.array([0, 0, 0, 0, 0, 0, 1], dtype=np.float64)
    body = shape_record("mesh", mesh) + f64(pose) + struct.pack("<Q", len(rays)) + f64(rays) + f64(max_t)
    out = np.empty(len(rays), proxima.RAY_HIT_DTYPE)

    def call(use_out):
        r = proxima.raycast_batch(shape, pose, rays, max_t, threads=1, out=out if use_out else None)
        return np.column_stack([r["hit"].astype(np.float64), r["t"]])

    return {"name": name, "query": RAYCAST, "n": len(rays), "body": body, "call": call}


def closest_point_case(name, mesh, points):
    shape = make_shape("mesh", mesh)
    pose = np.array([0, 0, 0, 0, 0, 0, 1], dtype=np.float64)
    body = shape_record("mesh", mesh) + f64(pose) + struct.pack("<Q", len(points)) + f64(points)
    out = np.empty(len(points), proxima.SURFACE_POINT_DTYPE)

    def call(use_out):
        r = proxima.closest_point_batch(shape, pose, points, threads=1, out=out if use_out else None)
        return np.column_stack([r["point"], r["signed_distance"]])

    return {"name": name, "query": CLOSEST_POINT, "n": len(points), "body": body, "call": call}


def points_around(rng, vertices, n):
    """n points uniform in the box of `vertices` grown by 10 % per side."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    margin = 0.1 * (hi - lo)
    return rng.uniform(lo - margin, hi + margin, size=(n, 3))


def build_cases(n, wanted):
    """The cases named in `wanted` (all when None) whose inputs exist, and the skipped names."""
    rng = np.random.default_rng(20240516)
    builders = {
        "distance_box_sphere": lambda: distance_case(
            "distance_box_sphere", ("box", (0.5, 0.3, 0.4)), ("sphere", 0.4),
            random_poses(rng, n, 0.9), random_poses(rng, n, 0.9)),
        "distance_hull_hull": lambda: distance_case(
            "distance_hull_hull", ("hull", ellipsoid_points(rng, 32, (0.6, 0.4, 0.3))),
            ("hull", ellipsoid_points(rng, 32, (0.5, 0.5, 0.35))), random_poses(rng, n, 1.0), random_poses(rng, n, 1.0)),
    }
    knot, sphere = load_mesh("mesh_torusknot.obj"), load_mesh("mesh_icosphere.obj")
    rays_file = example_data.workload_file("rays.txt")
    if knot is not None and rays_file is not None:
        def w5_case():
            rays, max_t, _ = example_data.read_rays(rays_file)
            rows = np.arange(n) % len(rays)  # the compact file has 100,000 rays; repeated beyond
            return raycast_case("raycast_w5_torusknot", knot, rays[rows], max_t[rows])
        builders["raycast_w5_torusknot"] = w5_case
    if knot is not None:
        builders["closest_point_torusknot"] = lambda: closest_point_case(
            "closest_point_torusknot", knot, points_around(rng, knot[0], n))
    if sphere is not None:
        builders["closest_point_icosphere"] = lambda: closest_point_case(
            "closest_point_icosphere", sphere, points_around(rng, sphere[0], n))
    names = list(builders) if wanted is None else wanted
    skipped = [name for name in names if name not in builders]
    return [builders[name]() for name in names if name in builders], skipped


# ---- timing -----------------------------------------------------------------------------------


def time_python(case, repeats, use_out):
    """(wall seconds, thread CPU seconds) of each of `repeats` calls, and the last answers."""
    wall, cpu, answers = [], [], None
    for _ in range(repeats):
        c0, w0 = time.thread_time(), time.perf_counter()
        answers = case["call"](use_out)
        w1, c1 = time.perf_counter(), time.thread_time()
        wall.append(w1 - w0)
        cpu.append(c1 - c0)
    return wall, cpu, answers


def time_cpp(case, loop, repeats, folder):
    """The C++ program's report (seconds per repeat of its "prepared" and "rows" loops, its Real
    type) and its answers."""
    input_path, answers_path = Path(folder) / "input.bin", Path(folder) / "answers.bin"
    if not input_path.exists():
        input_path.write_bytes(b"PXLOOP01" + struct.pack("<II", case["query"], repeats) + case["body"])
    run = subprocess.run([str(loop), str(input_path), str(answers_path)], capture_output=True, text=True, check=False)
    if run.returncode != 0:
        raise RuntimeError(f"{loop} failed: {run.stderr.strip()}")
    return json.loads(run.stdout), np.fromfile(answers_path, "<f8")


def measure(case, loop, repeats, rounds):
    """Smallest times per item of C++, the batched call and the batched call with out=, and checks."""
    times = {"cpp": ([], []), "cpp_rows": ([], []), "python": ([], []), "python_out": ([], [])}
    with tempfile.TemporaryDirectory(prefix="proxima_overhead_") as folder:
        for _ in range(rounds):
            report, cpp_answers = time_cpp(case, loop, repeats, folder)
            for key, loop_name in (("cpp", "prepared"), ("cpp_rows", "rows")):
                times[key][0].extend(report[loop_name]["wall_s"]), times[key][1].extend(report[loop_name]["cpu_s"])
            for key, use_out in (("python", False), ("python_out", True)):
                wall, cpu, answers = time_python(case, repeats, use_out)
                times[key][0].extend(wall), times[key][1].extend(cpu)
    python_answers = answers.reshape(-1)
    identical = np.array_equal(python_answers, cpp_answers)
    n = case["n"]
    row = {"case": case["name"], "n": n, "real": report["real"], "identical_answers": bool(identical)}
    for key, (wall, cpu) in times.items():
        row[f"{key}_ns"] = 1e9 * min(cpu) / n
        row[f"{key}_wall_ns"] = 1e9 * min(wall) / n
    row["ratio"] = row["python_ns"] / row["cpp_ns"]
    row["ratio_out"] = row["python_out_ns"] / row["cpp_ns"]
    row["ratio_wall"] = row["python_wall_ns"] / row["cpp_wall_ns"]
    row["ratio_rows"] = row["python_ns"] / row["cpp_rows_ns"]
    row["met"] = row["ratio"] <= TARGET_RATIO
    return row


def default_loop():
    root = Path(__file__).resolve().parents[2]
    return root / "build" / "release" / "bench" / "proxima_bench_python_loop"


def print_table(rows):
    print(f"{'case':24} {'n':>7} {'C++ ns':>8} {'C++rows':>8} {'batch':>8} {'out=':>8} {'ratio':>6} "
          f"{'out=':>6} {'wall':>6} {'/rows':>6}  same  target<=1.10")
    for r in rows:
        print(f"{r['case']:24} {r['n']:7d} {r['cpp_ns']:8.1f} {r['cpp_rows_ns']:8.1f} {r['python_ns']:8.1f} "
              f"{r['python_out_ns']:8.1f} {r['ratio']:6.3f} {r['ratio_out']:6.3f} {r['ratio_wall']:6.3f} "
              f"{r['ratio_rows']:6.3f}  {'yes' if r['identical_answers'] else 'NO':4}  {'met' if r['met'] else 'NOT met'}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=100_000)
    parser.add_argument("--repeats", type=int, default=3, help="timed calls per round and side")
    parser.add_argument("--rounds", type=int, default=2, help="alternating rounds of C++ and Python")
    parser.add_argument("--loop", type=Path, default=default_loop(), help="the proxima_bench_python_loop program")
    parser.add_argument("--cases", help="comma-separated case names (default: all)")
    parser.add_argument("--json", type=Path, help="also write the rows to this file")
    args = parser.parse_args(argv)
    if not args.loop.exists():
        sys.exit(f"{args.loop} not found: build the target proxima_bench_python_loop or pass --loop")
    cases, skipped = build_cases(args.n, args.cases.split(",") if args.cases else None)
    for name in skipped:
        print(f"skipped {name}: its workload files are absent or the name is unknown")
    rows = []
    for case in cases:
        rows.append(measure(case, args.loop, args.repeats, args.rounds))
        print(f"measured {case['name']}", file=sys.stderr, flush=True)
    print(f"proxima real: {rows[0]['real'] if rows else '?'}; ns per item, smallest thread CPU time of "
          f"{args.rounds} x {args.repeats} runs per side.\nC++: the loop on prepared Transform/Ray/Vec3; "
          f"C++rows: the loop converting the same float64 rows itself; batch: the batched call (threads=1), "
          f"out=: filling a preallocated array.\nratio = batch / C++ (the target), out= = out= / C++, "
          f"wall = the ratio on wall time, /rows = batch / C++rows.")
    print_table(rows)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=2))
    return 0 if all(r["identical_answers"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
