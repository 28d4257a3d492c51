"""Tumble: a 3D rigid-body dynamics engine.

Conventions: float64 everywhere, SI units, right-handed with **Z up** (default gravity
(0, 0, -9.81)), quaternions as **(x, y, z, w)**.

    import tumble
    w = tumble.World(gravity=(0, 0, -9.81), substeps=8)
    b = w.add_body(tumble.Box((0.5, 0.5, 0.5)), density=1000.0, position=(0, 0, 1))
    w.step(1 / 60, n=60)          # releases the GIL while stepping
    w.positions                   # (N, 3) float64, one row per body in body-slot order

State arrays (``positions`` (N, 3), ``orientations`` (N, 4), ``linear_velocities`` (N, 3),
``angular_velocities`` (N, 3)) have one row per live body in **body-slot order**: row ``i`` is the
body ``w.body_ids[i]``. Bodies take slots in the order they are added; removing a body frees its
slot (later rows move up) and the next body added reuses the most recently freed slot. Reading an
array returns a copy; assigning one checks the whole array (shape, finite values, unit
quaternions) before any body changes, so a bad array never half-writes a world.

Errors are :class:`TumbleError`; bad values are also :class:`ValueError`
(:class:`TumbleValueError`) and stale handles also :class:`LookupError` (:class:`StaleHandleError`).
The message is the engine's own.
"""

from .errors import StaleHandleError, TumbleError, TumbleValueError
from ._tumble import (
    Body,
    BodyId,
    Box,
    Capsule,
    Compound,
    Cone,
    ConvexHull,
    Cylinder,
    HeightField,
    Joint,
    JointId,
    MassProperties,
    Plane,
    RayHit,
    Shape,
    Sphere,
    TriMesh,
    World,
    mass_properties,
    step_many,
)

try:
    from importlib.metadata import version as _version

    __version__ = _version("tumble")
except Exception:  # pragma: no cover - running from a source tree without metadata
    __version__ = "0.0.0"

__all__ = [
    "World",
    "step_many",
    "Body",
    "BodyId",
    "Joint",
    "JointId",
    "Shape",
    "Sphere",
    "Box",
    "Capsule",
    "Cylinder",
    "Cone",
    "TriMesh",
    "Compound",
    "ConvexHull",
    "Plane",
    "HeightField",
    "RayHit",
    "MassProperties",
    "mass_properties",
    "TumbleError",
    "TumbleValueError",
    "StaleHandleError",
]
