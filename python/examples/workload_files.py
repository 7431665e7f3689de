"""Readers for the shared benchmark workloads that the examples, tests and Python benchmarks use.

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
