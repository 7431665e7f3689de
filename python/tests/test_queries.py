"""Pair queries from Python against two independent answers: closed forms (sphere pairs, a
sphere falling onto a box) and the `proxima query` tool on the same seeded inputs (the
protocol's JSON path reaches the library without the bindings)."""

import math

import numpy as np
import pytest

import proxima
from conftest import convex_shapes, pose_json, random_poses


def test_sphere_pair_distance_is_the_centre_gap_minus_the_radii(rng):
    a, b = proxima.Sphere(0.5), proxima.Sphere(0.25)
    for row in random_poses(rng, 200):
        pa = proxima.Transform(row[:3], row[3:])
        r = proxima.distance(a, pa, b, None)
        gap = np.linalg.norm(row[:3]) - 0.75
        assert r.signed_distance == pytest.approx(gap, abs=1e-5)
        assert proxima.intersect(a, pa, b, None) == (gap <= 0)


def test_box_resting_on_a_box_has_a_four_point_manifold():
    floor, box = proxima.Box((5, 5, 0.5)), proxima.Box((0.5, 0.5, 0.5))
    m = proxima.collide(floor, (0, 0, -0.5, 0, 0, 0, 1), box, (0, 0, 0.49, 0, 0, 0, 1))
    assert len(m) == 4
    np.testing.assert_allclose(m.normal, (0, 0, 1), atol=1e-6)
    for p in m.points:
        assert p.depth == pytest.approx(0.01, abs=1e-5)


def test_toi_and_cast_of_a_sphere_reaching_a_box_are_analytic():
    s, b = proxima.Sphere(0.5), proxima.Box((1, 1, 1))
    start, end = proxima.Transform((-5, 0, 0)), proxima.Transform((5, 0, 0))
    toi = proxima.toi(s, (start, end), b, None)
    assert toi.status == proxima.CcdStatus.Hit and toi.hit
    assert toi.toi == pytest.approx(3.5 / 10, abs=2e-4)
    assert toi.t_lower <= 0.35 <= toi.t_upper + 1e-6
    cast = proxima.cast(s, start, (10, 0, 0), b, None)
    assert cast.t == pytest.approx(0.35, abs=2e-4)
    np.testing.assert_allclose(cast.normal, (1, 0, 0), atol=1e-5)
    miss = proxima.cast(s, start, (0, 10, 0), b, None)
    assert miss.status == proxima.CcdStatus.Separated and not miss.hit
    step = proxima.safe_step(s, start, (10, 0, 0), (0, 0, 0), b, None)
    assert 0 < step <= 0.35 + 1e-6


def test_motion_from_velocity_matches_its_end_pose():
    m = proxima.Motion.from_velocity(proxima.Transform((1, 0, 0)), (2, 0, 0), (0, 0, math.pi), 0.5)
    np.testing.assert_allclose(m.end.position, (2, 0, 0), atol=1e-6)
    np.testing.assert_allclose(abs(m.end.rotation[2]), math.sin(math.pi / 4), atol=1e-6)


def test_distance_and_collide_agree_with_the_query_tool(rng, query):
    shapes = convex_shapes()
    requests, cases = [], []
    for i in range(120):
        (sa, ja), (sb, jb) = shapes[i % len(shapes)], shapes[(i * 7 + 3) % len(shapes)]
        pa, pb = random_poses(rng, 2, spread=1.2)
        cases.append((sa, pa, sb, pb))
        requests.append({"id": i, "op": "distance", "a": {"shape": ja, "pose": pose_json(pa)},
                         "b": {"shape": jb, "pose": pose_json(pb)}})
    answers = query(requests)
    for (sa, pa, sb, pb), answer in zip(cases, answers):
        r = proxima.distance(sa, pa, sb, pb)
        assert "distance" in answer, answer
        assert r.signed_distance == pytest.approx(answer["distance"], abs=1e-6)
        assert r.status.name.lower() == answer["status"]
        np.testing.assert_allclose(r.point_a, answer["point_a"], atol=1e-5)


def test_a_bad_pose_is_refused_with_its_field_and_nothing_is_computed():
    with pytest.raises(proxima.Error) as info:
        proxima.distance(proxima.Sphere(1), (0, 0, 0, 0, 0, 0, 3), proxima.Sphere(1), None)
    assert info.value.field == "pose_a.rotation"
    with pytest.raises(proxima.Error) as info:
        proxima.collide(proxima.Sphere(1), None, proxima.Sphere(1), None, max_contacts=9)
    assert info.value.field == "max_contacts"
    with pytest.raises(proxima.Error) as info:
        proxima.distance("sphere", None, proxima.Sphere(1), None)
    assert info.value.field == "a"
