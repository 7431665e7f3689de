#!/usr/bin/env python3
"""Writes the query answer corpus: a fixed, seeded set of `proxima query` requests over every
operation and every shape kind (convex shapes, half-space, mesh, compound), plus the examples
of docs/query-protocol.md and a set of rejected requests.

The corpus pins the tool's answers byte for byte across refactoring: `answers_float.jsonl` and
`answers_double.jsonl` beside it are what `proxima query` printed for `requests.jsonl` in each
precision, and tests/tools/test_query_corpus.cpp compares. Regenerate the requests only on
purpose (the answers must then be recorded again from a build known to be right):

    /usr/bin/python3 tests/tools/corpus/make_corpus.py > tests/tools/corpus/requests.jsonl
    build/release/tools/proxima query tests/tools/corpus/requests.jsonl > tests/tools/corpus/answers_float.jsonl
    build/double/tools/proxima query tests/tools/corpus/requests.jsonl > tests/tools/corpus/answers_double.jsonl

Run from the repository root: mesh files are named relative to it.
"""
import json
import math
import random
import re
import sys

SEED = 20261126
DOC = "docs/query-protocol.md"
DATA = "tests/tools/data"

CONVEX = ["point", "segment", "triangle", "sphere", "capsule", "box", "cylinder", "cone",
          "ellipsoid", "convex"]
KINDS = CONVEX + ["halfspace", "mesh", "compound"]
BOUND_VOLUMES = ["aabb", "sphere", "obb", "capsule", "kdop6", "kdop14", "kdop18", "kdop26"]
FIT_VOLUMES = ["aabb", "sphere", "sphere_centroid", "sphere_aabb", "sphere_ritter", "obb",
               "obb_pca", "obb_dito14", "obb_dito26", "capsule", "kdop6", "kdop14", "kdop18",
               "kdop26", "hull"]
STRUCTURES = ["brute", "sap", "sap_oneshot", "mbp", "tree", "kdtree", "bsp", "grid", "hash",
              "hgrid", "octree", "quadtree"]
MESH_FILES = ["tetrahedron.obj", "tetrahedron.stl", "tetrahedron.ply", "tetrahedron.gltf",
              "tetrahedron_mirrored.gltf", "cube_and_tetrahedron.obj"]

rng = random.Random(SEED)


def num(lo, hi, digits=3):
    return round(rng.uniform(lo, hi), digits)


def point(scale=1.0):
    return [num(-scale, scale) for _ in range(3)]


def positive3(lo, hi):
    return [num(lo, hi) for _ in range(3)]


def quaternion():
    # Uniform random rotation (Shoemake), rounded to 4 digits: well within the protocol's
    # 1e-3 tolerance on the length.
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    q = [a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2),
         b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3)]
    return [round(c, 4) for c in q]


def pose(scale=1.5):
    choice = rng.random()
    if choice < 0.15:
        return None
    result = {"position": point(scale)}
    if choice > 0.3:
        result["rotation"] = quaternion()
    return result


