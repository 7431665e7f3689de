#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (fuzz/corpus/<target>/seed_*), from the
protocol documents, the query answer corpus, the shared workload files' layouts and fixed
random bytes (seed 1). Files a campaign added (the minimised corpus, crash reproducers
named regression_*) are left alone; seed_* files are rewritten.

    python3 fuzz/make_seeds.py
"""
import collections
import json
import pathlib
import random
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"
rng = random.Random(1)


def write(target, name, data):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    (folder / f"seed_{name}").write_bytes(data)


def reaches_files(line):
    return "file" in line or "png" in line or "\\" in line


def query_seeds():
    """One request per (op, kinds of its shapes) of the answer corpus, and the documents' lines."""
    lines = []
    seen = set()
    for line in (ROOT / "tests/tools/corpus/requests.jsonl").read_text().splitlines():
        if reaches_files(line):
            continue
        op = re.search(r'"op":"(\w+)"', line)
        kinds = tuple(sorted(re.findall(r'"type":"(\w+)"', line)))
        key = (op.group(1) if op else None, kinds[:1])
        if key not in seen:
            seen.add(key)
            lines.append(line)
    for line in (ROOT / "docs/query-protocol.md").read_text().splitlines():
        line = re.sub(r"^echo '(.*)' \|.*$", r"\1", line)
        if line.startswith('{"') and '"op"' in line and not reaches_files(line):
            lines.append(line)
    lines.append('{"id":1,"op":"distance","a":{"type":"sphere","radius":1e18},"b":{"type":"box","half_extents":[1,1,1]}}')
    lines.append('[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]')
    for i, line in enumerate(lines):
        write("query_line", f"{i:03d}", line)


def world_seeds():
    """Each code block of the world protocol document with requests, as one session."""
    text = (ROOT / "docs/world-protocol.md").read_text()
    count = 0
    for block in re.findall(r"```[a-z]*\n(.*?)```", text, re.S):
        lines = [l for l in block.splitlines() if l.startswith('{"') and '"op"' in l and not reaches_files(l)]
        if lines:
            write("world_lines", f"{count:03d}", "\n".join(lines) + "\n")
            count += 1
    shapes = ['{"type":"sphere","radius":0.5}', '{"type":"box","half_extents":[1,0.5,0.25]}',
              '{"type":"capsule","radius":0.3,"half_length":1}', '{"type":"halfspace","normal":[0,0,1],"offset":0}',
              '{"type":"convex","points":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]]}',
              '{"type":"compound","children":[{"type":"sphere","radius":1},{"shape":{"type":"box","half_extents":[1,1,1]},"pose":{"position":[2,0,0]}}]}',
              '{"type":"mesh","vertices":[[0,0,0],[4,0,0],[0,4,0]],"triangles":[[0,1,2]]}']
    for i in range(24):
        lines = []
        for k in range(6):
            g = rng.choice(shapes)
            kind = "static" if ("halfspace" in g or "mesh" in g) else rng.choice(["moving", "static"])
            p = [round(rng.uniform(-3, 3), 2) for _ in range(3)]
            lines.append(f'{{"op":"add","geometry":{g},"kind":"{kind}","ccd":"{rng.choice(["off","auto","bullet"])}","pose":{{"position":{json.dumps(p)}}}}}')
        for k in range(4):
            p = [round(rng.uniform(-3, 3), 2) for _ in range(3)]
            lines.append(f'{{"op":"move","object":{rng.randrange(6)},"pose":{{"position":{json.dumps(p)}}}}}')
            lines.append('{"op":"step","dt":0.016,"contacts":true}')
        lines.append('{"op":"sweep","geometry":{"type":"sphere","radius":0.2},"translation":[5,0,0]}')
        lines.append('{"op":"closest","point":[0,0,0],"max_distance":10}')
        lines.append(f'{{"op":"remove","object":{rng.randrange(6)}}}')
        lines.append('{"op":"step"}')
        write("world_lines", f"gen{i:02d}", "\n".join(lines) + "\n")


SHAPE_EXTRA = {0: 0, 1: 12, 2: 18, 3: 0, 4: 0, 5: 2, 6: 0, 7: 0, 8: 2}


def convex_bytes(kind):
    """A shape as fuzz_shapes.hpp's read_convex reads it: kind, two sizes, the kind's fields."""
    data = bytes([kind]) + rng.randbytes(4)
    if kind in SHAPE_EXTRA:
        return data + rng.randbytes(SHAPE_EXTRA[kind])
    n = rng.randrange(0, 12)
    return data + bytes([n]) + rng.randbytes(6 * (4 + n))


def pose_bytes():
    return rng.randbytes(6) + bytes([rng.choice([0, 4, 1])]) + rng.randbytes(8)


def pair_seeds():
    for a in range(10):
        for b in range(10):
            # Positions near the middle of the cube: bytes 0x80 0x7f are about 0.
            data = convex_bytes(a) + convex_bytes(b) + pose_bytes() + pose_bytes() + rng.randbytes(4)
            write("narrowphase_pairs", f"{a}{b}", data)
    for i in range(40):
        a, b = rng.randrange(10), rng.randrange(10)
        data = convex_bytes(a) + convex_bytes(b) + b"".join(pose_bytes() for _ in range(4)) + rng.randbytes(8)
        write("ccd_queries", f"{i:02d}_{a}{b}", data)


