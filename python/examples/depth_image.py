#!/usr/bin/python3
"""A depth image of a mesh from one batched ray cast, saved as a PNG.

A pinhole camera (eye, target, vertical field of view) makes one ray per pixel; one
raycast_batch call (threads=0: every hardware thread) casts them all at the mesh. The depth
along each ray (unit directions, so t is the distance) is written as an 8-bit grey PNG with
Pillow: near is bright, far is dark, pixels whose ray misses are black. The mesh: the W4
torus knot of the shared workloads when present, else a built-in torus; or --mesh sphere
(a built-in UV sphere of radius 1), torus, or an OBJ file.

  PYTHONPATH=build/release/python /usr/bin/python3 python/examples/depth_image.py \
      [--mesh knot|torus|sphere|FILE.obj] [--size 320x240] [-o depth.png]
"""

import argparse
import sys
from pathlib import Path

import numpy as np
from PIL import Image

import proxima

sys.path.insert(0, str(Path(__file__).resolve().parent))
import example_data  # noqa: E402

EYE = (0.0, -4.2, 2.2)
TARGET = (0.0, 0.0, 0.0)
FIELD_OF_VIEW = 40.0  # degrees, vertical


def load_mesh(name):
    """(vertices, triangles) of `name`: knot (W4, else a torus), torus, sphere or an OBJ path."""
    if name == "knot":
        path = example_data.workload_file("mesh_torusknot.obj")
        return example_data.read_obj(path) if path is not None else example_data.torus_mesh()
    if name == "torus":
        return example_data.torus_mesh()
    if name == "sphere":
        return example_data.uv_sphere_mesh()
    return example_data.read_obj(name)


def camera_rays(width, height, eye=EYE, target=TARGET, fov=FIELD_OF_VIEW):
    """(height * width, 6) rays, row by row from the top: the eye and a unit direction per pixel centre."""
    eye, target = np.asarray(eye, float), np.asarray(target, float)
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half_height = np.tan(np.radians(fov) / 2)
    half_width = half_height * width / height
    x = ((np.arange(width) + 0.5) / width * 2 - 1) * half_width
    y = (1 - (np.arange(height) + 0.5) / height * 2) * half_height
    xx, yy = np.meshgrid(x, y)
    directions = forward + xx[..., None] * right + yy[..., None] * up
    directions /= np.linalg.norm(directions, axis=-1, keepdims=True)
    return np.hstack([np.broadcast_to(eye, (width * height, 3)), directions.reshape(-1, 3)])


def depth_image(mesh, width, height):
    """(height, width) distances to the mesh, +inf where the ray misses."""
    hits = proxima.raycast_batch(mesh, None, camera_rays(width, height), threads=0)
    return np.where(hits["hit"].astype(bool), hits["t"], np.inf).reshape(height, width)


def to_grey(depth):
    """8-bit grey: the nearest hit 255, the farthest 40, misses 0."""
    hit = np.isfinite(depth)
    grey = np.zeros(depth.shape, np.uint8)
    if hit.any():
        near, far = depth[hit].min(), depth[hit].max()
        grey[hit] = np.round(255 - 215 * (depth[hit] - near) / max(far - near, 1e-12)).astype(np.uint8)
    return grey


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mesh", default="knot")
    parser.add_argument("--size", default="320x240", help="WIDTHxHEIGHT in pixels")
    parser.add_argument("-o", "--output", type=Path, default=Path("depth.png"))
    args = parser.parse_args(argv)
    width, height = (int(v) for v in args.size.split("x"))
    mesh = proxima.TriangleMesh(*load_mesh(args.mesh))
    depth = depth_image(mesh, width, height)
    Image.fromarray(to_grey(depth), mode="L").save(args.output)
    hit = np.isfinite(depth)
    print(f"{args.output}: {width}x{height}, {hit.sum()} of {hit.size} pixels hit the mesh "
          f"({len(mesh.triangles)} triangles), depth {depth[hit].min():.3f} to {depth[hit].max():.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
