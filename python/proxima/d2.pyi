"""Type stubs of proxima (written by python/tools/make_stubs.py from the module; do not edit)."""

from typing import Any, Iterator, List, Optional, Tuple

import numpy


from typing import overload

def Box(hx: float, hy: float, radius: float = ...) -> Shape: """A box of half extents hx, hy centred on the origin."""

CONTACT_EVENT_DTYPE: numpy.dtype

def Capsule(a: Any, b: Any, radius: float) -> Shape: """Points within radius of the segment a-b (local frame)."""

class CcdMode:
    """Continuous detection of a world object."""
    Off: CcdMode
    Auto: CcdMode
    Bullet: CcdMode
    def __int__(self) -> int: ...
    @property
    def name(self) -> str: ...

def Chain(points: Any, loop: bool = ...) -> Shape: """One-sided segments through the points (the right side collides: the outside of a counter-clockwise loop)."""

def Circle(radius: float, center: Any = ...) -> Shape: """A disc of radius about center (local frame)."""

class CollisionFilter:
    """Which objects pair: (a.layer & b.mask) and (b.layer & a.mask) non-zero, and not the same non-zero group."""
    def __eq__(self: CollisionFilter, arg0: CollisionFilter) -> bool: ...
    def __init__(self: CollisionFilter, layer: int = ..., mask: int = ..., group: int = ...) -> None: ...
    @property
    def group(self) -> int: ...
    @property
    def layer(self) -> int: ...
    @property
    def mask(self) -> int: ...

class CollisionWorld:
    """The 2D collision world: objects by integer handle, a step that reports contacts, sensors and impacts, scene queries and snapshots. Lengths in the caller's units, poses (x, y, angle) local -> world."""
    def __contains__(self: CollisionWorld, arg0: int) -> bool: ...
    def __init__(self: CollisionWorld, broadphase: str = ..., contact_distance: float = ..., max_contacts: int = ..., sensors_sense_sensors: bool = ..., continuous: bool = ..., ccd_safety_factor: float = ..., ccd_tolerance: float = ...) -> None: ...
    def __len__(self: CollisionWorld) -> int: ...
    def add(self: CollisionWorld, shape: Any, pose: Any = ..., *, kind: ObjectKind = ..., filter: CollisionFilter = ..., sensor: bool = ..., ccd: CcdMode = ..., user_data: int = ...) -> int: """Adds an object at pose (x, y, angle); returns its handle (an int). A chain only as kind=ObjectKind.Static."""
    @property
    def events(self) -> dict: ...
    @staticmethod
    def load(snapshot: bytes) -> CollisionWorld: """A world from save()'s bytes; proxima.Error names what is wrong (field 'snapshot...')."""
    def manifolds(self: CollisionWorld) -> numpy.ndarray: """Every point of the touching pairs' manifolds, by pair then chain segment: an array of d2.MANIFOLD_POINT_DTYPE (a, b, part_a, part_b, normal, point_a, point_b, depth, feature_id)."""
    def move(self: CollisionWorld, object: int, pose: Any) -> None: """Sets the object's pose for the next step (its motion for CCD starts at the old one)."""
    def objects(self: CollisionWorld) -> numpy.ndarray: """Handles of every object, as a uint64 array (slot order)."""
    def overlap(self: CollisionWorld, shape: Any, pose: Any = ..., *, mask: int = ..., group: int = ..., ignore: Any = ...) -> List[int]: """Handles of the objects the placed shape touches or overlaps, ascending."""
    def pose(self: CollisionWorld, object: int) -> tuple: """The object's pose as (x, y, angle)."""
    def raycast(self: CollisionWorld, origin: Any, direction: Any, max_t: float = ..., *, mask: int = ..., group: int = ..., ignore: Any = ...) -> Optional[WorldRayHit]: """The first object hit within [0, max_t] (t in units of the direction's length): a d2.WorldRayHit or None."""
    def record(self: CollisionWorld, path: str, camera: Any = ...) -> None: """Records every following step to a 2D capture file (docs/capture-format.md, dimension 2: the objects in the plane z = 0; a step's dt is 1); read it with proxima.capture, draw it with proxima.render or proxima view. camera: a dict of position, target, up, fov_degrees, ortho_height."""
    def remove(self: CollisionWorld, object: int) -> None: """Removes the object (its touching pairs end at the next step)."""
    def save(self: CollisionWorld) -> bytes: """The world as a versioned binary snapshot (bytes)."""
    def set_filter(self: CollisionWorld, object: int, filter: CollisionFilter) -> None: """Replaces the object's filter."""
    def set_listener(self: CollisionWorld, listener: Any) -> None: """An object whose methods on_contact_begin, on_contact_persist, on_contact_end, on_sensor_enter, on_sensor_exit, on_impact (those it has) are called with each event during step(); None removes it."""
    def set_pair_excluded(self: CollisionWorld, a: int, b: int, excluded: bool = ...) -> None: """Never pair these two objects (or again allow it)."""
    def state_hash(self: CollisionWorld) -> int: """A hash of the whole state: equal hashes mean equal worlds."""
    def step(self: CollisionWorld, *, threads: int = ...) -> None: """Runs the broad and narrow phases and continuous detection, then calls the listener. threads: 0 every hardware thread; the GIL is released."""
    def stop_recording(self: CollisionWorld) -> None: """Closes the capture file."""
    def teleport(self: CollisionWorld, object: int, pose: Any) -> None: """Sets the pose with no motion (continuous detection sweeps nothing)."""

