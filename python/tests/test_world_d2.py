"""The 2D collision world from Python (proxima.d2.CollisionWorld): events against analytic
answers (two circles at known distances, a sensor, a fast circle through a thin wall), the
listener and its exceptions, scene queries against the pair queries over every object,
agreement with `proxima world --2d` (an independent path to the library), pickles that step
on exactly like the original, and errors that name their field and change nothing."""

import json
import math
import os
import pickle
import subprocess

import numpy as np
import pytest

import proxima
from proxima import d2

REAL = np.float64 if proxima.DOUBLE_PRECISION else np.float32


def pair_rows(rows):
    return [(int(r["a"]), int(r["b"])) for r in rows]


def two_circles(distance, **settings):
    w = d2.CollisionWorld(**settings)
    a = w.add(d2.Circle(1.0), (0, 0, 0), user_data=11)
    b = w.add(d2.Circle(1.0), (distance, 0, 0), user_data=22)
    return w, a, b


def test_two_circles_begin_persist_and_end_at_their_analytic_distance():
    w, a, b = two_circles(3.0)
    w.step()
    assert all(len(v) == 0 for v in w.events.values())
    w.move(b, (1.9, 0, 0))  # 0.1 overlap
    w.step()
    assert pair_rows(w.events["begin"]) == [(a, b)]
    assert (w.events["begin"]["user_data_a"][0], w.events["begin"]["user_data_b"][0]) == (11, 22)
    m = w.manifolds()
    assert len(m) == 1
    assert m["depth"][0] == pytest.approx(0.1, abs=1e-5)
    np.testing.assert_allclose(m["normal"][0], [1, 0], atol=1e-6)
    np.testing.assert_allclose(m["point_a"][0], [1, 0], atol=1e-5)
    np.testing.assert_allclose(m["point_b"][0], [0.9, 0], atol=1e-5)
    w.step()
    assert pair_rows(w.events["persist"]) == [(a, b)] and len(w.events["begin"]) == 0
    w.move(b, (2.05, 0, 0))
    w.step()
    assert pair_rows(w.events["end"]) == [(a, b)] and len(w.manifolds()) == 0


def test_the_contact_distance_reports_a_gap_as_negative_depth():
    w, a, b = two_circles(2.1, contact_distance=0.2)
    w.step()
    assert pair_rows(w.events["begin"]) == [(a, b)]
    assert w.manifolds()["depth"][0] == pytest.approx(-0.1, abs=1e-5)


def test_a_sensor_reports_enter_and_exit_and_no_contact():
    w = d2.CollisionWorld()
    zone = w.add(d2.Box(1, 1), (0, 0, 0), kind=d2.ObjectKind.Static, sensor=True, user_data=5)
    ball = w.add(d2.Circle(0.25), (3, 0, 0))
    w.step()
    assert len(w.events["sensor_enter"]) == 0
    w.move(ball, (1.2, 0, 0))  # 0.05 inside the box's edge
    w.step()
    rows = w.events["sensor_enter"]
    assert [(int(r["sensor"]), int(r["other"])) for r in rows] == [(zone, ball)]
    assert rows["user_data_sensor"][0] == 5
    assert len(w.events["begin"]) == 0 and len(w.manifolds()) == 0
    w.move(ball, (1.3, 0, 0))  # 0.05 outside
    w.step()
    assert [(int(r["sensor"]), int(r["other"])) for r in w.events["sensor_exit"]] == [(zone, ball)]


def test_a_fast_circle_through_a_thin_wall_reports_its_impact_at_the_analytic_time():
    w = d2.CollisionWorld()
    wall = w.add(d2.Segment((0, -5), (0, 5)), (5, 0, 0), kind=d2.ObjectKind.Static)
    bullet = w.add(d2.Circle(0.1), (0, 0, 0), ccd=d2.CcdMode.Bullet, user_data=3)
    w.step()
    w.move(bullet, (10, 0, 0))
    w.step()
    impacts = w.events["impacts"]
    assert len(impacts) == 1 and (int(impacts["a"][0]), int(impacts["b"][0])) == (bullet, wall)
    # Its surface reaches x = 5 when its centre is at 4.9: 4.9 of the 10 travelled.
    assert impacts["toi"][0] == pytest.approx(0.49, abs=1e-3)
    np.testing.assert_allclose(impacts["point"][0], [5, 0], atol=1e-2)
    np.testing.assert_allclose(impacts["normal"][0], [1, 0], atol=1e-3)
    assert impacts["part_b"][0] == -1 and impacts["user_data_a"][0] == 3
    assert len(w.events["begin"]) == 0  # the discrete step saw nothing


class Recorder:
    def __init__(self):
        self.calls = []

    def on_contact_begin(self, event):
        self.calls.append(("begin", event.a, event.b))

    def on_contact_end(self, event):
        self.calls.append(("end", event.a, event.b))

    def on_impact(self, event):
        self.calls.append(("impact", event.a, event.b, event.toi))


