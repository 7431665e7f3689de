"""proxima.d2: the 2D module (shapes, pair queries, rays, time of impact; poses are
(x, y, angle in radians)). The compiled part lives in proxima._proxima.d2."""

from ._proxima.d2 import *  # noqa: F401,F403
