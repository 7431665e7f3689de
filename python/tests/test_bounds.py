"""Bounding-volume fitting from numpy point clouds, against numpy's own answers: every fitted
volume contains every point, the box equals the coordinate extremes, the minimal ball of
points on a sphere is that sphere, and unknown methods or empty clouds raise naming the field."""

import numpy as np
import pytest

import proxima


@pytest.fixture
def cloud(rng):
    return rng.normal(size=(400, 3)) * [3.0, 1.0, 0.5] + [1, 2, 3]


def test_the_box_is_the_coordinate_extremes(cloud):
    box = proxima.fit_aabb(cloud)
    np.testing.assert_allclose(box.min, cloud.min(0), rtol=1e-6)
    np.testing.assert_allclose(box.max, cloud.max(0), rtol=1e-6)


def test_the_minimal_ball_of_points_on_a_sphere_is_that_sphere(rng):
    d = rng.normal(size=(300, 3))
    points = 2.5 * d / np.linalg.norm(d, axis=1)[:, None] + [4, -1, 0.5]
    ball = proxima.fit_sphere(points)
    assert ball.radius == pytest.approx(2.5, rel=1e-4)
    np.testing.assert_allclose(ball.center, (4, -1, 0.5), atol=1e-3)
    assert proxima.fit_sphere(points, method="ritter").radius >= ball.radius * (1 - 1e-6)


@pytest.mark.parametrize("method", ["min_volume", "pca", "dito14", "dito26"])
def test_every_box_fit_contains_the_points(cloud, method):
    obb = proxima.fit_obb(cloud, method=method)
    local = (cloud - obb.center) @ obb.axes.T
    assert np.all(np.abs(local) <= obb.half_extents + 1e-4)


def test_capsule_and_hull_contain_the_points(cloud):
    cap = proxima.fit_capsule(cloud)
    seg = cap.p1 - cap.p0
    t = np.clip(((cloud - cap.p0) @ seg) / max(seg @ seg, 1e-30), 0, 1)
    dist = np.linalg.norm(cloud - (cap.p0 + t[:, None] * seg), axis=1)
    assert np.all(dist <= cap.radius + 1e-4)
    hull = proxima.fit_hull(cloud)
    assert isinstance(hull, proxima.ConvexHull)
    assert all(hull.contains(p) for p in cloud[::20])


def test_bad_clouds_and_methods_name_the_field():
    with pytest.raises(proxima.Error) as info:
        proxima.fit_aabb(np.zeros((0, 3)))
    assert info.value.field.startswith("points")
    with pytest.raises(proxima.Error) as info:
        proxima.fit_sphere(np.zeros((4, 3)), method="best")
    assert info.value.field == "method"
