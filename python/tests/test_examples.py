"""The examples run and their answers hold against independent computations.

arm_trajectory: forward kinematics against rotation matrices, the first colliding
configuration against one proxima.intersect call per configuration, link and obstacle, and
against the analytic capsule-sphere distance for the lamp (the obstacle hit first), and the
printed index. depth_image: a built-in UV sphere's depth image against analytic ray-sphere
hits, and the PNG the example writes (size, a silhouette: some pixels hit, not all).
world_events: the 2D and the 3D world's events along the scripted path against the frames
where the ball's analytic height makes it touch, and the impact against the analytic time.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import require

import proxima

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import arm_trajectory  # noqa: E402

STEPS = 2000


def rotation_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rotation_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def link_segments_by_matrices(angles):
    """(start, end) of each link's axis for one configuration, with 3x3 rotation matrices."""
    rotation, joint, segments = rotation_z(angles[0]), np.zeros(3), []
    for k, length in enumerate(arm_trajectory.LINK_LENGTHS):
        rotation = rotation @ rotation_y(angles[k + 1])
        end = joint + rotation @ np.array([0.0, 0.0, length])
        segments.append((joint, end))
        joint = end
    return segments


def segment_of_pose(pose, half_length):
    """The capsule axis of a pose (px py pz qx qy qz qw): its two end points."""
    axis = arm_trajectory.rotate(pose[None, 3:], np.array([0.0, 0.0, 1.0]))[0]
    return pose[:3] - half_length * axis, pose[:3] + half_length * axis


def test_forward_kinematics_matches_rotation_matrices():
    angles = arm_trajectory.trajectory(7)
    poses = arm_trajectory.link_poses(angles)
    for m in range(len(angles)):
        expected = link_segments_by_matrices(angles[m])
        for k, length in enumerate(arm_trajectory.LINK_LENGTHS):
            start, end = segment_of_pose(poses[k][m], 0.5 * length)
            assert np.allclose(start, expected[k][0], atol=1e-12) and np.allclose(end, expected[k][1], atol=1e-12)


@pytest.fixture(scope="module")
def arm_run():
    angles = arm_trajectory.trajectory(STEPS)
    return angles, arm_trajectory.check_trajectory(angles)


def test_first_collision_matches_one_query_per_configuration(arm_run):
    angles, result = arm_run
    first = arm_trajectory.first_collision(result)
    assert first is not None and 0 < first < STEPS - 1
    shapes, poses = arm_trajectory.link_shapes(), arm_trajectory.link_poses(angles[: first + 1])
    touching = [any(proxima.intersect(shape, pose[m], obstacle, obstacle_pose)
                    for shape, pose in zip(shapes, poses) for _, obstacle, obstacle_pose in arm_trajectory.OBSTACLES)
                for m in range(first + 1)]
    assert touching.index(True) == first


def point_segment_distance(points, a, b):
    ab = b - a
    s = np.clip(np.einsum("ij,ij->i", points - a, ab) / np.einsum("ij,ij->i", ab, ab), 0, 1)
    return np.linalg.norm(points - (a + s[:, None] * ab), axis=1)


def test_first_collision_matches_the_analytic_lamp_distance(arm_run):
    angles, result = arm_run
    name, lamp, lamp_pose = arm_trajectory.OBSTACLES[2]
    assert name == "lamp"
    centre = np.broadcast_to(np.asarray(lamp_pose[:3], float), (len(angles), 3))
    gaps = []
    for pose, length, radius in zip(arm_trajectory.link_poses(angles), arm_trajectory.LINK_LENGTHS,
                                    arm_trajectory.LINK_RADII):
        axis = arm_trajectory.rotate(pose[:, 3:], np.array([0.0, 0.0, 1.0]))
        a, b = pose[:, :3] - 0.5 * length * axis, pose[:, :3] + 0.5 * length * axis
        gaps.append(point_segment_distance(centre, a, b) - radius - lamp.radius)
    analytic_first = int(np.flatnonzero(np.min(gaps, axis=0) <= 0)[0])
    assert abs(analytic_first - arm_trajectory.first_collision(result)) <= 1  # float rounding at the contact
    before = slice(0, analytic_first)
    assert result["clearance"][before].min() <= np.min(gaps, axis=0)[before].min() + 1e-5


def test_arm_example_prints_the_first_collision(arm_run, capsys):
    assert arm_trajectory.main(["--steps", str(STEPS)]) == 0
    printed = capsys.readouterr().out
    assert f"first colliding configuration: {arm_trajectory.first_collision(arm_run[1])} " in printed


# ---- depth image ----------------------------------------------------------------------------


def test_sphere_depth_matches_analytic_hits():
    require("PIL")
    import depth_image

    width, height = 160, 120
    mesh = proxima.TriangleMesh(*depth_image.load_mesh("sphere"))
    depth = depth_image.depth_image(mesh, width, height).ravel()
    rays = depth_image.camera_rays(width, height)
    o, d = rays[:, :3], rays[:, 3:]
    b = np.einsum("ij,ij->i", o, d)
    disc = b * b - (np.einsum("ij,ij->i", o, o) - 1.0)
    analytic = np.where(disc >= 0, -b - np.sqrt(np.maximum(disc, 0)), np.inf)
    hit, expected_hit = np.isfinite(depth), np.isfinite(analytic)
    assert 0 < expected_hit.sum() < len(rays)
    assert (hit != expected_hit).sum() <= 0.01 * expected_hit.sum()  # silhouette pixels of the faceted sphere
    clear = hit & (disc > 0.05)
    assert np.abs(depth[clear] - analytic[clear]).max() <= 0.01


def test_depth_example_writes_a_png_with_a_silhouette(tmp_path, capsys):
    image_module = require("PIL.Image")
    import depth_image

    output = tmp_path / "depth.png"
    assert depth_image.main(["--size", "160x120", "-o", str(output)]) == 0
    with image_module.open(output) as image:
        assert image.size == (160, 120) and image.mode == "L"
        pixels = np.asarray(image)
    assert 0 < (pixels > 0).sum() < pixels.size
    assert "pixels hit the mesh" in capsys.readouterr().out


# ---- world events ---------------------------------------------------------------------------


def test_world_events_match_the_script_in_2d_and_3d(capsys):
    import world_events

    # The ball's bottom is 0.4, 0.18, then -0.04 (touching) above the floor, slides, lifts off
    # at frame 5 (0.16 above); the shot from x = 0.4 meets the wall's face (x = 6.95) when its
    # centre reaches x = 6.45.
    start, end = world_events.SCRIPT[-2][0], world_events.SCRIPT[-1][0]
    face = world_events.WALL_X - world_events.WALL_HALF - world_events.RADIUS
    expected_toi = (face - start) / (end - start)
    for make_world in (world_events.world_2d, world_events.world_3d):
        log = world_events.run(make_world)
        assert [e[:4] for e in log] == [(2, "begin", 0, 2), (3, "persist", 0, 2), (4, "persist", 0, 2),
                                        (5, "end", 0, 2), (6, "impact", 2, 1)]
        assert log[-1][4] == pytest.approx(expected_toi, abs=2e-3)
    assert world_events.main([]) == 0
    printed = capsys.readouterr().out
    assert "2D world:" in printed and "3D world:" in printed and printed.count("impact") == 2