class ContactEvent:
    """A pair that began, kept or stopped touching (a < b)."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    @property
    def a(self) -> int: ...
    @property
    def b(self) -> int: ...
    @property
    def user_data_a(self) -> int: ...
    @property
    def user_data_b(self) -> int: ...

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

IMPACT_EVENT_DTYPE: numpy.dtype

class ImpactEvent:
    """The first impact of a fast 2D object during a step (world frame)."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    @property
    def a(self) -> int: ...
    @property
    def b(self) -> int: ...
    @property
    def normal(self) -> numpy.ndarray: ...
    @property
    def part_b(self) -> int: ...
    @property
    def point(self) -> numpy.ndarray: ...
    @property
    def toi(self) -> float: ...
    @property
    def user_data_a(self) -> int: ...
    @property
    def user_data_b(self) -> int: ...

MANIFOLD_POINT_DTYPE: numpy.dtype

class Manifold:
    """Up to 2 contact points sharing one normal (world frame)."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    def __len__(self: Manifold) -> int: ...
    @property
    def normal(self) -> numpy.ndarray: ...
    @property
    def points(self) -> list: ...

class ObjectKind:
    """How an object takes part in the step."""
    Static: ObjectKind
    Moving: ObjectKind
    def __int__(self) -> int: ...
    @property
    def name(self) -> str: ...

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

SENSOR_EVENT_DTYPE: numpy.dtype

def Segment(a: Any, b: Any) -> Shape: """The segment from a to b (local frame); a != b."""

class SensorEvent:
    """An object that entered or left a sensor."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    @property
    def other(self) -> int: ...
    @property
    def sensor(self) -> int: ...
    @property
    def user_data_other(self) -> int: ...
    @property
    def user_data_sensor(self) -> int: ...

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

class WorldRayHit:
    """The object a ray hits first in a 2D world (world frame)."""
    def __init__(*args: Any, **kwargs: Any) -> Any: ...
    @property
    def normal(self) -> numpy.ndarray: ...
    @property
    def object(self) -> int: ...
    @property
    def part(self) -> int: ...
    @property
    def point(self) -> numpy.ndarray: ...
    @property
    def t(self) -> float: ...

def cast(a: Any, pose_a: Any, translation: Any, b: Any, pose_b: Any) -> ToiResult: """Where a, moved from pose_a along translation (t in [0, 1]), first meets b at rest."""

def collide(a: Any, pose_a: Any, b: Any, pose_b: Any, contact_distance: float = ...) -> Manifold: """The contact manifold (up to 2 points) of shapes touching, overlapping or within contact_distance."""

def contains(shape: Any, pose: Any, point: Any) -> bool: """True when the placed shape contains the point."""

def distance(a: Any, pose_a: Any, b: Any, pose_b: Any) -> DistanceResult: """Signed distance with witness points and the unit normal from A to B (world frame)."""

def intersect(a: Any, pose_a: Any, b: Any, pose_b: Any) -> bool: """True when the placed shapes touch or overlap."""

def raycast(shape: Any, pose: Any, origin: Any, direction: Any, max_t: float = ...) -> Optional[RayHit]: """The first hit with t in [0, max_t], or None."""

def toi(a: Any, start_a: Any, translation_a: Any, rotation_a: float, b: Any, start_b: Any, translation_b: Any = ..., rotation_b: float = ..., target_distance: float = ..., tolerance: float = ...) -> ToiResult: """Certified time of impact in [0, 1]: each shape moves from its start pose (x, y, angle) by a translation and a counter-clockwise turn (radians)."""
