"""The collision world from Python: events as structured arrays and through a listener,
exceptions raised by callbacks, scene queries against brute force, batched queries equal to
single ones, rejected calls that leave the state unchanged, snapshots and pickling."""

import pickle

import numpy as np
import pytest

import proxima


def stacked_world():
    w = proxima.CollisionWorld()
    floor = w.add(proxima.Box((10, 10, 0.5)), (0, 0, -0.5, 0, 0, 0, 1), kind=proxima.ObjectKind.Static, user_data=100)
    balls = [w.add(proxima.Sphere(0.5), (2.0 * i, 0, 0.45, 0, 0, 0, 1), user_data=i) for i in range(4)]
    far = w.add(proxima.Sphere(0.5), (0, 5, 5, 0, 0, 0, 1), user_data=9)
    return w, floor, balls, far


class Recorder:
    def __init__(self):
        self.calls = []

    def on_contact_begin(self, event):
        self.calls.append(("begin", event.a, event.b, event.user_data_a, event.user_data_b))

    def on_contact_end(self, event):
        self.calls.append(("end", event.a, event.b))

    def on_sensor_enter(self, event):
        self.calls.append(("enter", event.sensor, event.other))


def test_step_reports_each_resting_ball_once_in_arrays_and_callbacks():
    w, floor, balls, far = stacked_world()
    rec = Recorder()
    w.set_listener(rec)
    w.step(1 / 60)
    begin = w.events["begin"]
    assert begin.dtype == proxima.CONTACT_EVENT_DTYPE
    assert sorted(zip(begin["a"], begin["b"])) == sorted((min(floor, b), max(floor, b)) for b in balls)
    assert sorted(c[1:3] for c in rec.calls) == sorted(zip(begin["a"].tolist(), begin["b"].tolist()))
    contacts = w.contacts()
    assert len(contacts) == 4 and np.allclose(contacts["depth"], 0.05, atol=1e-5)
    w.move(balls[0], (0, 0, 3, 0, 0, 0, 1))
    w.step(1 / 60)
    end = w.events["end"]
    assert list(zip(end["a"], end["b"])) == [(min(floor, balls[0]), max(floor, balls[0]))]
    assert ("end", min(floor, balls[0]), max(floor, balls[0])) in rec.calls


def test_an_exception_in_a_callback_is_raised_from_step():
    w, *_ = stacked_world()

    class Failing:
        def on_contact_begin(self, event):
            raise KeyError("from the listener")

    w.set_listener(Failing())
    with pytest.raises(KeyError):
        w.step(1 / 60)
    assert w.step_count == 1  # the step itself finished
    w.set_listener(None)
    w.step(1 / 60)


def test_sensors_report_entries():
    w, floor, balls, far = stacked_world()
    sensor = w.add(proxima.Box((1, 1, 1)), (0, 0, 0, 0, 0, 0, 1), sensor=True)
    w.step(1 / 60)
    enter = w.events["sensor_enter"]
    assert set(enter["other"].tolist()) == {floor, balls[0]}
    assert set(enter["sensor"].tolist()) == {sensor}


def test_raycasts_match_a_brute_force_over_the_objects(rng):
    w, floor, balls, far = stacked_world()
    handles = [floor, *balls, far]
    rays = np.hstack([rng.uniform(-3, 9, (300, 3)) + [0, 0, 6], rng.normal(size=(300, 3))])
    rows = w.raycast_batch(rays, 20.0)
    for i, ray in enumerate(rays):
        best = None
        for h in handles:
            hit = w.object(h).geometry.raycast(ray[:3], ray[3:], 20.0, pose=w.pose(h))
            if hit is not None and (best is None or hit.t < best[0]):
                best = (hit.t, h)
        single = w.raycast(ray[:3], ray[3:], 20.0)
        assert bool(rows["hit"][i]) == (best is not None) == bool(single)
        if best is not None:
            assert rows["t"][i] == pytest.approx(best[0], abs=1e-5)
            assert rows["object"][i] == single[0].object


def test_filters_hide_objects_from_pairs_and_queries():
    w = proxima.CollisionWorld()
    a = w.add(proxima.Sphere(1), None, filter=proxima.CollisionFilter(layer=1, mask=1))
    b = w.add(proxima.Sphere(1), (0.5, 0, 0, 0, 0, 0, 1), filter=proxima.CollisionFilter(layer=2, mask=2))
    w.step(1 / 60)
    assert len(w.events["begin"]) == 0
    assert w.overlap_point((0.2, 0, 0), mask=2) == [b]
    w.set_filter(b, proxima.CollisionFilter(layer=1, mask=1))
    w.step(1 / 60)
    assert len(w.events["begin"]) == 1
    w.set_pair_excluded(a, b)
    w.step(1 / 60)
    assert len(w.events["end"]) == 1


def test_a_rejected_call_leaves_the_world_unchanged():
    w, floor, balls, far = stacked_world()
    w.step(1 / 60)
    before = w.state_hash()
    with pytest.raises(proxima.Error) as info:
        w.move_batch(np.array(balls[:2], dtype=np.uint64), np.array([[0, 0, 1, 0, 0, 0, 1], [0, 0, np.inf, 0, 0, 0, 1]]))
    assert info.value.field.startswith("poses[1]")
    with pytest.raises(proxima.Error):
        w.add(proxima.HalfSpace((0, 0, 1), 0), None)  # a half-space must be static
    with pytest.raises(proxima.Error):
        w.remove(123456789)
    assert w.state_hash() == before and len(w) == 6


def test_snapshots_and_pickles_rebuild_an_equal_world():
    w, floor, balls, far = stacked_world()
    w.step(1 / 60)
    copy = pickle.loads(pickle.dumps(w))
    assert copy.state_hash() == w.state_hash()
    again = proxima.CollisionWorld.load(w.save())
    for world in (w, copy, again):
        world.move(balls[1], (2, 0, 2, 0, 0, 0, 1))
        world.step(1 / 60)
    assert copy.state_hash() == w.state_hash() == again.state_hash()
    with pytest.raises(proxima.Error) as info:
        proxima.CollisionWorld.load(b"not a snapshot")
    assert info.value.field.startswith("snapshot")


def test_attached_objects_follow_their_parent():
    w = proxima.CollisionWorld()
    body = w.add(proxima.Box((1, 1, 1)), (0, 0, 0, 0, 0, 0, 1))
    hand = w.add(proxima.Sphere(0.2), parent=body, local_pose=(0, 0, 2, 0, 0, 0, 1))
    w.move(body, (5, 0, 0, 0, 0, 0, 1))
    w.step(1 / 60)
    np.testing.assert_allclose(w.pose(hand).position, (5, 0, 2), atol=1e-6)
    assert w.object(hand).parent == body


def test_closest_point_batch_equals_single_queries(rng):
    w, *_ = stacked_world()
    points = rng.uniform(-2, 8, (200, 3))
    rows = w.closest_point_batch(points, 3.0)
    for i in range(0, 200, 7):
        single = w.closest_point(points[i], 3.0)
        assert bool(rows["found"][i]) == (single is not None)
        if single is not None:
            assert rows["signed_distance"][i] == pytest.approx(single.signed_distance)
