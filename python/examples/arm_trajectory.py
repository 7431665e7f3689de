#!/usr/bin/python3
"""Motion-planning check of a robot-arm-like chain of capsules along a trajectory of joint angles.

The arm: a base joint turning about z (yaw) and three joints turning about their local y
(pitch), each followed by a capsule link along its local z. For every configuration of the
trajectory (a straight line in joint space, 2,000 steps by default), forward kinematics in numpy
gives the pose of each link; then, per link and obstacle, one intersect_batch and one
distance_batch call over all configurations at once. Printed: the first colliding configuration
(which link against which obstacle) and the smallest clearance before it.

  PYTHONPATH=build/release/python /usr/bin/python3 python/examples/arm_trajectory.py [--steps 2000]
"""

import argparse
import sys

import numpy as np

import proxima

LINK_LENGTHS = (0.55, 0.45, 0.35)
LINK_RADII = (0.07, 0.06, 0.05)
OBSTACLES = (  # name, shape, pose (px, py, pz, qx, qy, qz, qw)
    ("floor", proxima.HalfSpace((0, 0, 1), -0.2), (0, 0, 0, 0, 0, 0, 1)),
    ("table", proxima.Box((0.3, 0.4, 0.15)), (0.75, -0.35, 0.15, 0, 0, 0, 1)),
    ("lamp", proxima.Sphere(0.12), (0.85, 0.45, 0.6, 0, 0, 0, 1)),
    ("post", proxima.Cylinder(0.08, 0.7), (-0.55, 0.35, 0.5, 0, 0, 0, 1)),
)
START = (-1.3, 0.25, 0.5, 0.3)  # joint angles (rad): yaw, pitch, pitch, pitch
GOAL = (1.6, 1.0, 0.8, 0.5)


# ---- quaternions (x, y, z, w), vectorised over rows ---------------------------------------


def axis_angle(axis, angles):
    """(M, 4) quaternions turning by `angles` (M,) about one unit axis."""
    half = 0.5 * np.asarray(angles)
    return np.column_stack([np.outer(np.sin(half), axis), np.cos(half)])


def multiply(a, b):
    """Hamilton products a * b of (M, 4) quaternions."""
    ax, ay, az, aw = a.T
    bx, by, bz, bw = b.T
    return np.column_stack([aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
                            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz])


def rotate(q, v):
    """Vectors v (3,) rotated by each quaternion of q (M, 4): (M, 3)."""
    u, w = q[:, :3], q[:, 3:]
    t = 2 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


# ---- the arm ------------------------------------------------------------------------------


def link_shapes():
    return [proxima.Capsule(r, 0.5 * length) for r, length in zip(LINK_RADII, LINK_LENGTHS)]


def link_poses(joint_angles):
    """Forward kinematics: one (M, 7) pose array per link for (M, 4) joint angles. A link's
    capsule runs along its local z from its joint to the next one."""
    joint_angles = np.atleast_2d(joint_angles)
    rotation = axis_angle((0, 0, 1), joint_angles[:, 0])
    joint = np.zeros((len(joint_angles), 3))
    poses = []
    for k, length in enumerate(LINK_LENGTHS):
        rotation = multiply(rotation, axis_angle((0, 1, 0), joint_angles[:, k + 1]))
        axis = rotate(rotation, np.array([0.0, 0.0, 1.0]))
        poses.append(np.hstack([joint + 0.5 * length * axis, rotation]))
        joint = joint + length * axis
    return poses


def trajectory(steps, start=START, goal=GOAL):
    """(steps, 4) joint angles on the straight line from start to goal."""
    s = np.linspace(0.0, 1.0, steps)[:, None]
    return (1 - s) * np.asarray(start) + s * np.asarray(goal)


def check_trajectory(joint_angles):
    """Per configuration: whether any link touches an obstacle, and the clearance (smallest
    signed distance) with the link and obstacle it comes from."""
    poses, shapes = link_poses(joint_angles), link_shapes()
    count = len(joint_angles)
    colliding = np.zeros(count, bool)
    distances = np.empty((len(shapes), len(OBSTACLES), count))
    for i, (shape, pose) in enumerate(zip(shapes, poses)):
        for j, (_, obstacle, obstacle_pose) in enumerate(OBSTACLES):
            colliding |= proxima.intersect_batch(shape, pose, obstacle, obstacle_pose)
            distances[i, j] = proxima.distance_batch(shape, pose, obstacle, obstacle_pose)["signed_distance"]
    flat = distances.reshape(-1, count)
    nearest = flat.argmin(axis=0)
    return {"colliding": colliding, "clearance": flat.min(axis=0),
            "link": nearest // len(OBSTACLES), "obstacle": nearest % len(OBSTACLES)}


def first_collision(result):
    """Index of the first colliding configuration, or None."""
    hits = np.flatnonzero(result["colliding"])
    return int(hits[0]) if hits.size else None


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, default=2000)
    args = parser.parse_args(argv)
    angles = trajectory(args.steps)
    result = check_trajectory(angles)
    first = first_collision(result)
    free = slice(0, first if first is not None else args.steps)
    k = int(np.argmin(result["clearance"][free]))
    print(f"{args.steps} configurations x {len(LINK_LENGTHS)} links x {len(OBSTACLES)} obstacles")
    if first is None:
        print("no configuration collides")
    else:
        link, obstacle = result["link"][first], OBSTACLES[result["obstacle"][first]][0]
        print(f"first colliding configuration: {first} (joint angles {np.round(angles[first], 4).tolist()}): "
              f"link {link} touches the {obstacle}")
    print(f"smallest clearance before it: {result['clearance'][k]:.4f} at configuration {k} "
          f"(link {result['link'][k]}, {OBSTACLES[result['obstacle'][k]][0]})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