def inline_mesh():
    kind = rng.randrange(4)
    if kind == 0:  # closed tetrahedron
        return {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                "triangles": [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]}
    if kind == 1:  # closed cube with random half extents
        h = positive3(0.3, 1.2)
        v = [[sx * h[0], sy * h[1], sz * h[2]] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        t = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
             [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
        return {"type": "mesh", "vertices": v, "triangles": t}
    if kind == 2:  # open height-field patch, 3 x 3 quads
        v = [[x - 1.5, y - 1.5, num(-0.3, 0.3)] for y in range(4) for x in range(4)]
        t = []
        for y in range(3):
            for x in range(3):
                i = y * 4 + x
                t += [[i, i + 1, i + 5], [i, i + 5, i + 4]]
        mesh = {"type": "mesh", "vertices": v, "triangles": t}
        if rng.random() < 0.3:
            mesh["repair"] = False
        return mesh
    # a random triangle soup of 3 to 6 triangles
    n = rng.randint(3, 6)
    v = [point(1.2) for _ in range(3 * n)]
    return {"type": "mesh", "vertices": v, "triangles": [[3 * i, 3 * i + 1, 3 * i + 2] for i in range(n)],
            "repair": rng.random() < 0.5}


def mesh():
    if rng.random() < 0.4:
        return {"type": "mesh", "file": f"{DATA}/{rng.choice(MESH_FILES)}"}
    return inline_mesh()


def convex_shape(kind):
    if kind == "point":
        return {"type": "point"}
    if kind == "segment":
        return {"type": "segment", "vertices": [point(), point()]}
    if kind == "triangle":
        return {"type": "triangle", "vertices": [point(), point(), point()]}
    if kind == "sphere":
        return {"type": "sphere", "radius": num(0.2, 1.5)}
    if kind == "capsule":
        return {"type": "capsule", "radius": num(0.1, 0.8), "half_length": num(0, 1.2)}
    if kind == "box":
        return {"type": "box", "half_extents": positive3(0.1, 1.2)}
    if kind in ("cylinder", "cone"):
        return {"type": kind, "radius": num(0.2, 1.2), "half_length": num(0.1, 1.2)}
    if kind == "ellipsoid":
        return {"type": "ellipsoid", "radii": positive3(0.2, 1.3)}
    if kind == "convex":
        return {"type": "convex", "points": [point(1.0) for _ in range(rng.randint(4, 24))]}
    raise ValueError(kind)


def shape(kind, depth=0):
    if kind in CONVEX:
        return convex_shape(kind)
    if kind == "halfspace":
        return {"type": "halfspace", "normal": point(), "offset": num(-1, 1)}
    if kind == "mesh":
        return mesh()
    if kind == "compound":
        children = []
        for _ in range(rng.randint(1, 3)):
            r = rng.random()
            if r < 0.6:
                child = convex_shape(rng.choice(CONVEX))
            elif r < 0.85 or depth >= 1:
                child = inline_mesh()
            else:
                child = shape("compound", depth + 1)
            entry = {"shape": child}
            p = pose(1.0)
            if p is not None:
                entry["pose"] = p
            children.append(entry)
        return {"type": "compound", "children": children}
    raise ValueError(kind)


def target(kind, scale=1.5):
    s = shape(kind)
    p = pose(scale)
    if p is None and rng.random() < 0.5:
        return s  # a bare shape at the identity
    result = {"shape": s}
    if p is not None:
        result["pose"] = p
    return result


requests = []


def add(request):
    request = {"id": len(requests) + 1, **request}
    requests.append(json.dumps(request, separators=(",", ":")))


def doc_examples():
    """The request lines of the protocol document's plain code blocks (request/answer pairs)."""
    lines, block, pending = [], None, None
    with open(DOC, encoding="utf-8") as doc:
        for line in doc:
            line = line.rstrip("\n")
            if line.startswith("```"):
                block = None if block is not None else (line == "```")
                pending = None
                continue
            if not block or not line.startswith("{"):
                pending = None
                continue
            if pending is None:
                pending = line
            else:
                lines.append(pending)
                pending = None
    return lines


def main():
    for kind in KINDS:
        for _ in range(80):
            req = {"op": "raycast", "target": target(kind), "origin": point(4), "direction": point(1)}
            if rng.random() < 0.5:
                req["max_t"] = num(0.5, 10)
            add(req)
        for op in ("contains", "closest_point"):
            for _ in range(30):
                add({"op": op, "target": target(kind), "point": point(2.5)})
        for _ in range(12):
            req = {"op": "mass", "target": target(kind)}
            if rng.random() < 0.5:
                req["density"] = num(0.1, 10)
            add(req)
        for volume in BOUND_VOLUMES:
            for _ in range(3):
                add({"op": "bound", "target": target(kind), "volume": volume})
    for volume in FIT_VOLUMES:
        for _ in range(15):
            n = rng.randint(1 if volume != "hull" else 4, 40)
            add({"op": "fit", "points": [point(3) for _ in range(n)], "volume": volume})
    for structure in STRUCTURES:
        for _ in range(10):
            boxes = []
            for _ in range(rng.randint(0, 40)):
                lo = point(5)
                boxes.append(lo + [round(c + rng.uniform(0, 2), 3) for c in lo])
            add({"op": "pairs", "boxes": boxes, "structure": structure})
    for a in KINDS:
        for b in KINDS:
            for op in ("intersect", "distance", "collide"):
                for _ in range(5):
                    req = {"op": op, "a": target(a, 0.5), "b": target(b, 1.5)}
                    if op == "collide" and rng.random() < 0.5:
                        req["max_contacts"] = rng.randint(1, 4)
                        req["contact_distance"] = num(0, 0.3)
                    add(req)
    # Rejected requests: every answer of an error is pinned too.
    bad = [
        {"op": "contains", "target": {"type": "sphere", "radius": -1}, "point": [0, 0, 0]},
        {"op": "raycast", "target": {"type": "sphere", "radius": 1}, "origin": [0, 0], "direction": [0, 0, 1]},
        {"op": "raycast", "target": {"type": "box", "half_extents": [1, 1, 0]}, "origin": [0, 0, 5], "direction": [0, 0, -1]},
        {"op": "distance", "a": {"type": "sphere", "radius": 1}, "b": {"type": "capsule", "radius": 1}},
        {"op": "collide", "a": {"type": "sphere", "radius": 1}, "b": {"type": "sphere", "radius": 1}, "max_contacts": 9},
        {"op": "mass", "target": {"type": "halfspace", "normal": [0, 0, 1], "offset": 0}},
        {"op": "bound", "target": {"type": "halfspace", "normal": [0, 0, 1], "offset": 0}, "volume": "obb"},
        {"op": "fit", "points": [], "volume": "aabb"},
        {"op": "fit", "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "volume": "hull"},
        {"op": "pairs", "boxes": [[0, 0, 0, 1, 1, 1]], "structure": "nope"},
        {"op": "nope"},
        {"op": "contains", "target": {"type": "sphere", "radius": 1}, "point": [0, 0, 0], "extra": 1},
        {"op": "raycast", "target": {"type": "mesh", "file": "no/such/file.obj"}, "origin": [0, 0, 1], "direction": [0, 0, -1]},
        {"op": "contains", "target": {"type": "compound", "children": [{"shape": {"type": "sphere", "radius": 1}}]}, "point": [0, 0, 0]},
        {"op": "raycast", "target": {"shape": {"type": "sphere", "radius": 1}, "pose": {"rotation": [0, 0, 0, 2]}}, "origin": [0, 0, 5], "direction": [0, 0, -1]},
        {"op": "raycast", "target": {"type": "convex", "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}, "origin": [0, 0, 5], "direction": [0, 0, -1]},
        {"op": "mass", "target": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]]}},
        {"op": "collide", "a": {"type": "compound", "children": [{"shape": {"type": "halfspace", "normal": [0, 0, 1], "offset": 0}}]}, "b": {"type": "sphere", "radius": 1}},
    ]
    for request in bad:
        add(request)
    for line in doc_examples():
        # Verbatim (some are malformed on purpose), with the document's own ids.
        requests.append(line)
    sys.stdout.write("\n".join(requests) + "\n")


if __name__ == "__main__":
    main()
