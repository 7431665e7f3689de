"""Reference counting: 100,000 calls of each kind (single queries, batched queries, shapes
made and dropped, errors raised and caught, world steps with events) leave the resident set
where it was after a warm-up: no leak per call."""

import resource

import numpy as np

import proxima


def rss_kib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def growth_kib(action, calls=100_000, warmup=5_000):
    for _ in range(warmup):
        action()
    before = rss_kib()
    for _ in range(calls):
        action()
    return rss_kib() - before


def test_single_queries_do_not_leak():
    a, b = proxima.Box((0.5, 0.5, 0.5)), proxima.Sphere(0.5)
    pose = proxima.Transform((0.7, 0, 0))
    # a leak of one 24-byte object per call would show as > 2,000 KiB here
    assert growth_kib(lambda: proxima.distance(a, pose, b, None).normal) < 1024
    assert growth_kib(lambda: proxima.collide(a, None, b, pose).points) < 1024


def test_shapes_and_errors_do_not_leak():
    assert growth_kib(lambda: proxima.Capsule(0.5, 1.0).aabb()) < 1024

    def failing():
        try:
            proxima.Sphere(-1.0)
        except proxima.Error:
            pass

    assert growth_kib(failing) < 1024


def test_batched_calls_do_not_leak():
    a, b = proxima.Box((0.5, 0.5, 0.5)), proxima.Sphere(0.5)
    poses = np.tile([0.7, 0, 0, 0, 0, 0, 1.0], (16, 1))
    out = np.zeros(16, dtype=proxima.DISTANCE_DTYPE)
    assert growth_kib(lambda: proxima.distance_batch(a, poses, b, None, out=out, threads=1)) < 1024
    assert growth_kib(lambda: proxima.intersect_batch(a, poses, b, None, threads=1)) < 1024


def test_world_steps_and_events_do_not_leak():
    w = proxima.CollisionWorld()
    w.add(proxima.Box((5, 5, 0.5)), (0, 0, -0.5, 0, 0, 0, 1), kind=proxima.ObjectKind.Static)
    ball = w.add(proxima.Sphere(0.5), (0, 0, 0.4, 0, 0, 0, 1))
    heights = [0.4, 3.0]
    state = {"i": 0}

    def step():
        state["i"] += 1
        w.move(ball, (0, 0, heights[state["i"] % 2], 0, 0, 0, 1))
        w.step(1 / 60)
        return w.events["begin"], w.contacts()

    assert growth_kib(step, calls=30_000, warmup=2_000) < 1024
