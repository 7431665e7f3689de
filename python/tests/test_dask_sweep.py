"""The example's collision sweep split over a dask.distributed LocalCluster of 2 worker processes
gives the serial run's answers bit for bit, and the answers are right.

The full 1,000,000 poses (about 10 s here). Checked independently: for every 20th pose the
capsule-sphere distance from the segment-point distance in numpy (clearance can be no larger,
and equals it where the sphere is the nearest obstacle), and collision flags agree with the
sign of the clearance. The cluster is closed by the example; the test checks no worker process
outlives it. Skipped when dask.distributed is not importable.
"""

import multiprocessing
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import require

require("dask.distributed")
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import dask_sweep  # noqa: E402

POSES = 1_000_000


@pytest.fixture(scope="module")
def sweeps():
    return dask_sweep.run(POSES, chunks=8, workers=2)


def test_distributed_answers_equal_serial_ones_bit_for_bit(sweeps):
    serial, spread, _ = sweeps
    assert len(serial["clearance"]) == POSES
    assert dask_sweep.identical(serial, spread)


def test_cluster_processes_are_gone(sweeps):
    assert multiprocessing.active_children() == []


def capsule_sphere_distance(poses, radius, half_length, center, sphere_radius):
    """Distance from the capsule (axis z of each pose) to the sphere: segment-point distance minus radii."""
    q = poses[:, 3:]  # qx qy qz qw
    x, y, z, w = q.T
    axis = np.column_stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
    to_center = np.asarray(center) - poses[:, :3]
    s = np.clip(np.einsum("ij,ij->i", to_center, axis), -half_length, half_length)
    return np.linalg.norm(to_center - s[:, None] * axis, axis=1) - radius - sphere_radius


def test_clearance_matches_the_analytic_sphere_distance(sweeps):
    serial = sweeps[0]
    poses = dask_sweep.random_poses(POSES)[::20]
    sphere, pose = dask_sweep.OBSTACLES[0]
    expected = capsule_sphere_distance(poses, dask_sweep.LINK.radius, dask_sweep.LINK.half_length, pose[:3], sphere.radius)
    clearance, nearest = serial["clearance"][::20], serial["nearest"][::20]
    assert np.all(clearance <= expected + 1e-5)
    assert np.abs(clearance[nearest == 0] - expected[nearest == 0]).max() <= 1e-5
    assert (nearest == 0).sum() > len(poses) // 10


def test_collision_flags_follow_the_clearance(sweeps):
    serial = sweeps[0]
    clear = np.abs(serial["clearance"]) > 1e-4  # within it the library may call a pair touching (float build)
    assert np.array_equal(serial["colliding"][clear], serial["clearance"][clear] < 0)
    assert 0 < serial["colliding"].sum() < POSES