def test_the_listener_hears_the_arrays_in_order_and_its_exceptions_come_from_step():
    w, a, b = two_circles(1.5)
    rec = Recorder()
    w.set_listener(rec)
    w.step()
    assert rec.calls == [("begin", a, b)]

    class Failing:
        def on_contact_end(self, event):
            raise KeyError("from the listener")

    w.set_listener(Failing())
    w.move(b, (5, 0, 0))
    with pytest.raises(KeyError):
        w.step()
    assert pair_rows(w.events["end"]) == [(a, b)]  # the step itself finished
    w.set_listener(None)
    w.step()


def random_world(rng, n=30, **settings):
    """A floor chain and n objects of every convex kind; returns (world, shapes, handles)."""
    w = d2.CollisionWorld(**settings)
    shapes = [d2.Chain([[20, 0], [0, 0.5], [-20, 0]])]
    handles = [w.add(shapes[0], kind=d2.ObjectKind.Static)]
    for i in range(n):
        kind = i % 5
        if kind == 0:
            s = d2.Circle(rng.uniform(0.2, 0.8))
        elif kind == 1:
            s = d2.Box(rng.uniform(0.2, 0.8), rng.uniform(0.2, 0.8))
        elif kind == 2:
            s = d2.Capsule((-0.5, 0), (0.5, 0), 0.2)
        elif kind == 3:
            s = d2.Polygon(rng.uniform(-0.7, 0.7, (6, 2)), 0.02)
        else:
            s = d2.Segment((-0.6, 0), (0.6, 0.1))
        pose = (rng.uniform(-8, 8), rng.uniform(-0.5, 5), rng.uniform(-3, 3))
        shapes.append(s)
        handles.append(w.add(s, pose, sensor=(i % 11 == 5), ccd=d2.CcdMode.Bullet, user_data=i))
    return w, shapes, handles


def moves(rng, handles, frames):
    """Per frame, a list of (handle, pose): each object drifts, one jumps far (a bullet)."""
    out = []
    for _ in range(frames):
        frame = []
        for h in handles[1:]:
            frame.append((h, (rng.uniform(-8, 8), rng.uniform(-0.5, 5), rng.uniform(-3, 3))))
        out.append(frame)
    return out


def snapshot(w):
    return (w.events, w.manifolds(), w.state_hash())


def assert_same(x, y):
    for key in x[0]:
        assert np.array_equal(x[0][key], y[0][key]), key
    assert np.array_equal(x[1], y[1])
    assert x[2] == y[2]


def test_a_pickled_world_steps_on_exactly_like_the_original(rng):
    w, _, handles = random_world(rng)
    w.set_pair_excluded(handles[1], handles[2])
    plan = moves(rng, handles, 12)
    for h, pose in plan[0]:
        w.move(h, pose)
    w.step()
    for h, pose in plan[1]:
        w.move(h, pose)  # moved, not stepped: the motion is in the snapshot
    copy = pickle.loads(pickle.dumps(w))
    assert copy.state_hash() == w.state_hash() and len(copy) == len(w)
    assert d2.CollisionWorld.load(w.save()).state_hash() == w.state_hash()
    for frame in plan[2:]:
        w.step()
        copy.step(threads=2)
        assert_same(snapshot(w), snapshot(copy))
        for h, pose in frame:
            w.move(h, pose)
            copy.move(h, pose)


def test_queries_equal_the_pair_queries_over_every_object(rng):
    w, shapes, handles = random_world(rng)
    for _ in range(40):
        origin = rng.uniform(-8, 8, 2)
        direction = rng.normal(size=2)
        hit = w.raycast(origin, direction, 10.0)
        best = None
        for s, h in zip(shapes, handles):
            r = d2.raycast(s, w.pose(h), origin, direction, 10.0)
            if r is not None and (best is None or r.t < best[0]):
                best = (r.t, h)
        assert (hit is None) == (best is None)
        if hit is not None:
            assert hit.t == pytest.approx(best[0], abs=1e-5)
        probe = d2.Circle(rng.uniform(0.2, 2))
        at = (rng.uniform(-8, 8), rng.uniform(-1, 5), 0)
        expected = [h for s, h in zip(shapes, handles) if d2.intersect(probe, at, s, w.pose(h))]
        assert w.overlap(probe, at) == sorted(expected)


def test_exclusions_silence_a_touching_pair_until_allowed_again():
    w, a, b = two_circles(1.5)
    w.step()
    w.set_pair_excluded(a, b)
    w.step()
    assert pair_rows(w.events["end"]) == [(a, b)]
    w.set_pair_excluded(a, b, False)
    w.step()
    assert pair_rows(w.events["begin"]) == [(a, b)]


def field_of(call):
    with pytest.raises(proxima.Error) as e:
        call()
    return e.value.field


