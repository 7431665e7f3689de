#!/usr/bin/python3
"""A 2D and a 3D world stepped with events: one small scene built in both.

A ball (radius 0.5) drops onto a floor (its top at height 0), slides along it, lifts off, and is
then fired through a thin wall (0.1 thick, centred at x = 7) in a single step. Each world is
stepped frame by frame along the same script, and every begin / persist / end and impact event
is printed: the floor contact begins, persists and ends, and continuous detection reports the
impact the discrete step misses, at the fraction of the step where the ball's surface reaches
the wall (6.05 of the 10 travelled).

  PYTHONPATH=build/release/python /usr/bin/python3 python/examples/world_events.py
"""

import sys

import proxima
from proxima import d2

RADIUS = 0.5
WALL_X, WALL_HALF = 7.0, 0.05
# (x, height) of the ball's centre at each frame: it drops, slides, lifts off (each move
# shorter than a quarter of its size, so continuous detection leaves it alone), then one fast
# shot of 10 through the wall.
SCRIPT = [(0.0, 0.9), (0.0, 0.68), (0.0, 0.46), (0.2, 0.46), (0.4, 0.46), (0.4, 0.66), (10.4, 0.66)]


def world_2d():
    """The scene in proxima.d2: poses are (x, y, angle)."""
    w = d2.CollisionWorld()
    w.add(d2.Box(10, 0.5), (0, -0.5, 0), kind=d2.ObjectKind.Static, user_data=1)  # handle 0: floor
    w.add(d2.Box(WALL_HALF, 5), (WALL_X, 0, 0), kind=d2.ObjectKind.Static, user_data=2)  # handle 1: wall
    ball = w.add(d2.Circle(RADIUS), (*SCRIPT[0], 0), user_data=3)
    return w, ball, lambda x, height: (x, height, 0)


def world_3d():
    """The scene in proxima: the plane is x-z, poses are (px, py, pz, qx, qy, qz, qw)."""
    w = proxima.CollisionWorld()
    w.add(proxima.Box((10, 10, 0.5)), (0, 0, -0.5, 0, 0, 0, 1), kind=proxima.ObjectKind.Static, user_data=1)
    w.add(proxima.Box((WALL_HALF, 5, 5)), (WALL_X, 0, 0, 0, 0, 0, 1), kind=proxima.ObjectKind.Static, user_data=2)
    ball = w.add(proxima.Sphere(RADIUS), (SCRIPT[0][0], 0, SCRIPT[0][1], 0, 0, 0, 1), user_data=3)
    return w, ball, lambda x, height: (x, 0, height, 0, 0, 0, 1)


def run(make_world):
    """Steps the script; returns the events as (frame, kind, a, b, toi or None)."""
    w, ball, pose = make_world()
    log = []
    for frame, (x, height) in enumerate(SCRIPT):
        w.move(ball, pose(x, height))
        if isinstance(w, d2.CollisionWorld):
            w.step()
        else:
            w.step(1 / 60)
        for kind in ("begin", "persist", "end"):
            log += [(frame, kind, int(e["a"]), int(e["b"]), None) for e in w.events[kind]]
        log += [(frame, "impact", int(e["a"]), int(e["b"]), float(e["toi"])) for e in w.events["impacts"]]
    return log


def main(argv=None):
    del argv
    for name, make_world in (("2D", world_2d), ("3D", world_3d)):
        print(f"{name} world:")
        for frame, kind, a, b, toi in run(make_world):
            at = f" at {toi:.4f} of the step" if toi is not None else ""
            print(f"  frame {frame}: {kind:7} {a} - {b}{at}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
