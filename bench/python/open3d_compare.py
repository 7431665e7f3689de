#!/usr/bin/python3
"""Proxima's batched mesh queries beside Open3D's RaycastingScene (Embree), with answers checked.

Queries (shared workloads, shared/bench/FORMATS.md):
  rays            the W5 rays against the W4 torus knot: proxima.raycast_batch vs cast_rays.
                  Open3D has no ray length, so both libraries are timed on unbounded rays (the
                  same question); proxima is also timed with the W5 tmax ("rays_tmax").
                  Open3D's hits are then clipped to tmax to compare with the W5 answers.
  closest         points uniform in each W4 mesh's box grown by 10 % per side:
                  proxima.closest_point_batch (point and signed distance in one call) vs
                  compute_closest_points ("closest") and compute_signed_distance ("signed").
Each query runs single-threaded (proxima threads=1, Open3D nthreads=1) and threaded (proxima
threads=0, Open3D nthreads=0: both use every hardware thread). Open3D works in float32: its
inputs are float32 tensors made before timing; proxima reads the float64 arrays in place.
Times: smallest wall time of --repeats calls, the two libraries alternating. Agreement: hit
flags, |t difference| on rays both hit, |distance difference| and sign agreement on points;
for the icosphere (radii 0.97 to 1.03) each library's signs are also checked against the
radius (points below 0.97 are inside, above 1.03 outside). Before timing, Open3D's ray casting
is probed on its own documented example (a ray through the unit box from create_box): a build
whose cast_rays misses it is reported as such, its ray answers and signed-distance signs (which
it computes by counting ray crossings) as wrong, and its ray times as not comparable.

  PYTHONPATH=build/release/python /usr/bin/python3 bench/python/open3d_compare.py \
      [--n 100000] [--repeats 3] [--json out.json]
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

import numpy as np
import open3d as o3d

import proxima

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python" / "examples"))
import example_data  # noqa: E402

# Agreement tolerances (both libraries in float32 on coordinates of size ~1 to 5).
T_TOLERANCE = 1e-4
DISTANCE_TOLERANCE = 1e-4


def open3d_scene(vertices, triangles):
    """A RaycastingScene holding one mesh (float32 vertices, uint32 indices)."""
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(vertices.astype(np.float32)), o3d.core.Tensor(triangles.astype(np.uint32)))
    return scene


def open3d_rays_work():
    """Whether Open3D's cast_rays hits the unit box of create_box with a ray straight through it."""
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.t.geometry.TriangleMesh.from_legacy(o3d.geometry.TriangleMesh.create_box()))
    ray = o3d.core.Tensor([[0.5, 0.5, 10.0, 0.0, 0.0, -1.0]], dtype=o3d.core.Dtype.Float32)
    return bool(np.isfinite(scene.cast_rays(ray)["t_hit"].numpy()[0]))


def proxima_mesh(vertices, triangles):
    """The mesh as proxima builds it, triangles kept in file order (no repair: the W4 meshes are clean)."""
    return proxima.TriangleMesh(vertices, triangles, repair=False)


def best_times(calls, repeats):
    """Smallest wall time of each named call over `repeats` alternating rounds, and each one's last
    answer (Open3D's answers are tensors, kept alive until read: a .numpy() view does not hold them)."""
    best, answers = {name: float("inf") for name in calls}, {}
    for _ in range(repeats):
        for name, call in calls.items():
            start = time.perf_counter()
            answers[name] = call()
            best[name] = min(best[name], time.perf_counter() - start)
    return best, answers


# ---- agreement ----------------------------------------------------------------------------------


def ray_agreement(proxima_hits, open3d_t, max_t):
    """Hit-flag mismatches and the largest |t difference| over rays both libraries hit within max_t."""
    o3d_hit = np.isfinite(open3d_t) & (open3d_t <= max_t)
    ours = proxima_hits["hit"].astype(bool)  # RAY_HIT_DTYPE stores hit as u1
    both = ours & o3d_hit
    dt = np.abs(proxima_hits["t"][both] - open3d_t[both])
    return {
        "rays": int(len(max_t)),
        "hits_proxima": int(ours.sum()),
        "hits_open3d": int(o3d_hit.sum()),
        "hit_mismatches": int((ours != o3d_hit).sum()),
        "max_t_difference": float(dt.max()) if dt.size else 0.0,
        "t_beyond_tolerance": int((dt > T_TOLERANCE * np.maximum(1.0, open3d_t[both])).sum()),
    }


def point_agreement(surface, points, open3d_points, open3d_signed, sphere_like):
    """Largest |distance difference| (closest points and signed distances) and sign mismatches;
    for a sphere-like mesh (radii 0.97..1.03) also each library's signs that contradict the radius."""
    unsigned = np.linalg.norm(points - open3d_points, axis=1)
    ours = surface["signed_distance"]
    extra = {}
    if sphere_like:
        radius = np.linalg.norm(points, axis=1)
        inside, outside = radius < 0.97, radius > 1.03
        extra = {"sign_errors_proxima": int((ours[inside] >= 0).sum() + (ours[outside] <= 0).sum()),
                 "sign_errors_open3d": int((open3d_signed[inside] >= 0).sum() + (open3d_signed[outside] <= 0).sum())}
    return extra | {
        "points": int(len(points)),
        "max_distance_difference": float(np.abs(np.abs(ours) - unsigned).max()),
        "max_signed_difference": float(np.abs(ours - open3d_signed).max()),
        "sign_mismatches": int((np.sign(ours) != np.sign(open3d_signed)).sum()),
        "beyond_tolerance": int((np.abs(np.abs(ours) - unsigned) > DISTANCE_TOLERANCE).sum()),
    }


