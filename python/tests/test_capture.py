"""Recording a world from Python and reading the capture back: the poses, events and contacts
of every step equal what the world reported while it ran, the scene's snapshot rebuilds the
recorded world, truncated or foreign files raise CaptureError naming the line, and the
tool (`proxima render`) reads and draws the same file. A 2D world records a dimension-2
capture whose objects lie in the plane z = 0 and whose snapshot rebuilds a d2.CollisionWorld."""

import math
import os
import subprocess

import numpy as np
import pytest

import proxima
from proxima import capture, d2


def falling_world():
    w = proxima.CollisionWorld()
    floor = w.add(proxima.Box((5, 5, 0.5)), (0, 0, -0.5, 0, 0, 0, 1), kind=proxima.ObjectKind.Static)
    ball = w.add(proxima.Sphere(0.5), (0, 0, 2, 0, 0, 0, 1))
    return w, floor, ball


@pytest.fixture
def recorded(tmp_path):
    w, floor, ball = falling_world()
    path = tmp_path / "fall.jsonl"
    w.record(str(path))
    seen = []
    for i in range(12):
        w.move(ball, (0, 0, 2 - 0.2 * i, 0, 0, 0, 1))
        w.step(0.1)
        seen.append((w.pose(ball).position.copy(), w.events["begin"].copy(), w.contacts().copy(), w.state_hash()))
    w.raycast((0, 0, 10), (0, 0, -1), 20)
    w.stop_recording()
    return path, floor, ball, seen


def test_every_step_reads_back_as_the_world_ran(recorded):
    path, floor, ball, seen = recorded
    cap = capture.load(path)
    assert cap.header["format"] == "proxima-capture" and cap.header["version"] == 1
    assert len(cap) == 12
    for i, (position, begin, contacts, _) in enumerate(seen):
        objects = cap.objects_at(i)
        np.testing.assert_allclose(objects[ball]["position"], position, atol=1e-6)
        assert cap.steps[i]["events"]["begin"] == [[int(a), int(b)] for a, b in zip(begin["a"], begin["b"])]
        assert len(cap.steps[i]["contacts"]) == len({(int(a), int(b)) for a, b in zip(contacts["a"], contacts["b"])})
    assert any(step["events"]["begin"] == [[floor, ball]] for step in cap.steps)
    assert cap.objects_at(0)[floor]["geometry"]["type"] == "box"
    assert len(cap.objects_at(0)[ball]["mesh"]["indices"]) % 3 == 0


def test_the_snapshot_rebuilds_the_recorded_world(recorded):
    path, floor, ball, seen = recorded
    world = capture.load(path).world()
    assert world.state_hash() == seen[0][3]
    assert set(world.objects().tolist()) == {floor, ball}


@pytest.mark.parametrize("cut, line, field", [
    (lambda text: text[: len(text) // 2], None, "line"),
    (lambda text: text.replace("proxima-capture", "something-else", 1), 1, "format"),
    (lambda text: "\n".join(l for i, l in enumerate(text.splitlines()) if i != 3) + "\n", 4, "index"),
    (lambda text: "", 1, "format"),
])
def test_bad_files_name_the_line_and_field(recorded, tmp_path, cut, line, field):
    text = recorded[0].read_text()
    bad = tmp_path / "bad.jsonl"
    bad.write_text(cut(text))
    with pytest.raises(capture.CaptureError) as info:
        capture.load(bad)
    assert info.value.field == field
    if line is not None:
        assert info.value.line == line
    assert isinstance(info.value, proxima.Error)


def test_the_tool_draws_the_python_capture(recorded, tmp_path):
    cli = os.environ.get("PROXIMA_CLI")
    if not cli or not os.path.exists(cli):
        pytest.skip("PROXIMA_CLI is not available")
    out = tmp_path / "frame.png"
    done = subprocess.run([cli, "render", str(recorded[0]), "--frame", "11", "-o", str(out)],
                          capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_render_from_python_draws_the_objects_and_the_contact(recorded, tmp_path):
    if not hasattr(proxima, "render"):
        pytest.skip("built without the tool (PROXIMA_BUILD_TOOLS=OFF)")
    path = recorded[0]
    image = proxima.render(str(path), 11, width=320, height=240)
    assert image.shape == (240, 320, 4) and image.dtype == np.uint8
    np.testing.assert_array_equal(image[0, 0], (32, 34, 40, 255))  # the background
    rgb = image[..., :3].astype(int)
    ball = (rgb[..., 2] > rgb[..., 0] + 40).sum()  # the moving sphere is drawn blue
    red = ((rgb[..., 0] > 180) & (rgb[..., 1] < 90)).sum()  # contact markers
    assert ball > 50 and red > 0
    shapes_only = proxima.render(str(path), 11, width=320, height=240, layers=["shapes"])[..., :3].astype(int)
    assert ((shapes_only[..., 0] > 180) & (shapes_only[..., 1] < 90)).sum() == 0
    proxima.render(str(path), 11, str(tmp_path / "frame.svg"))
    assert "<svg" in (tmp_path / "frame.svg").read_text()[:400]
    with pytest.raises(proxima.Error) as info:
        proxima.render(str(path), 99)
    assert info.value.field == "frame"


def test_a_2d_world_records_a_dimension_2_capture(tmp_path):
    w = d2.CollisionWorld()
    floor = w.add(d2.Box(5, 0.5), (0, -0.5, 0), kind=proxima.ObjectKind.Static)
    ball = w.add(d2.Circle(0.5), (0, 2, 0))
    path = tmp_path / "fall2d.jsonl"
    w.record(str(path))
    hashes = []
    for i in range(8):
        w.move(ball, (0, 2 - 0.25 * i, 0.1 * i))
        w.step()
        hashes.append(w.state_hash())
    w.stop_recording()
    cap = capture.load(path)
    assert cap.header["dimension"] == 2 and len(cap) == 8
    objects = cap.objects_at(7)
    assert objects[floor]["geometry"]["type"] == "polygon" and objects[ball]["geometry"]["type"] == "circle"
    np.testing.assert_allclose(objects[ball]["position"], [0, 0.25, 0], atol=1e-6)
    # The turn of 0.7 rad about +z as [x, y, z, w].
    np.testing.assert_allclose(objects[ball]["rotation"], [0, 0, math.sin(0.35), math.cos(0.35)], atol=1e-6)
    assert all(z == 0 for z in objects[ball]["mesh"]["positions"][2::3])
    assert any(step["events"]["begin"] == [[floor, ball]] for step in cap.steps)
    world = cap.world()
    assert isinstance(world, d2.CollisionWorld) and world.state_hash() == hashes[0]
    assert world.objects().tolist() == [floor, ball]
