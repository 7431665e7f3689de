"""The data the examples, tests and Python benchmarks use: readers for the shared benchmark
workloads, and built-in meshes (a torus, a UV sphere) for when those files are absent.

Where the files are: the PROXIMA_WORKLOADS environment variable, else the folder
`../shared/bench/data` beside the source tree (the default the C++ benchmarks compile in).
Formats (shared/bench/FORMATS.md): W4 OBJ meshes (`v x y z`, `f i j k`, 1-based) and the W5
rays file (`rays 1 count=<M> mesh=<obj>` then `ox oy oz dx dy dz tmax` lines). Only numpy.
"""

import os
from pathlib import Path

import numpy as np

SOURCE_ROOT = Path(__file__).resolve().parents[2]


def workload_dir():
    """The shared workload folder (a Path), or None when it does not exist."""
    folder = Path(os.environ.get("PROXIMA_WORKLOADS", SOURCE_ROOT.parent / "shared" / "bench" / "data"))
    return folder if folder.is_dir() else None


def workload_file(name):
    """The path of one shared workload file, or None when it is absent."""
    folder = workload_dir()
    if folder is None or not (folder / name).is_file():
        return None
    return folder / name


def _data_lines(path):
    """The lines of a text file without blank and `#` comment lines."""
    with open(path, encoding="ascii") as f:
        return [line for line in f.read().splitlines() if line.strip() and not line.lstrip().startswith("#")]


def read_obj(path):
    """A W4 OBJ mesh as (vertices float64 (N, 3), triangles int64 (M, 3), 0-based)."""
    lines = _data_lines(path)
    vertex_text = " ".join(line[2:] for line in lines if line.startswith("v "))
    face_text = " ".join(line[2:] for line in lines if line.startswith("f "))
    vertices = np.array(vertex_text.split(), dtype=np.float64).reshape(-1, 3)
    triangles = np.array(face_text.split(), dtype=np.int64).reshape(-1, 3) - 1
    return vertices, triangles


def read_rays(path):
    """A W5 rays file as (rays float64 (M, 6): origin, direction; max_t float64 (M,); mesh name)."""
    lines = _data_lines(path)
    header = lines[0].split()
    if header[:2] != ["rays", "1"]:
        raise ValueError(f"{path}: not a version 1 rays file")
    keys = dict(token.split("=", 1) for token in header[2:] if "=" in token)
    table = np.array(" ".join(lines[1:]).split(), dtype=np.float64).reshape(-1, 7)
    if len(table) != int(keys["count"]):
        raise ValueError(f"{path}: {len(table)} rays, header says {keys['count']}")
    return np.ascontiguousarray(table[:, :6]), np.ascontiguousarray(table[:, 6]), keys["mesh"]


def torus_mesh(major_radius=1.0, minor_radius=0.35, rings=64, sides=24):
    """A closed torus around z (vertices (rings * sides, 3), triangles (2 * rings * sides, 3), outward)."""
    u = np.repeat(np.linspace(0, 2 * np.pi, rings, endpoint=False), sides)
    v = np.tile(np.linspace(0, 2 * np.pi, sides, endpoint=False), rings)
    ring = major_radius + minor_radius * np.cos(v)
    vertices = np.column_stack([ring * np.cos(u), ring * np.sin(u), minor_radius * np.sin(v)])
    i, j = np.meshgrid(np.arange(rings), np.arange(sides), indexing="ij")
    a, b = i * sides + j, ((i + 1) % rings) * sides + j
    c, d = ((i + 1) % rings) * sides + (j + 1) % sides, i * sides + (j + 1) % sides
    triangles = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return vertices, triangles


def uv_sphere_mesh(radius=1.0, stacks=48, slices=96):
    """A closed UV sphere centred on the origin: the poles are single vertices; outward triangles."""
    theta = np.linspace(0, np.pi, stacks + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, slices, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.column_stack([np.sin(t).ravel() * np.cos(p).ravel(), np.sin(t).ravel() * np.sin(p).ravel(), np.cos(t).ravel()])
    vertices = radius * np.vstack([[0, 0, 1], ring, [0, 0, -1]])
    south = len(vertices) - 1
    k = np.arange(slices)

    def row(stack):  # index of the first vertex of a ring
        return 1 + stack * slices

    triangles = [np.column_stack([np.zeros(slices, int), row(0) + k, row(0) + (k + 1) % slices])]
    for s in range(stacks - 2):
        a, b = row(s) + k, row(s) + (k + 1) % slices
        c, d = row(s + 1) + (k + 1) % slices, row(s + 1) + k
        triangles += [np.column_stack([a, d, c]), np.column_stack([a, c, b])]
    last = row(stacks - 2)
    triangles.append(np.column_stack([np.full(slices, south), last + (k + 1) % slices, last + k]))
    return vertices, np.vstack(triangles).astype(np.int64)
