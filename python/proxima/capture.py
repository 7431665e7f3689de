"""proxima.capture: read a capture file (docs/capture-format.md) written by
CollisionWorld.record, the C++ CaptureRecorder or `proxima world --record`.

    cap = proxima.capture.load("run.jsonl")
    cap.header["version"], len(cap), cap.objects_at(10)[id]["position"]
    world = cap.world()          # the recorded world, rebuilt from the scene's snapshot
    for step in cap.steps: step["events"]["begin"]

Steps of reading: the header line (format and version checked), the scene line, then each step
line in order (its index checked); a malformed or truncated line raises CaptureError naming the
line number and the field."""

import base64
import copy
import json

from ._proxima import CollisionWorld, Error
from ._proxima.d2 import CollisionWorld as D2CollisionWorld

FORMAT = "proxima-capture"
VERSION = 1


class CaptureError(Error):
    """A capture that cannot be read: `line` is its 1-based line number, `field` the member."""

    def __init__(self, line, field, message):
        super().__init__(f"line {line}: {field}: {message}")
        self.line, self.field, self.message, self.code = line, field, message, "invalid_argument"


def _require(record, line, field, kind):
    if field not in record:
        raise CaptureError(line, field, "missing")
    if not isinstance(record[field], kind):
        raise CaptureError(line, field, f"expected {getattr(kind, '__name__', kind)}")
    return record[field]


def _parse(text, line):
    try:
        record = json.loads(text)
    except json.JSONDecodeError as e:
        raise CaptureError(line, "line", f"not JSON (cut short or corrupt: {e.msg})") from None
    if not isinstance(record, dict):
        raise CaptureError(line, "line", "expected a JSON object")
    return record


class Capture:
    """A capture read whole: header, scene objects, steps (dicts as in the format)."""

    def __init__(self, header, scene, steps):
        self.header, self.scene, self.steps = header, scene, steps

    def __len__(self):
        return len(self.steps)

    def __repr__(self):
        return f"Capture(version={self.header['version']}, objects={len(self.scene['objects'])}, steps={len(self)})"

    def objects_at(self, frame):
        """The objects after step `frame` (0-based): {id: object record with that step's pose}."""
        if not 0 <= frame < len(self.steps):
            raise CaptureError(0, "frame", f"must be in [0, {len(self.steps)})")
        objects = {o["id"]: copy.deepcopy(o) for o in self.scene["objects"]}
        for step in self.steps[: frame + 1]:
            for gone in step.get("removed", []):
                objects.pop(gone, None)
            for added in step.get("added", []):
                objects[added["id"]] = copy.deepcopy(added)
            for pose in step.get("poses", []):
                if pose["id"] in objects:
                    objects[pose["id"]]["position"] = pose["position"]
                    objects[pose["id"]]["rotation"] = pose["rotation"]
        return objects

    def world(self):
        """The recorded world (as after the first recorded step), rebuilt from the snapshot:
        a CollisionWorld, or a d2.CollisionWorld for a 2D capture (header "dimension": 2)."""
        snapshot = self.scene.get("snapshot")
        if snapshot is None:
            raise CaptureError(2, "snapshot", "this capture was recorded without a snapshot")
        world_type = D2CollisionWorld if self.header.get("dimension", 3) == 2 else CollisionWorld
        return world_type.load(base64.b64decode(snapshot))


def read(lines):
    """A Capture from an iterable of text lines."""
    header = scene = None
    steps = []
    for number, text in enumerate(lines, start=1):
        if not text.strip():
            continue
        record = _parse(text, number)
        if header is None:
            if record.get("format") != FORMAT:
                raise CaptureError(number, "format", f'expected "{FORMAT}"')
            if _require(record, number, "version", int) != VERSION:
                raise CaptureError(number, "version", f"unsupported version {record['version']} (this reader: {VERSION})")
            header = record
        elif scene is None:
            if record.get("type") != "scene":
                raise CaptureError(number, "type", 'expected "scene"')
            _require(record, number, "objects", list)
            scene = record
        else:
            if record.get("type") != "step":
                raise CaptureError(number, "type", 'expected "step"')
            if _require(record, number, "index", int) != len(steps):
                raise CaptureError(number, "index", f"expected {len(steps)}")
            steps.append(record)
    if header is None:
        raise CaptureError(1, "format", "empty file: no header")
    if scene is None:
        raise CaptureError(2, "type", "no scene line")
    return Capture(header, scene, steps)


def load(path):
    """A Capture read from the file at `path`."""
    with open(path, encoding="utf-8") as f:
        return read(f)