# ---- the comparisons -----------------------------------------------------------------------------


def compare_rays(mesh_data, rays, max_t, repeats):
    """Rows of queries/s for the W5 rays, single-threaded and threaded, and the agreement."""
    mesh, scene = proxima_mesh(*mesh_data), open3d_scene(*mesh_data)
    identity = np.array([0, 0, 0, 0, 0, 0, 1.0])
    rays32 = o3d.core.Tensor(rays.astype(np.float32))
    rows, agreement = [], None
    for mode, threads in (("single", 1), ("threaded", 0)):
        calls = {
            "proxima": lambda: proxima.raycast_batch(mesh, identity, rays, threads=threads),
            "proxima_tmax": lambda: proxima.raycast_batch(mesh, identity, rays, max_t, threads=threads),
            "open3d": lambda: scene.cast_rays(rays32, nthreads=threads),
        }
        best, answers = best_times(calls, repeats)
        rows.append(rate_row("rays", "torusknot", mode, len(rays), best["proxima"], best["open3d"]))
        rows.append(rate_row("rays_tmax", "torusknot", mode, len(rays), best["proxima_tmax"], best["open3d"]))
        agreement = ray_agreement(answers["proxima_tmax"], answers["open3d"]["t_hit"].numpy().copy(), max_t)
    return rows, agreement


def compare_closest(name, mesh_data, points, repeats):
    """Rows of queries/s for closest points and signed distances to one mesh, and the agreement."""
    mesh, scene = proxima_mesh(*mesh_data), open3d_scene(*mesh_data)
    identity = np.array([0, 0, 0, 0, 0, 0, 1.0])
    points32 = o3d.core.Tensor(points.astype(np.float32))
    rows, agreement = [], None
    for mode, threads in (("single", 1), ("threaded", 0)):
        calls = {
            "proxima": lambda: proxima.closest_point_batch(mesh, identity, points, threads=threads),
            "open3d_closest": lambda: scene.compute_closest_points(points32, nthreads=threads),
            "open3d_signed": lambda: scene.compute_signed_distance(points32, nthreads=threads),
        }
        best, answers = best_times(calls, repeats)
        rows.append(rate_row("closest", name, mode, len(points), best["proxima"], best["open3d_closest"]))
        rows.append(rate_row("signed", name, mode, len(points), best["proxima"], best["open3d_signed"]))
        closest = answers["open3d_closest"]["points"].numpy().copy()
        agreement = point_agreement(answers["proxima"], points, closest, answers["open3d_signed"].numpy().copy(),
                                    name == "icosphere")
    return rows, agreement


def rate_row(query, mesh, mode, n, proxima_seconds, open3d_seconds):
    return {"query": query, "mesh": mesh, "threads": mode, "n": n,
            "proxima_per_s": n / proxima_seconds, "open3d_per_s": n / open3d_seconds,
            "ratio": open3d_seconds / proxima_seconds}


def points_around(rng, vertices, n):
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    margin = 0.1 * (hi - lo)
    return rng.uniform(lo - margin, hi + margin, size=(n, 3))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=100_000, help="rays (at most the file's) and points per mesh")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--json", type=Path)
    args = parser.parse_args(argv)
    files = {name: example_data.workload_file(name) for name in ("mesh_torusknot.obj", "mesh_icosphere.obj", "rays.txt")}
    if None in files.values():
        sys.exit("the shared W4/W5 workload files are absent (set PROXIMA_WORKLOADS)")
    knot = example_data.read_obj(files["mesh_torusknot.obj"])
    sphere = example_data.read_obj(files["mesh_icosphere.obj"])
    rays, max_t, _ = example_data.read_rays(files["rays.txt"])
    rays, max_t = rays[: args.n], max_t[: args.n]
    rays_work = open3d_rays_work()
    rng = np.random.default_rng(7)
    rows, agreement = [], {}
    rays_rows, agreement["rays_torusknot"] = compare_rays(knot, rays, max_t, args.repeats)
    rows += rays_rows
    for name, mesh_data in (("torusknot", knot), ("icosphere", sphere)):
        mesh_rows, agreement[f"closest_{name}"] = compare_closest(name, mesh_data, points_around(rng, mesh_data[0], args.n), args.repeats)
        rows += mesh_rows
    print(f"Open3D {o3d.__version__}; {os.cpu_count()} hardware threads; threaded = proxima threads=0, "
          f"Open3D nthreads=0; smallest wall time of {args.repeats} calls")
    print(f"{'query':10} {'mesh':10} {'threads':9} {'proxima q/s':>12} {'Open3D q/s':>12} {'proxima/Open3D':>15}")
    for r in rows:
        print(f"{r['query']:10} {r['mesh']:10} {r['threads']:9} {r['proxima_per_s']:12.4g} {r['open3d_per_s']:12.4g} "
              f"{r['ratio']:15.2f}")
    if not rays_work:
        print("Open3D's cast_rays misses its own box example here: its ray answers (and the signs of "
              "compute_signed_distance, found by counting ray crossings) are wrong, and the ray times are not comparable")
    for name, a in agreement.items():
        print(f"agreement {name}: " + ", ".join(f"{k}={v:.3g}" if isinstance(v, float) else f"{k}={v}" for k, v in a.items()))
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "agreement": agreement, "open3d_rays_work": rays_work}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
