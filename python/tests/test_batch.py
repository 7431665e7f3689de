"""Batched queries on numpy arrays: each row equals the single call's answer, for any thread
count; float32 and strided inputs are read in place; `out=` is written in place (the same
memory comes back); bad rows raise an error naming the row and leave `out` untouched."""

import numpy as np
import pytest

import proxima
from conftest import random_poses


@pytest.fixture
def pair(rng):
    return proxima.Box((0.5, 0.4, 0.3)), proxima.Capsule(0.3, 0.5), random_poses(rng, 3000)


def test_distance_rows_equal_the_single_queries(pair):
    a, b, poses = pair
    rows = proxima.distance_batch(a, poses, b, None, threads=1)
    assert rows.dtype == proxima.DISTANCE_DTYPE and rows.shape == (3000,)
    for i in range(0, 3000, 37):
        r = proxima.distance(a, poses[i], b, None)
        assert rows["signed_distance"][i] == r.signed_distance
        np.testing.assert_array_equal(rows["normal"][i], r.normal)
        assert rows["status"][i] == int(r.status)


def test_every_thread_count_gives_identical_answers(pair):
    a, b, poses = pair
    serial = proxima.distance_batch(a, poses, b, poses[::-1].copy(), threads=1)
    for threads in (0, 2, 3):
        np.testing.assert_array_equal(proxima.distance_batch(a, poses, b, poses[::-1].copy(), threads=threads), serial)
    inter = proxima.intersect_batch(a, poses, b, None, threads=2)
    assert inter.dtype == np.bool_ and inter.sum() > 0


def test_intersect_agrees_with_the_distance_sign(pair):
    a, b, poses = pair
    inter = proxima.intersect_batch(a, poses, b, None)
    d = proxima.distance_batch(a, poses, b, None)["signed_distance"]
    clear = np.abs(d) > 1e-4  # rows at the tolerance may go either way
    np.testing.assert_array_equal(inter[clear], d[clear] < 0)


def test_out_is_written_in_place_and_returned(pair):
    a, b, poses = pair
    out = np.zeros(3000, dtype=proxima.DISTANCE_DTYPE)
    address = out.__array_interface__["data"][0]
    result = proxima.distance_batch(a, poses, b, None, out=out)
    assert result is out or np.shares_memory(result, out)
    assert out.__array_interface__["data"][0] == address
    assert np.all(out["signed_distance"] != 0)
    with pytest.raises(proxima.Error) as info:
        proxima.distance_batch(a, poses, b, None, out=np.zeros(10, dtype=proxima.DISTANCE_DTYPE))
    assert info.value.field == "out"


def test_float32_and_strided_inputs_give_the_same_rows(pair):
    a, b, poses = pair
    p32 = poses.astype(np.float32)
    wide = np.zeros((3000, 10))
    wide[:, 2:9] = p32  # a strided view: every row 10 numbers apart
    view = wide[:, 2:9]
    assert not view.flags["C_CONTIGUOUS"]
    np.testing.assert_array_equal(proxima.distance_batch(a, p32, b, None), proxima.distance_batch(a, view, b, None))


def test_a_bad_row_names_itself_and_writes_nothing(pair):
    a, b, poses = pair
    bad = poses.copy()
    bad[1234, 0] = np.nan
    out = np.zeros(3000, dtype=proxima.DISTANCE_DTYPE)
    with pytest.raises(proxima.Error) as info:
        proxima.distance_batch(a, bad, b, None, out=out)
    assert info.value.field.startswith("poses_a[1234]")
    assert np.all(out["signed_distance"] == 0)
    with pytest.raises(proxima.Error) as info:
        proxima.distance_batch(a, poses[:10], b, poses[:9])
    assert info.value.field == "poses_b"


def test_raycast_batch_against_a_sphere_is_analytic(rng):
    s = proxima.Sphere(1.0)
    origins = rng.uniform(-5, 5, (2000, 3))
    targets = rng.uniform(-0.5, 0.5, (2000, 3))
    rays = np.hstack([origins, targets - origins])
    rows = proxima.raycast_batch(s, (1, 0, 0, 0, 0, 0, 1), rays, max_t=10.0)
    # the exact first root of |o + t d - c|^2 = 1
    o, d, c = origins, targets - origins, np.array([1.0, 0, 0])
    oc = o - c
    qa, qb, qc = (d * d).sum(1), 2 * (oc * d).sum(1), (oc * oc).sum(1) - 1
    disc = qb * qb - 4 * qa * qc
    hit = disc >= 0
    t = (-qb - np.sqrt(np.where(hit, disc, 0))) / (2 * qa)
    hit &= (t >= 0) & (t <= 10)
    inside = qc <= 0
    sure = ~inside & (np.abs(disc) > 1e-3)
    np.testing.assert_array_equal(rows["hit"][sure].astype(bool), hit[sure])
    both = sure & hit
    np.testing.assert_allclose(rows["t"][both], t[both], atol=1e-4)
    assert np.all(rows["part"] == -1)


def test_closest_point_and_contains_batches_match_single_calls(rng):
    box = proxima.Box((1, 2, 3))
    pose = proxima.Transform((0.5, 0, 0), (0, 0, np.sin(0.2), np.cos(0.2)))
    points = rng.uniform(-4, 4, (500, 3))
    rows = proxima.closest_point_batch(box, pose, points)
    inside = proxima.contains_batch(box, pose, points)
    for i in range(0, 500, 11):
        sp = box.closest_point(points[i], pose=pose)
        assert rows["signed_distance"][i] == sp.signed_distance
        assert inside[i] == box.contains(points[i], pose=pose)
    np.testing.assert_array_equal(inside, rows["signed_distance"] <= 0)


def test_a_mesh_raycast_batch_reports_its_triangles():
    mesh = proxima.TriangleMesh([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], [[0, 1, 2], [0, 2, 3]])
    rays = np.array([[0.5, -0.5, 1, 0, 0, -1], [-0.5, 0.5, 1, 0, 0, -1], [3, 3, 1, 0, 0, -1]], float)
    rows = proxima.raycast_batch(mesh, None, rays)
    assert list(rows["hit"]) == [1, 1, 0]
    assert list(rows["part"]) == [0, 1, -1]
    np.testing.assert_allclose(rows["t"][:2], 1.0)
