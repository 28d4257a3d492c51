"""Type stubs for tumble (the Rust extension tumble._tumble plus tumble.errors)."""

import os
from typing import Iterable, Literal, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

from .errors import StaleHandleError as StaleHandleError
from .errors import TumbleError as TumbleError
from .errors import TumbleValueError as TumbleValueError

__version__: str

_Vec3 = Union[Sequence[float], npt.NDArray[np.floating]]
"""Three numbers: a tuple, list or array."""
_Quat = Union[Sequence[float], npt.NDArray[np.floating]]
"""A quaternion (x, y, z, w)."""
_ArrayLike = npt.ArrayLike
_F64 = npt.NDArray[np.float64]
_BodyKind = Literal["dynamic", "static", "kinematic"]

@final
class BodyId:
    """Names a body in a World (slot index + generation). Stale once the body is removed."""

    @property
    def index(self) -> int: ...
    @property
    def generation(self) -> int: ...
    def __eq__(self, other: object, /) -> bool: ...
    def __lt__(self, other: "BodyId", /) -> bool: ...
    def __le__(self, other: "BodyId", /) -> bool: ...
    def __gt__(self, other: "BodyId", /) -> bool: ...
    def __ge__(self, other: "BodyId", /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class JointId:
    """Names a joint in a World (slot index + generation). Stale once the joint is removed."""

    @property
    def index(self) -> int: ...
    @property
    def generation(self) -> int: ...
    def __eq__(self, other: object, /) -> bool: ...
    def __lt__(self, other: "JointId", /) -> bool: ...
    def __le__(self, other: "JointId", /) -> bool: ...
    def __gt__(self, other: "JointId", /) -> bool: ...
    def __ge__(self, other: "JointId", /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class MassProperties:
    """Mass, centre of mass and inertia about the centre of mass, in the solid's own frame."""

    def __init__(
        self, mass: float, inertia: _ArrayLike, center_of_mass: Optional[_Vec3] = None, volume: float = 0.0
    ) -> None: ...
    @property
    def volume(self) -> float: ...
    @property
    def mass(self) -> float: ...
    @property
    def center_of_mass(self) -> _F64:
        """(3,)"""
    @property
    def inertia(self) -> _F64:
        """(3, 3), about the centre of mass."""
    @property
    def principal_moments(self) -> _F64:
        """(3,), ascending."""
    @property
    def principal_axes(self) -> _F64:
        """(3, 3), the axes as columns: inertia == axes @ diag(moments) @ axes.T."""
    def with_mass(self, mass: float) -> "MassProperties": ...

def mass_properties(vertices: _ArrayLike, triangles: _ArrayLike, density: float = 1.0) -> MassProperties:
    """Mass properties of a closed, outward-wound triangle mesh: vertices (N, 3), triangles (M, 3)."""

class Shape:
    """A shape in its own frame. Capsule, cylinder and cone lie along local Z."""

    @property
    def kind(
        self,
    ) -> Literal["sphere", "box", "capsule", "cylinder", "cone", "hull", "mesh", "compound", "plane", "heightfield"]: ...
    def mass_properties(self, density: float = 1000.0) -> MassProperties: ...

@final
class Sphere(Shape):
    def __init__(self, radius: float) -> None: ...
    @property
    def radius(self) -> float: ...

@final
class Box(Shape):
    def __init__(self, half_extents: _Vec3) -> None: ...
    @property
    def half_extents(self) -> _F64: ...

@final
class Capsule(Shape):
    def __init__(self, radius: float, half_height: float) -> None: ...
    @property
    def radius(self) -> float: ...
    @property
    def half_height(self) -> float: ...

@final
class Cylinder(Shape):
    def __init__(self, radius: float, half_height: float) -> None: ...
    @property
    def radius(self) -> float: ...
    @property
    def half_height(self) -> float: ...

@final
class Cone(Shape):
    """Base disc at z = -half_height, apex at z = +half_height."""

    def __init__(self, radius: float, half_height: float) -> None: ...
    @property
    def radius(self) -> float: ...
    @property
    def half_height(self) -> float: ...

@final
class TriMesh(Shape):
    """A closed, outward-wound triangle mesh."""

    def __init__(self, vertices: _ArrayLike, triangles: _ArrayLike) -> None: ...
    @property
    def vertices(self) -> _F64:
        """(N, 3)"""
    @property
    def triangles(self) -> npt.NDArray[np.uint32]:
        """(M, 3)"""

@final
class Compound(Shape):
    """Parts (shape, position) or (shape, position, orientation) in the compound's frame."""

    def __init__(self, parts: Iterable[Union[Tuple[Shape, _Vec3], Tuple[Shape, _Vec3, _Quat]]]) -> None: ...
    @property
    def parts(self) -> list[Tuple[Shape, _F64, _F64]]: ...

@final
class ConvexHull(Shape):
    """The convex hull of points (N, 3)."""

    def __init__(self, points: _ArrayLike) -> None: ...
    @property
    def vertices(self) -> _F64:
        """The extreme points, (V, 3)."""

class Plane(Shape):
    """The half-space ``normal · x <= offset`` (solid below the plane). Static bodies only."""

    def __init__(self, normal: _ArrayLike = (0.0, 0.0, 1.0), offset: float = 0.0) -> None: ...
    @property
    def normal(self) -> _F64:
        """The outward unit normal (x, y, z)."""
    @property
    def offset(self) -> float:
        """Signed distance of the surface from the origin along the normal, m."""

class HeightField(Shape):
    """Terrain from a (rows, cols) grid of heights, centred on the origin in X and Y; ``scale``
    is (column spacing, row spacing, height factor). Static bodies only."""

    def __init__(self, heights: _ArrayLike, scale: _ArrayLike = (1.0, 1.0, 1.0)) -> None: ...
    @property
    def heights(self) -> _F64:
        """The raw (unscaled) heights, (rows, cols)."""
    @property
    def scale(self) -> _F64:
        """(x spacing, y spacing, height factor)."""
    @property
    def rows(self) -> int: ...
    @property
    def cols(self) -> int: ...

@final
class RayHit:
    """Where a ray hit a body (world frame)."""

    @property
    def body(self) -> BodyId: ...
    @property
    def distance(self) -> float: ...
    @property
    def point(self) -> _F64: ...
    @property
    def normal(self) -> _F64: ...

_Pair = Union[Tuple[float, float], Sequence[float], npt.NDArray[np.floating]]
"""Two numbers: limits (lower, upper), motor (target_speed, max_force), spring (hertz, damping_ratio)."""

@final
class Body:
    """A live view of one body: reads the world on every access; setters change the world."""

    @property
    def id(self) -> BodyId: ...
    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> _BodyKind: ...
    @property
    def shape(self) -> Optional[Shape]: ...
    @property
    def position(self) -> _F64:
        """World position of the body frame's origin, (3,)."""
    @position.setter
    def position(self, value: _Vec3) -> None: ...
    @property
    def orientation(self) -> _F64:
        """(x, y, z, w)"""
    @orientation.setter
    def orientation(self, value: _Quat) -> None: ...
    @property
    def linear_velocity(self) -> _F64:
        """Velocity of the centre of mass, world frame."""
    @linear_velocity.setter
    def linear_velocity(self, value: _Vec3) -> None: ...
    @property
    def angular_velocity(self) -> _F64:
        """World frame."""
    @angular_velocity.setter
    def angular_velocity(self, value: _Vec3) -> None: ...
    @property
    def mass(self) -> float: ...
    @property
    def inverse_mass(self) -> float: ...
    @property
    def center_of_mass(self) -> _F64:
        """World frame."""
    @property
    def center_of_mass_local(self) -> _F64:
        """Body frame."""
    @property
    def inertia(self) -> _F64:
        """(3, 3) about the centre of mass, world axes."""
    @property
    def inverse_inertia(self) -> _F64: ...
    @property
    def principal_moments(self) -> _F64: ...
    @property
    def principal_orientation(self) -> _F64: ...
    @property
    def mass_properties(self) -> MassProperties:
        """In the body frame."""
    @property
    def force(self) -> _F64: ...
    @property
    def torque(self) -> _F64: ...
    @property
    def linear_damping(self) -> float: ...
    @property
    def angular_damping(self) -> float: ...
    @property
    def gravity_scale(self) -> float: ...
    @property
    def friction(self) -> float: ...
    @property
    def restitution(self) -> float: ...
    @property
    def is_sensor(self) -> bool: ...
    @property
    def bullet(self) -> bool: ...
    @bullet.setter
    def bullet(self, value: bool) -> None: ...
    @property
    def is_awake(self) -> bool: ...
    @property
    def kinetic_energy(self) -> float: ...
    @property
    def linear_momentum(self) -> _F64: ...
    @property
    def angular_momentum(self) -> _F64:
        """About the centre of mass."""

@final
class Joint:
    """A live view of one joint."""

    @property
    def id(self) -> JointId: ...
    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> Literal["ball", "hinge", "slider", "fixed", "distance"]: ...
    @property
    def body_a(self) -> BodyId: ...
    @property
    def body_b(self) -> BodyId: ...
    @property
    def is_broken(self) -> bool: ...
    @property
    def constraint_force(self) -> float: ...
    @property
    def constraint_torque(self) -> float: ...
    @property
    def anchor_a(self) -> _F64: ...
    @property
    def anchor_b(self) -> _F64: ...

@final
class World:
    """A rigid-body world.

    State arrays have one row per live body in body-slot order (row i is ``body_ids[i]``).
    Reading copies; assigning checks the whole array first, so a bad array changes nothing.
    """

    def __init__(self, gravity: Optional[_Vec3] = None, substeps: Optional[int] = None, sleep: bool = True) -> None: ...
    gravity: _F64
    substeps: int
    @property
    def time(self) -> float: ...
    @property
    def step_count(self) -> int: ...
    @property
    def body_count(self) -> int: ...
    @property
    def awake_body_count(self) -> int: ...
    @property
    def joint_count(self) -> int: ...
    @property
    def body_ids(self) -> list[BodyId]: ...
    @property
    def joint_ids(self) -> list[JointId]: ...
    def __len__(self) -> int: ...
    def add_body(
        self,
        shape: Optional[Shape] = None,
        *,
        density: float = 1000.0,
        mass: Optional[float] = None,
        mass_properties: Optional[MassProperties] = None,
        position: Optional[_Vec3] = None,
        orientation: Optional[_Quat] = None,
        linear_velocity: Optional[_Vec3] = None,
        angular_velocity: Optional[_Vec3] = None,
        kind: _BodyKind = "dynamic",
        name: str = "",
        linear_damping: float = 0.0,
        angular_damping: float = 0.0,
        gravity_scale: float = 1.0,
        allow_sleep: bool = True,
        friction: float = 0.6,
        restitution: float = 0.0,
        rolling_friction: float = 0.0,
        torsional_friction: float = 0.0,
        group: int = 1,
        mask: int = 0xFFFFFFFF,
        sensor: bool = False,
        bullet: bool = False,
    ) -> BodyId: ...
    def remove_body(self, body: BodyId) -> None: ...
    def body(self, body: BodyId) -> Body: ...
    def find_body(self, name: str) -> Optional[BodyId]: ...
    def set_pose(self, body: BodyId, position: _Vec3, orientation: _Quat) -> None: ...
    def wake_body(self, body: BodyId) -> None: ...
    def add_ball_joint(
        self,
        a: BodyId,
        b: BodyId,
        anchor: _Vec3,
        *,
        axis: Optional[_Vec3] = None,
        swing_limit: Optional[float] = None,
        twist_limits: Optional[_Pair] = None,
        name: str = "",
        break_force: Optional[float] = None,
        break_torque: Optional[float] = None,
        collide_connected: bool = False,
    ) -> JointId: ...
    def add_hinge_joint(
        self,
        a: BodyId,
        b: BodyId,
        anchor: _Vec3,
        axis: _Vec3,
        limits: Optional[_Pair] = None,
        motor: Optional[_Pair] = None,
        spring: Optional[_Pair] = None,
        *,
        spring_target: float = 0.0,
        name: str = "",
        break_force: Optional[float] = None,
        break_torque: Optional[float] = None,
        collide_connected: bool = False,
    ) -> JointId:
        """limits (rad), motor (target_speed rad/s, max_torque N·m), spring (hertz, damping_ratio)."""
    def add_slider_joint(
        self,
        a: BodyId,
        b: BodyId,
        anchor: _Vec3,
        axis: _Vec3,
        limits: Optional[_Pair] = None,
        motor: Optional[_Pair] = None,
        spring: Optional[_Pair] = None,
        *,
        spring_target: float = 0.0,
        name: str = "",
        break_force: Optional[float] = None,
        break_torque: Optional[float] = None,
        collide_connected: bool = False,
    ) -> JointId:
        """limits (m), motor (target_speed m/s, max_force N), spring (hertz, damping_ratio)."""
    def add_fixed_joint(
        self,
        a: BodyId,
        b: BodyId,
        anchor: _Vec3,
        *,
        name: str = "",
        break_force: Optional[float] = None,
        break_torque: Optional[float] = None,
        collide_connected: bool = False,
    ) -> JointId: ...
    def add_distance_joint(
        self,
        a: BodyId,
        b: BodyId,
        anchor_a: _Vec3,
        anchor_b: _Vec3,
        *,
        length: Optional[float] = None,
        min_length: float = 0.0,
        max_length: float = float("inf"),
        spring: Optional[_Pair] = None,
        name: str = "",
        break_force: Optional[float] = None,
        collide_connected: bool = False,
    ) -> JointId: ...
    def remove_joint(self, joint: JointId) -> None: ...
    def joint(self, joint: JointId) -> Joint: ...
    def apply_force(self, body: BodyId, force: _Vec3, point: Optional[_Vec3] = None) -> None: ...
    def apply_torque(self, body: BodyId, torque: _Vec3) -> None: ...
    def apply_impulse(self, body: BodyId, impulse: _Vec3, point: Optional[_Vec3] = None) -> None: ...
    def apply_angular_impulse(self, body: BodyId, angular_impulse: _Vec3) -> None: ...
    def point_velocity(self, body: BodyId, point: _Vec3) -> _F64: ...
    def contacts(self) -> npt.NDArray[np.void]:
        """One row per contact point: body_a, body_b (int64 slot indices), point (3,), normal (3,),
        separation, impulse (normal impulse of the last step, N·s), sensor (bool)."""
    @property
    def contact_count(self) -> int: ...
    def raycast(
        self,
        origin: _Vec3,
        direction: _Vec3,
        max_distance: float = float("inf"),
        *,
        include_sensors: bool = False,
        group: int = 0xFFFFFFFF,
        mask: int = 0xFFFFFFFF,
    ) -> Optional[RayHit]: ...
    def raycast_all(
        self,
        origin: _Vec3,
        direction: _Vec3,
        max_distance: float = float("inf"),
        *,
        include_sensors: bool = False,
        group: int = 0xFFFFFFFF,
        mask: int = 0xFFFFFFFF,
    ) -> list[RayHit]: ...
    def contact_begin_events(self) -> list[Tuple[BodyId, BodyId]]: ...
    def contact_end_events(self) -> list[Tuple[BodyId, BodyId]]: ...
    def sensor_begin_events(self) -> list[Tuple[BodyId, BodyId]]: ...
    def sensor_end_events(self) -> list[Tuple[BodyId, BodyId]]: ...
    @staticmethod
    def from_scene(path: Union[str, "os.PathLike[str]"]) -> "World":
        """A world built from a scene file (TOML)."""
    def point_acceleration(self, body: BodyId, point: _Vec3) -> _F64: ...
    def inverse_mass_matrix(self, body: BodyId, r1: _Vec3, r2: _Vec3) -> _F64: ...
    def kinetic_energy(self) -> float: ...
    def potential_energy(self) -> float: ...
    def linear_momentum(self) -> _F64: ...
    def angular_momentum(self, about: Optional[_Vec3] = None) -> _F64: ...
    def save(self) -> bytes:
        """The world's complete state; `World.load(data)` rebuilds a world with a bit-identical future."""
    @staticmethod
    def load(data: bytes) -> World:
        """A world rebuilt from `save()` bytes; damaged data raises TumbleValueError."""
    def state_hash(self) -> int:
        """A 64-bit fingerprint of the exact state."""
    def step(self, dt: float, n: int = 1) -> None:
        """Advances n steps of dt seconds with the GIL released."""
    positions: _F64
    """(N, 3) body-frame origins."""
    orientations: _F64
    """(N, 4) quaternions (x, y, z, w)."""
    linear_velocities: _F64
    """(N, 3) centre-of-mass velocities, world frame."""
    angular_velocities: _F64
    """(N, 3) world frame."""

def step_many(worlds: Iterable[World], dt: float, n: int = 1) -> None:
    """Steps every world n times in parallel on all cores, GIL released; same results as
    stepping them one by one."""

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
    "MassProperties",
    "mass_properties",
    "TumbleError",
    "TumbleValueError",
    "StaleHandleError",
]
