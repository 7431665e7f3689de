"""Type stubs of proxima (written by python/tools/make_stubs.py from the module; do not edit)."""

from typing import Any, Iterator, List, Optional, Tuple

import numpy


from typing import overload

def Box(hx: float, hy: float, radius: float = ...) -> Shape: """A box of half extents hx, hy centred on the origin."""

def Capsule(a: Any, b: Any, radius: float) -> Shape: """Points within radius of the segment a-b (local frame)."""

def Chain(points: Any, loop: bool = ...) -> Shape: """One-sided segments through the points (the right side collides: the outside of a counter-clockwise loop)."""

def Circle(radius: float, center: Any = ...) -> Shape: """A disc of radius about center (local frame)."""

class DistanceResult:
    """2D separation or penetration (world frame)."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    @property
    def normal(self) -> numpy.ndarray: ...
    @property
    def part_a(self) -> int: ...
    @property
    def part_b(self) -> int: ...
    @property
    def point_a(self) -> numpy.ndarray: ...
    @property
    def point_b(self) -> numpy.ndarray: ...
    @property
    def signed_distance(self) -> float: ...
    @property
    def status(self) -> PairStatus: ...

class Manifold:
    """Up to 2 contact points sharing one normal (world frame)."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    def __len__(self: Manifold) -> int: ...
    @property
    def normal(self) -> numpy.ndarray: ...
    @property
    def points(self) -> list: ...

def Point(position: Any = ...) -> Shape: """A point at position (local frame)."""

def Polygon(points: Any, radius: float = ...) -> Shape: """The convex hull of 3 to 16 points, optionally rounded."""

class RayHit:
    """Where a 2D ray meets a shape."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    @property
    def normal(self) -> numpy.ndarray: ...
    @property
    def part(self) -> int: ...
    @property
    def point(self) -> numpy.ndarray: ...
    @property
    def t(self) -> float: ...

def Segment(a: Any, b: Any) -> Shape: """The segment from a to b (local frame); a != b."""

class Shape:
    """A 2D geometry (immutable); made by proxima.d2.Circle, Polygon, Box, ..."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    def aabb(self: Shape, pose: Any = ...) -> tuple: """(min, max) corners of the placed shape's box."""
    @property
    def is_convex(self) -> bool: ...
    @property
    def type(self) -> str: ...

class ToiResult:
    """2D time of impact (world frame at toi)."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    @property
    def normal(self) -> numpy.ndarray: ...
    @property
    def point(self) -> numpy.ndarray: ...
    @property
    def status(self) -> CcdStatus: ...
    @property
    def t_lower(self) -> float: ...
    @property
    def t_upper(self) -> float: ...
    @property
    def toi(self) -> float: ...

def cast(a: Any, pose_a: Any, translation: Any, b: Any, pose_b: Any) -> ToiResult: """Where a, moved from pose_a along translation (t in [0, 1]), first meets b at rest."""

def collide(a: Any, pose_a: Any, b: Any, pose_b: Any, contact_distance: float = ...) -> Manifold: """The contact manifold (up to 2 points) of shapes touching, overlapping or within contact_distance."""

def contains(shape: Any, pose: Any, point: Any) -> bool: """True when the placed shape contains the point."""

def distance(a: Any, pose_a: Any, b: Any, pose_b: Any) -> DistanceResult: """Signed distance with witness points and the unit normal from A to B (world frame)."""

def intersect(a: Any, pose_a: Any, b: Any, pose_b: Any) -> bool: """True when the placed shapes touch or overlap."""

def raycast(shape: Any, pose: Any, origin: Any, direction: Any, max_t: float = ...) -> Optional[RayHit]: """The first hit with t in [0, max_t], or None."""

def toi(a: Any, start_a: Any, translation_a: Any, rotation_a: float, b: Any, start_b: Any, translation_b: Any = ..., rotation_b: float = ..., target_distance: float = ..., tolerance: float = ...) -> ToiResult: """Certified time of impact in [0, 1]: each shape moves from its start pose (x, y, angle) by a translation and a counter-clockwise turn (radians)."""
