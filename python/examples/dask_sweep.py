#!/usr/bin/python3
"""A 1,000,000-pose collision sweep split over a dask.distributed cluster of worker processes.

The sweep: a capsule (a robot link) at each of N random poses against a few fixed obstacles
(a sphere, a box, a cylinder); per pose, the clearance (smallest signed distance to any
obstacle, from distance_batch), the nearest obstacle and whether any obstacle is touched (from
intersect_batch). The scene travels to the workers as one pickle (the shapes pickle by their
constructor arguments); each worker process rebuilds it once (cached by the pickle's digest)
and runs the batched queries on its chunks of poses with threads=1. The script runs the sweep
serially too and checks that the distributed answers are identical, bit for bit.

  PYTHONPATH=build/release/python /usr/bin/python3 python/examples/dask_sweep.py \
      [--poses 1000000] [--chunks 16] [--workers 2]

Hook for the collision world: scene_payload() and rebuild_scene() are the only places that know
what a scene is; when proxima's world pickles through its snapshot, the payload becomes
pickle.dumps(world) and check_chunk queries the rebuilt world instead of the shape list.
"""

import argparse
import hashlib
import os
import pickle
import sys
import time
from pathlib import Path

import numpy as np

import proxima

LINK = proxima.Capsule(radius=0.08, half_length=0.3)
OBSTACLES = (  # shape, pose (px, py, pz, qx, qy, qz, qw)
    (proxima.Sphere(0.35), (0.6, 0.2, 0.3, 0, 0, 0, 1)),
    (proxima.Box((0.5, 0.25, 0.4)), (-0.5, -0.4, 0.0, 0, 0, 0.3826834, 0.9238795)),
    (proxima.Cylinder(0.2, 0.6), (0.1, 0.7, -0.4, 0.7071068, 0, 0, 0.7071068)),
)

_scenes = {}  # payload digest -> rebuilt scene, per process


def scene_payload(link=LINK, obstacles=OBSTACLES):
    """The scene as bytes to send to the workers (see the module's note on the world's snapshot)."""
    return pickle.dumps({"link": link, "obstacles": [(shape, np.array(pose, float)) for shape, pose in obstacles]})


def rebuild_scene(payload):
    """The scene of a payload, unpickled once per process."""
    key = hashlib.sha256(payload).hexdigest()
    if key not in _scenes:
        _scenes[key] = pickle.loads(payload)
    return _scenes[key]


def random_poses(count, seed=1):
    """(count, 7) poses of the link: positions uniform in [-1.2, 1.2]^3, uniform random rotations."""
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(count, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return np.hstack([rng.uniform(-1.2, 1.2, size=(count, 3)), q])


def check_chunk(payload, poses):
    """Clearance (float64), nearest obstacle (int8) and collision flag (bool) of each pose."""
    scene = rebuild_scene(payload)
    distances, touching = [], np.zeros(len(poses), bool)
    for shape, pose in scene["obstacles"]:
        distances.append(proxima.distance_batch(scene["link"], poses, shape, pose, threads=1)["signed_distance"])
        touching |= proxima.intersect_batch(scene["link"], poses, shape, pose, threads=1)
    distances = np.stack(distances)
    return {"clearance": distances.min(axis=0), "nearest": distances.argmin(axis=0).astype(np.int8),
            "colliding": touching}


def concatenate(parts):
    return {key: np.concatenate([part[key] for part in parts]) for key in parts[0]}


def serial_sweep(payload, poses, chunks):
    """The sweep in this process, chunk by chunk."""
    return concatenate([check_chunk(payload, chunk) for chunk in np.array_split(poses, chunks)])


def distributed_sweep(client, payload, poses, chunks):
    """The sweep on the cluster: the payload broadcast once, the chunks scattered, answers in order."""
    payload_future = client.scatter(payload, broadcast=True)
    chunk_futures = client.scatter(np.array_split(poses, chunks))
    futures = client.map(check_chunk, [payload_future] * len(chunk_futures), chunk_futures, pure=False)
    return concatenate(client.gather(futures))


def identical(a, b):
    """Whether two sweeps' answers are equal bit for bit."""
    return all(a[key].dtype == b[key].dtype and a[key].tobytes() == b[key].tobytes() for key in a)


def start_cluster(workers):
    """A LocalCluster of `workers` single-threaded worker processes that can import this module."""
    from dask.distributed import Client, LocalCluster

    folders = [str(Path(__file__).resolve().parent), str(Path(proxima.__file__).resolve().parents[1])]
    os.environ["PYTHONPATH"] = os.pathsep.join(folders + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p])
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
    return cluster, Client(cluster)


def run(poses_count, chunks, workers, seed=1):
    """Both sweeps and their times; returns (serial answers, distributed answers, timings)."""
    payload, poses = scene_payload(), random_poses(poses_count, seed)
    start = time.perf_counter()
    serial = serial_sweep(payload, poses, chunks)
    serial_seconds = time.perf_counter() - start
    cluster, client = start_cluster(workers)
    try:
        client.run(rebuild_scene, payload)  # warm: every worker imports proxima and rebuilds once
        start = time.perf_counter()
        spread = distributed_sweep(client, payload, poses, chunks)
        spread_seconds = time.perf_counter() - start
    finally:
        client.close()
        cluster.close()
    return serial, spread, {"serial_s": serial_seconds, "distributed_s": spread_seconds}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--poses", type=int, default=1_000_000)
    parser.add_argument("--chunks", type=int, default=16)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    serial, spread, times = run(args.poses, args.chunks, args.workers)
    same = identical(serial, spread)
    print(f"{args.poses} poses in {args.chunks} chunks: serial {times['serial_s']:.2f} s, "
          f"{args.workers} worker processes {times['distributed_s']:.2f} s")
    print(f"colliding poses: {int(serial['colliding'].sum())}; smallest clearance of a free pose: "
          f"{serial['clearance'][~serial['colliding']].min():.3g}; identical to the serial run: {same}")
    return 0 if same else 1


if __name__ == "__main__":
    # Run through the importable module so that the workers unpickle check_chunk by reference
    # and share its per-process scene cache.
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import dask_sweep

    sys.exit(dask_sweep.main())
