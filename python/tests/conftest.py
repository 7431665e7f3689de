"""Shared fixtures of the Python tests: random poses and shapes of every kind, and the
`proxima query` command-line tool (PROXIMA_CLI, set by ctest) as an independent path to the
same library for agreement checks."""

import importlib
import json
import os
import subprocess

import numpy as np
import pytest

import proxima


def random_poses(rng, n, spread=3.0):
    """(n, 7) poses: positions uniform in [-spread, spread]^3, rotations uniform."""
    poses = np.empty((n, 7))
    poses[:, :3] = rng.uniform(-spread, spread, (n, 3))
    q = rng.normal(size=(n, 4))
    poses[:, 3:] = q / np.linalg.norm(q, axis=1)[:, None]
    return poses


def convex_shapes():
    """One shape of each convex kind, with its query-protocol JSON form."""
    hull_points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.6, 0.6, 0.6]]
    return [
        (proxima.Sphere(0.5), {"type": "sphere", "radius": 0.5}),
        (proxima.Capsule(0.3, 0.6), {"type": "capsule", "radius": 0.3, "half_length": 0.6}),
        (proxima.Box((0.5, 0.4, 0.3)), {"type": "box", "half_extents": [0.5, 0.4, 0.3]}),
        (proxima.Cylinder(0.4, 0.5), {"type": "cylinder", "radius": 0.4, "half_length": 0.5}),
        (proxima.Cone(0.4, 0.6), {"type": "cone", "radius": 0.4, "half_length": 0.6}),
        (proxima.Ellipsoid((0.5, 0.3, 0.4)), {"type": "ellipsoid", "radii": [0.5, 0.3, 0.4]}),
        (proxima.ConvexHull(hull_points), {"type": "convex", "points": hull_points}),
        (proxima.Segment((0, 0, -0.5), (0, 0, 0.5)), {"type": "segment", "vertices": [[0, 0, -0.5], [0, 0, 0.5]]}),
        (proxima.Triangle((0, 0, 0), (1, 0, 0), (0, 1, 0)),
         {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}),
        (proxima.Point(), {"type": "point"}),
    ]


@pytest.fixture
def rng():
    return np.random.default_rng(20261127)


def pose_json(row):
    return {"position": list(map(float, row[:3])), "rotation": list(map(float, row[3:]))}


@pytest.fixture
def query():
    """Runs requests (dicts) through `proxima query`; returns the answers (dicts)."""
    cli = os.environ.get("PROXIMA_CLI")
    if not cli or not os.path.exists(cli):
        pytest.skip("PROXIMA_CLI (the proxima tool) is not available")

    def run(requests):
        text = "\n".join(json.dumps(r) for r in requests) + "\n"
        done = subprocess.run([cli, "query", "-"], input=text, capture_output=True, text=True, check=False)
        answers = [json.loads(line) for line in done.stdout.splitlines() if line.strip()]
        assert len(answers) == len(requests), done.stderr
        return answers

    return run


def require(module):
    """The optional module (a peer or an example's dependency), imported. Without it the test
    is skipped, except where PROXIMA_PYTHON_PEERS_REQUIRED=1 (set by ctest: the set-up installs
    every one of them), where its absence fails the test instead of passing it silently."""
    if os.environ.get("PROXIMA_PYTHON_PEERS_REQUIRED") == "1":
        return importlib.import_module(module)
    return pytest.importorskip(module)
