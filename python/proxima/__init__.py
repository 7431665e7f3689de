"""Proxima: collision detection for games, simulation and robotics.

Shapes (proxima.Sphere, proxima.Box, proxima.TriangleMesh, ...), pair queries
(intersect, distance, collide, raycast), continuous detection (toi, cast, safe_step),
bounding volumes, batched queries on numpy arrays, the broad phases, the collision world
and the 2D module (proxima.d2). Lengths are in the caller's units; poses are
proxima.Transform or 7 numbers (px, py, pz, qx, qy, qz, qw); errors raise proxima.Error
(a ValueError) whose `field` names the argument at fault.
"""

from ._proxima import *  # noqa: F401,F403
from ._proxima import DOUBLE_PRECISION, Error, __doc__ as _native_doc  # noqa: F401

from . import capture  # noqa: E402,F401  (reading capture files)

__version__ = "0.1.0"