def test_errors_name_their_field_and_change_nothing():
    w, a, b = two_circles(1.5)
    before = w.state_hash()
    assert field_of(lambda: w.add(d2.Circle(1), (math.nan, 0, 0))).startswith("pose")
    assert field_of(lambda: w.add(d2.Chain([[0, 0], [1, 0]]))) == "desc.kind"
    assert field_of(lambda: w.add(proxima.Sphere(1))) == "shape"
    w.remove(b)
    after_remove = w.state_hash()
    assert field_of(lambda: w.move(b, (0, 0, 0))) == "handle"
    assert field_of(lambda: w.set_pair_excluded(a, a)) == "b"
    assert field_of(lambda: w.raycast((0, 0), (0, 0))) == "direction"
    assert w.state_hash() == after_remove != before
    assert field_of(lambda: d2.CollisionWorld(contact_distance=-1)).startswith("settings")
    data = w.save()
    assert field_of(lambda: d2.CollisionWorld.load(b"not a snapshot")) == "snapshot"
    for n in range(0, len(data), 7):
        assert field_of(lambda: d2.CollisionWorld.load(data[:n])).startswith("snapshot")


# ---- agreement with `proxima world --2d` ---------------------------------------------------


def shape_json(kind, rng):
    if kind == 0:
        r = float(rng.uniform(0.2, 0.8))
        return d2.Circle(r), {"type": "circle", "radius": r}
    if kind == 1:
        h = [float(x) for x in rng.uniform(0.2, 0.8, 2)]
        return d2.Box(*h), {"type": "box2d", "half_extents": h}
    if kind == 2:
        return d2.Capsule((-0.5, 0), (0.5, 0), 0.2), {"type": "capsule2d", "vertices": [[-0.5, 0], [0.5, 0]],
                                                     "radius": 0.2}
    pts = [[float(x) for x in p] for p in rng.uniform(-0.7, 0.7, (6, 2))]
    return d2.Polygon(pts), {"type": "polygon", "points": pts}


def run_cli(requests):
    cli = os.environ.get("PROXIMA_CLI")
    if not cli or not os.path.exists(cli):
        pytest.skip("PROXIMA_CLI (the proxima tool) is not available")
    text = "\n".join(json.dumps(r) for r in requests) + "\n"
    done = subprocess.run([cli, "world", "--2d", "-"], input=text, capture_output=True, text=True, check=False)
    answers = [json.loads(line) for line in done.stdout.splitlines() if line.strip()]
    assert len(answers) == len(requests), done.stderr
    return answers


def as_real(values):
    return np.asarray(values, dtype=np.float64).astype(REAL)


def test_the_world_agrees_with_the_command_line_tool(rng):
    w = d2.CollisionWorld()
    floor = [[20, 0], [0, 0.5], [-20, 0]]
    requests = [{"op": "add", "geometry": {"type": "chain", "points": floor}, "kind": "static"}]
    w.add(d2.Chain(floor), kind=d2.ObjectKind.Static)
    for i in range(16):
        shape, js = shape_json(i % 4, rng)
        x, y, angle = (float(v) for v in (rng.uniform(-6, 6), rng.uniform(-0.5, 4), rng.uniform(-3, 3)))
        w.add(shape, (x, y, angle), ccd=d2.CcdMode.Bullet)
        requests.append({"op": "add", "geometry": js, "pose": {"position": [x, y], "angle": angle}, "ccd": "bullet"})
    steps = []
    for frame in range(8):
        w.step()
        steps.append((len(requests), dict(w.events), w.manifolds()))
        requests.append({"op": "step", "contacts": True})
        for h in range(1, 17):
            x, y, angle = (float(v) for v in (rng.uniform(-6, 6), rng.uniform(-0.5, 4), rng.uniform(-3, 3)))
            w.move(h, (x, y, angle))
            requests.append({"op": "move", "object": h, "pose": {"position": [x, y], "angle": angle}})
    for i, r in enumerate(requests):
        r["id"] = i
    answers = run_cli(requests)
    for at, events, manifolds in steps:
        answer = answers[at]
        for key in ("begin", "persist", "end"):
            assert [tuple(p) for p in answer[key]] == pair_rows(events[key]), key
        impacts = events["impacts"]
        assert [(i["a"], i["b"]) for i in answer["impacts"]] == pair_rows(impacts)
        for mine, theirs in zip(impacts, answer["impacts"]):
            assert REAL(mine["toi"]) == as_real(theirs["toi"])
            assert np.array_equal(mine["point"].astype(REAL), as_real(theirs["point"]))
        points = [(c["a"], c["b"], p) for c in answer["contacts"] for p in c["points"]]
        assert len(points) == len(manifolds)
        for row, (a, b, p) in zip(manifolds, points):
            assert (int(row["a"]), int(row["b"]), int(row["feature_id"])) == (a, b, p["feature_id"])
            assert np.array_equal(row["point_a"].astype(REAL), as_real(p["point_a"]))
            assert REAL(row["depth"]) == as_real(p["depth"])