def hull_seeds():
    for i in range(30):
        mode = i % 3
        write("convex_hull", f"{i:02d}", bytes([mode]) + rng.randbytes(2) + rng.randbytes(rng.choice([12, 24, 48, 96, 200])))


def broadphase_seeds():
    for i in range(26):
        ops = bytearray([i % 13])
        for _ in range(40):
            op = rng.randrange(9)
            ops += bytes([op, rng.randrange(12)])
            ops += bytes([rng.randrange(8, 256)]) + bytes(rng.randrange(120, 136) for _ in range(3)) + rng.randbytes(6)
        write("broadphase_ops", f"{i:02d}", bytes(ops))


def workload_seeds():
    """The head of each shared workload format, counts cut down to the records kept."""
    samples = {
        0: "box_pairs 1 count=1\n",
        1: "broadphase 1 n=3 frames=2 dt=1 lo=0 hi=10 name=w\n1 1 1 0.5 0.5 0.5 0.1 0 0\n2 1 1 0.5 0.5 0.5 -0.1 0 0\n9.9 5 5 1 1 1 0.5 0.5 0.5\n",
        2: "convex_shapes 1 count=1 points=4\nshape 0 4 1 1 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n",
        3: "convex_pairs 1 count=1 shapes=s.txt\n0 0 0.8528 1.9637 2.8001 0.72120 0.00360 -0.43049 -0.54271 0.4663 1.1936 1.6848 0.77118 0.61696 -0.14141 -0.06814\n",
        4: "box_pairs 1 count=1\n0.9056 0.1923 0.2127 0.5224 0.5896 -2.6346 0.09183 0.93282 -0.34699 -0.03170  0.6981 0.3468 0.6306 1.6023 0.3524 -2.0765 0.26345 0.74127 -0.47318 -0.39651\n",
        5: "# t\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
        6: "mesh_poses 1 count=1 a=a.obj b=b.obj\n0.5535 -1.9720 -1.4238 0.43973 0.00291 -0.83030 -0.34241\n",
        7: "rays 1 count=2 mesh=m.obj\n0.4837 -1.5742 3.6453 -0.18015 0.65026 -0.73804 2.728\n3.0511 -1.6418 1.9989 -0.50474 0.40396 -0.76292 100\n",
        8: "ccd_pairs 1 count=1 hulls=h.txt\nsphere 0.1725 | box 1.4013 0.6255 0.0160 | 3.3020 -1.9697 0.3969 0.12443 0.90336 0.41042 0.00264 3.8689 -2.7080 5.1167 0.12443 0.90336 0.41042 0.00264 | 1.8685 -1.2857 1.6987 0.48215 0.06812 -0.05403 0.87176 1.8625 -1.2870 1.6832 0.42887 0.18478 -0.05403 0.87176\n",
        9: "sphere_pairs 1 count=2 repeat=2\n3.697 4.522 9.257 0.1023 3.991 4.711 9.078 0.1622\n8.630 6.606 9.483 0.3948 9.436 7.413 9.942 0.9369\n",
        10: "capsule_pairs 1 count=1 repeat=3\n5.613 2.829 4.540 5.712 2.109 3.522 0.0959  5.579 2.848 4.626 5.505 2.561 3.403 0.1954\n",
        12: "world_bullets_expected 1 count=3 world=w.txt\n0 59 0.044720903 1024\n1 29 0.272581900 1151\n2 -1 -1 -1\n",
        13: "polygons2d_pairs 1 count=2\nbox2d 0.908 0.851 0.079 | -1.485 -1.072 2.0136 | polygon 3 -0.267 0.717 -0.451 -0.496 0.446 -0.579 0 | -2.497 -1.208 -1.7655\nbox2d 0.901 0.534 0 | 2.755 0.217 0.9552 | polygon 5 -0.614 -0.359 0.292 -0.797 0.672 -0.422 -0.403 0.745 -0.729 0.037 0 | 0.994 0.55 3.0018\n",
        14: "sprite_masks 1 count=1 encoding=hex\nmask 0 8 2\n0f\nf0\n",
        15: "sprites 1 count=2 repeat=1 masks=m.txt\n0 0 0 0 3 1\n0 1 2 0 0 0\n",
        16: "sprites_expected 1 count=2 sprites=s.txt\n0 0 0\n1 1 664\n",
    }
    data = ROOT.parent / "shared/bench/data"
    for name, which in (("world_bullets.txt", 11), ("world_terrain.txt", 11), ("world_level_40k.txt", 11),
                        ("world_mixed_10k.txt", 11), ("world2d_mixed_20k.txt", 17)):
        path = data / name
        if not path.exists():
            continue
        lines = path.read_text().splitlines()
        header = re.sub(r"objects=\d+", "objects=4", lines[0])
        write("workload_readers", f"{which:02d}_{name.split('.')[0]}", bytes([which]) + ("\n".join([header] + lines[1:5]) + "\n").encode())
    for which, text in samples.items():
        write("workload_readers", f"{which:02d}", bytes([which]) + text.encode())


query_seeds()
world_seeds()
pair_seeds()
hull_seeds()
broadphase_seeds()
workload_seeds()
