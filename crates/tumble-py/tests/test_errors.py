"""Bad input raises TumbleError subclasses with the core's message and leaves the world as it was."""

import numpy as np
import pytest

import tumble


def snapshot(w):
    return [w.positions, w.orientations, w.linear_velocities, w.angular_velocities, w.body_count, w.time]


def assert_unchanged(w, snap):
    after = snapshot(w)
    for a, b in zip(snap[:4], after[:4]):
        np.testing.assert_array_equal(a, b)
    assert snap[4:] == after[4:]


@pytest.fixture
def world():
    w = tumble.World()
    w.add_body(tumble.Box((0.5, 0.5, 0.5)), position=(0, 0, 1), name="a")
    w.add_body(tumble.Sphere(0.5), position=(2, 0, 1), linear_velocity=(1, 0, 0), name="b")
    return w


def test_exception_hierarchy():
    assert issubclass(tumble.TumbleValueError, tumble.TumbleError)
    assert issubclass(tumble.TumbleValueError, ValueError)
    assert issubclass(tumble.StaleHandleError, tumble.TumbleError)
    assert issubclass(tumble.StaleHandleError, LookupError)


def test_nan_position(world):
    snap = snapshot(world)
    with pytest.raises(tumble.TumbleValueError, match=r'body "box": position must be finite, got \[NaN'):
        world.add_body(tumble.Box((0.5, 0.5, 0.5)), position=(np.nan, 0, 0), name="box")
    assert_unchanged(world, snap)


def test_negative_density(world):
    snap = snapshot(world)
    with pytest.raises(ValueError, match='body "c": density must be finite and > 0, got -5') as e:
        world.add_body(tumble.Box((0.5, 0.5, 0.5)), density=-5.0, name="c")
    assert isinstance(e.value, tumble.TumbleError)
    assert_unchanged(world, snap)


def test_other_bad_bodies(world):
    snap = snapshot(world)
    with pytest.raises(ValueError, match="orientation must be a unit quaternion"):
        world.add_body(tumble.Sphere(1.0), orientation=(0, 0, 0, 2))
    with pytest.raises(ValueError, match="a dynamic body needs a shape or mass_properties"):
        world.add_body()
    with pytest.raises(ValueError, match='kind must be "dynamic", "static" or "kinematic", got "wobbly"'):
        world.add_body(tumble.Sphere(1.0), kind="wobbly")
    with pytest.raises(ValueError, match="mass must be finite and > 0, got 0"):
        world.add_body(tumble.Sphere(1.0), mass=0.0)
    with pytest.raises(ValueError, match="position must have shape"):
        world.add_body(tumble.Sphere(1.0), position=(1, 2))
    with pytest.raises(ValueError, match="position must be an array of numbers"):
        world.add_body(tumble.Sphere(1.0), position=("a", "b", "c"))
    # Unknown settings are not accepted (and never silently ignored).
    with pytest.raises(TypeError):
        world.add_body(tumble.Sphere(1.0), colour=0.5)
    with pytest.raises(TypeError):
        world.add_body("not a shape")
    assert_unchanged(world, snap)


def test_stale_body_handle(world):
    b = world.add_body(tumble.Sphere(0.1), name="gone")
    view = world.body(b)
    world.remove_body(b)
    snap = snapshot(world)
    message = r"BodyId\(2v0\) does not name a body in this world"
    with pytest.raises(tumble.StaleHandleError, match=message):
        world.body(b)
    with pytest.raises(LookupError, match=message):
        view.position
    with pytest.raises(tumble.StaleHandleError):
        view.position = (0, 0, 0)
    with pytest.raises(tumble.StaleHandleError):
        world.apply_force(b, (1, 0, 0))
    with pytest.raises(tumble.StaleHandleError):
        world.remove_body(b)
    # The slot is reused, but the old handle stays stale.
    new = world.add_body(tumble.Sphere(0.1))
    assert new.index == b.index and new != b
    with pytest.raises(tumble.StaleHandleError):
        world.point_velocity(b, (0, 0, 0))
    assert "stale" in repr(view)
    world.remove_body(new)
    assert_unchanged(world, snap)


@pytest.mark.parametrize(
    "name,bad,match",
    [
        ("positions", np.zeros((3, 3)), r"positions must have shape \(2, 3\), got shape \[3, 3\]"),
        ("positions", np.zeros(6), r"positions must have shape \(2, 3\)"),
        ("orientations", np.zeros((2, 3)), r"orientations must have shape \(2, 4\)"),
        ("linear_velocities", [[0, 0, 0], [0, np.nan, 0]], r"linear_velocities\[1\] must be finite"),
        ("angular_velocities", [[np.inf, 0, 0], [0, 0, 0]], r"angular_velocities\[0\] must be finite"),
        ("positions", [[1, 2, 3], [4, 5, np.nan]], r"positions\[1\] must be finite"),
        ("orientations", [[0, 0, 0, 1], [0, 0, 0, 0.5]], r"orientations\[1\] must be a unit quaternion"),
        ("positions", "abc", r"positions must be an array of numbers"),
        ("positions", None, r"positions must have shape"),
    ],
)
def test_bad_arrays_leave_the_world_unchanged(world, name, bad, match):
    snap = snapshot(world)
    with pytest.raises(tumble.TumbleValueError, match=match):
        setattr(world, name, bad)
    assert_unchanged(world, snap)


def test_bad_steps_and_settings(world):
    snap = snapshot(world)
    with pytest.raises(ValueError, match="time step must be finite and > 0, got -0.1"):
        world.step(-0.1, n=10)
    with pytest.raises(ValueError, match="time step must be finite and > 0, got NaN"):
        tumble.step_many([world], float("nan"))
    with pytest.raises(ValueError, match="gravity must be finite"):
        world.gravity = (0, 0, np.nan)
    with pytest.raises(ValueError, match="substeps must be between 1 and 1000, got 0"):
        world.substeps = 0
    with pytest.raises(ValueError, match="substeps must be between 1 and 1000, got 0"):
        tumble.World(substeps=0)
    with pytest.raises(ValueError, match="force must be finite"):
        world.apply_force(world.body_ids[0], (np.nan, 0, 0))
    assert_unchanged(world, snap)
    assert world.substeps == 8
    np.testing.assert_array_equal(world.body(world.body_ids[0]).force, [0, 0, 0])


def test_bad_joints(world):
    a, b = world.body_ids
    with pytest.raises(ValueError, match="body_a and body_b are the same body"):
        world.add_ball_joint(a, a, (0, 0, 0))
    with pytest.raises(ValueError, match="anchor must be finite"):
        world.add_ball_joint(a, b, (0, np.inf, 0))
    with pytest.raises(ValueError, match="break_force must be finite and > 0"):
        world.add_ball_joint(a, b, (0, 0, 0), break_force=-1.0)
    assert world.joint_count == 0
    j = world.add_ball_joint(a, b, (1, 0, 1))
    world.remove_joint(j)
    with pytest.raises(tumble.StaleHandleError, match=r"JointId\(0v0\) does not name a joint"):
        world.joint(j)
