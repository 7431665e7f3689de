"""Broad phases against brute force (every registered structure, random boxes) and the 2D
module's queries against closed forms."""

import math

import numpy as np
import pytest

import proxima
from proxima import d2


def brute_pairs(boxes):
    lo, hi = boxes[:, :3], boxes[:, 3:]
    overlap = np.all((lo[:, None, :] <= hi[None, :, :]) & (lo[None, :, :] <= hi[:, None, :]), axis=2)
    i, j = np.nonzero(np.triu(overlap, 1))
    return sorted(zip(i.tolist(), j.tolist()))


@pytest.mark.parametrize("name", proxima.broadphase_names())
def test_every_structure_finds_the_brute_force_pairs(name, rng):
    centres = rng.uniform(0, 20, (300, 3))
    if name in ("quadtree", "region_quadtree"):
        centres[:, 2] = 0  # the 2D structures take flat boxes
    half = rng.uniform(0.1, 1.0, (300, 3))
    boxes = np.hstack([centres - half, centres + half])
    bp = proxima.BroadPhase(name)
    bp.insert(np.arange(300), boxes)
    assert bp.name == name and len(bp) == 300
    assert [tuple(p) for p in bp.pairs().tolist()] == brute_pairs(boxes)
    boxes[:, :3] += 0.5
    boxes[:, 3:] += 0.5
    bp.update(np.arange(300), boxes)
    assert [tuple(p) for p in bp.pairs(threads=2).tolist()] == brute_pairs(boxes)


def test_an_unknown_structure_is_named_in_the_error():
    with pytest.raises(proxima.Error):
        proxima.BroadPhase("no such structure")


def test_d2_circle_and_box_answers_are_analytic():
    c, b = d2.Circle(0.5), d2.Box(1, 1)
    r = d2.distance(c, (3, 0, 0), b, None)
    assert r.signed_distance == pytest.approx(1.5)
    np.testing.assert_allclose(r.normal, (-1, 0), atol=1e-6)
    turned = d2.distance(c, (3, 0, 0), b, (0, 0, math.pi / 4))
    assert turned.signed_distance == pytest.approx(3 - math.sqrt(2) - 0.5, abs=1e-5)
    m = d2.collide(c, (1.2, 0, 0), b, None)
    assert len(m) == 1 and m.points[0]["depth"] == pytest.approx(0.3, abs=1e-5)
    hit = d2.raycast(b, None, (5, 0), (-1, 0))
    assert hit.t == pytest.approx(4)
    assert d2.contains(b, (0, 0, 0.3), (0.9, 0.0)) and not d2.contains(b, None, (1.1, 0))
    toi = d2.toi(c, (-5, 0, 0), (10, 0), 0.0, b, None)
    assert toi.toi == pytest.approx(0.35, abs=2e-4)
    assert d2.cast(c, (-5, 0, 0), (10, 0), b, None).toi == pytest.approx(0.35, abs=2e-4)


def test_d2_chains_are_one_sided_and_errors_name_fields():
    ground = d2.Chain([[-5, 0], [5, 0]])  # the right side of left-to-right is below
    below = d2.distance(d2.Circle(0.5), (0, -0.3, 0), ground, None)
    assert below.signed_distance < 0
    with pytest.raises(proxima.Error) as info:
        d2.Polygon([[0, 0], [1, 0]])
    assert info.value.field.startswith("points")
    with pytest.raises(proxima.Error) as info:
        d2.distance(d2.Circle(1), (0, 0, float("nan")), d2.Circle(1), None)
    assert info.value.field.startswith("pose_a")
