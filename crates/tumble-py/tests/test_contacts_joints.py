"""Contacts, ray casts, events, materials, convex hulls, every joint kind and scene files from
Python."""

import math
from pathlib import Path

import numpy as np
import pytest

import tumble

SCENES = Path(__file__).resolve().parents[3] / "scenes"
DT = 1.0 / 60.0


def resting_box_world():
    """A 1 m cube (1000 kg) resting on a static slab whose top is at z = 0."""
    w = tumble.World(substeps=4)
    ground = w.add_body(tumble.Box((2, 2, 0.5)), kind="static", position=(0, 0, -0.5), name="ground")
    box = w.add_body(tumble.Box((0.5, 0.5, 0.5)), density=1000.0, position=(0, 0, 0.5), name="box")
    return w, ground, box


def test_a_resting_box_has_four_contacts_carrying_its_weight():
    w, ground, box = resting_box_world()
    w.step(DT, n=60)
    c = w.contacts()
    assert c.dtype.names == ("body_a", "body_b", "point", "normal", "separation", "impulse", "sensor")
    assert c.shape == (4,)
    assert c["point"].shape == (4, 3) and c["body_a"].dtype == np.int64
    assert {int(c["body_a"][0]), int(c["body_b"][0])} == {ground.index, box.index}
    # The normal points from a to b; from the ground up to the box.
    up = np.where((c["body_a"] == ground.index)[:, None], 1.0, -1.0) * c["normal"]
    np.testing.assert_allclose(up, np.tile([0.0, 0.0, 1.0], (4, 1)), atol=1e-12)
    np.testing.assert_allclose(np.sort(np.abs(c["point"][:, :2]), axis=0), np.full((4, 2), 0.5), atol=1e-5)
    assert np.all(np.abs(c["separation"]) < 5e-3)
    assert not c["sensor"].any()
    # The normal impulses over one step hold the weight: sum = m g dt.
    assert c["impulse"].sum() == pytest.approx(1000.0 * 9.81 * DT, rel=1e-3)
    assert w.contact_count == 1


def test_no_contacts_is_an_empty_structured_array():
    w = tumble.World()
    c = w.contacts()
    assert c.shape == (0,) and "impulse" in c.dtype.names


def test_raycast_down_hits_the_ground_at_the_right_distance():
    w, ground, box = resting_box_world()
    hit = w.raycast((1.5, 0.0, 10.0), (0, 0, -1))
    assert isinstance(hit, tumble.RayHit)
    assert hit.body == ground
    assert hit.distance == pytest.approx(10.0, abs=1e-12)
    np.testing.assert_allclose(hit.point, (1.5, 0.0, 0.0), atol=1e-12)
    np.testing.assert_allclose(hit.normal, (0, 0, 1), atol=1e-12)
    top = w.raycast((0.0, 0.0, 10.0), (0, 0, -2.0), 100.0)
    assert top.body == box and top.distance == pytest.approx(9.0, abs=1e-9)
    assert w.raycast((0.0, 0.0, 10.0), (0, 0, 1)) is None
    assert w.raycast((0.0, 0.0, 10.0), (0, 0, -1), max_distance=5.0) is None
    assert [h.body for h in w.raycast_all((0.0, 0.0, 10.0), (0, 0, -1))] == [box, ground]
    with pytest.raises(tumble.TumbleValueError, match="direction"):
        w.raycast((0, 0, 0), (0, 0, 0))
    with pytest.raises(tumble.TumbleValueError, match="max_distance"):
        w.raycast((0, 0, 0), (0, 0, 1), -1.0)
    with pytest.raises(ValueError):
        w.raycast((0, 0), (0, 0, 1))


def test_sensors_are_skipped_by_rays_unless_asked_and_report_events():
    w = tumble.World()
    gate = w.add_body(tumble.Box((1, 1, 0.2)), kind="static", sensor=True)
    ball = w.add_body(tumble.Sphere(0.1), position=(0, 0, 1))
    assert w.body(gate).is_sensor
    assert w.raycast((0, 0, 5), (0, 0, -1)).body == ball
    w.set_pose(ball, (5, 0, 1), (0, 0, 0, 1))
    assert w.raycast((0, 0, 5), (0, 0, -1)) is None
    assert w.raycast((0, 0, 5), (0, 0, -1), include_sensors=True).body == gate
    w.set_pose(ball, (0, 0, 1), (0, 0, 0, 1))
    begins, ends = [], []
    for _ in range(90):
        w.step(DT)
        begins += w.sensor_begin_events()
        ends += w.sensor_end_events()
    assert begins == [(gate, ball)] and ends == [(gate, ball)]


def test_landing_gives_a_contact_begin_event():
    w = tumble.World()
    ground = w.add_body(tumble.Box((2, 2, 0.5)), kind="static", position=(0, 0, -0.5))
    ball = w.add_body(tumble.Sphere(0.1), position=(0, 0, 1))
    events = []
    for _ in range(90):
        w.step(DT)
        events += w.contact_begin_events()
    assert events == [(ground, ball)]


def test_material_keywords_reach_the_body_and_restitution_bounces():
    w = tumble.World()
    w.add_body(tumble.Box((2, 2, 0.5)), kind="static", position=(0, 0, -0.5), restitution=1.0)
    ball = w.add_body(tumble.Sphere(0.1), position=(0, 0, 1), restitution=0.8, friction=0.3)
    b = w.body(ball)
    assert (b.friction, b.restitution) == (0.3, 0.8)
    top_after_bounce = 0.0
    fell = False
    for _ in range(120):
        w.step(DT)
        vz = b.linear_velocity[2]
        fell = fell or vz < -3.0
        if fell and vz > 0:
            top_after_bounce = max(top_after_bounce, b.position[2])
    assert top_after_bounce > 0.4, "a restitution-1 floor bounces the ball back up"
    with pytest.raises(tumble.TumbleValueError, match="restitution"):
        w.add_body(tumble.Sphere(0.1), restitution=2.0)
    with pytest.raises(tumble.TumbleValueError, match="friction"):
        w.add_body(tumble.Sphere(0.1), friction=-1.0)


def test_convex_hull_shape():
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.1, 0.1, 0.1]], dtype=float)
    hull = tumble.ConvexHull(pts)
    assert hull.kind == "hull"
    assert hull.vertices.shape == (4, 3)
    assert hull.mass_properties(1.0).volume == pytest.approx(1.0 / 6.0, rel=1e-12)
    w = tumble.World()
    b = w.add_body(hull, density=1000.0)
    assert isinstance(w.body(b).shape, tumble.ConvexHull)
    with pytest.raises(tumble.TumbleValueError, match="convex hull"):
        tumble.ConvexHull([[0, 0, 0], [1, 0, 0], [2, 0, 0]])
    with pytest.raises(ValueError):
        tumble.ConvexHull([[0, 0], [1, 0]])


def pendulum(w, joint_adder):
    pivot = w.add_body(tumble.Box((0.1, 0.1, 0.1)), kind="static", position=(0, 0, 2))
    bob = w.add_body(tumble.Sphere(0.1), position=(1, 0, 2))
    return pivot, bob, joint_adder(pivot, bob)


def test_hinge_joint_with_limits_motor_and_spring():
    w = tumble.World(gravity=(0, 0, 0))
    pivot, bob, j = pendulum(
        w, lambda a, b: w.add_hinge_joint(a, b, (0, 0, 2), (0, 0, 1), motor=(1.0, 1000.0), name="hinge")
    )
    assert w.joint(j).kind == "hinge" and w.joint(j).name == "hinge"
    w.step(DT, n=120)
    # The motor turns the bob about Z at 1 rad/s: after ~2 s it has turned ~2 rad.
    p = w.body(bob).position
    assert p[2] == pytest.approx(2.0, abs=1e-3), "stays in the hinge plane"
    assert math.atan2(p[1], p[0]) == pytest.approx(2.0, abs=0.1)
    # Limits stop it (a moderate motor: a soft limit gives way to a huge one).
    w2 = tumble.World(gravity=(0, 0, 0))
    _, bob2, _ = pendulum(w2, lambda a, b: w2.add_hinge_joint(a, b, (0, 0, 2), (0, 0, 1), (-0.5, 0.5), (1.0, 20.0)))
    w2.step(DT, n=120)
    p2 = w2.body(bob2).position
    assert math.atan2(p2[1], p2[0]) == pytest.approx(0.5, abs=0.03)
    # A spring turns a bar hinged at its centre to the spring's target angle.
    w3 = tumble.World(gravity=(0, 0, 0))
    post = w3.add_body(tumble.Box((0.1, 0.1, 0.1)), kind="static", position=(0, 0, 0))
    bar = w3.add_body(tumble.Box((1.0, 0.1, 0.1)), position=(0, 0, 2))
    w3.add_hinge_joint(post, bar, (0, 0, 2), (0, 0, 1), spring=(1.0, 1.0), spring_target=0.3)
    w3.step(DT, n=240)
    q = w3.body(bar).orientation
    assert 2.0 * math.atan2(q[2], q[3]) == pytest.approx(0.3, abs=0.01)
    with pytest.raises(tumble.TumbleValueError, match="limits"):
        w.add_hinge_joint(pivot, bob, (0, 0, 2), (0, 0, 1), limits=(1.0, -1.0))
    with pytest.raises(ValueError, match="motor"):
        w.add_hinge_joint(pivot, bob, (0, 0, 2), (0, 0, 1), motor=(1.0,))


def test_slider_fixed_and_distance_joints():
    w = tumble.World()
    pivot, bob, slider = pendulum(w, lambda a, b: w.add_slider_joint(a, b, (1, 0, 2), (0, 0, 1), limits=(-0.5, 0.0)))
    w.step(DT, n=60)
    assert w.joint(slider).kind == "slider"
    np.testing.assert_allclose(w.body(bob).position, (1, 0, 1.5), atol=1e-2)  # slid down to the limit

    w = tumble.World()
    pivot, bob, fixed = pendulum(w, lambda a, b: w.add_fixed_joint(a, b, (0.5, 0, 2)))
    w.step(DT, n=60)
    assert w.joint(fixed).kind == "fixed"
    np.testing.assert_allclose(w.body(bob).position, (1, 0, 2), atol=1e-2)
    assert w.joint(fixed).constraint_force > 0

    w = tumble.World(gravity=(0, 0, 0))
    pivot, bob, rope = pendulum(
        w, lambda a, b: w.add_distance_joint(a, b, (0, 0, 2), (1, 0, 2), min_length=0.0, max_length=1.0, spring=(0.0, 0.0))
    )
    w.body(bob).linear_velocity = (3.0, 0.0, 0.0)
    w.step(DT, n=60)
    assert w.joint(rope).kind == "distance"
    assert np.linalg.norm(w.body(bob).position - (0, 0, 2)) <= 1.0 + 1e-2, "the rope holds"

    w = tumble.World(gravity=(0, 0, 0))
    pivot, bob, ball = pendulum(w, lambda a, b: w.add_ball_joint(a, b, (0, 0, 2), axis=(1, 0, 0), swing_limit=0.3))
    w.body(bob).linear_velocity = (0.0, 2.0, 0.0)
    w.step(DT, n=60)
    p = w.body(bob).position - (0, 0, 2)
    assert math.acos(p[0] / np.linalg.norm(p)) <= 0.3 + 0.03


def test_world_from_scene_builds_the_demo_and_the_playground():
    w = tumble.World.from_scene(SCENES / "demo.toml")
    handle = w.find_body("handle")
    assert handle is not None and w.body_count == 1
    np.testing.assert_allclose(w.gravity, (0, 0, 0))
    np.testing.assert_allclose(w.body(handle).angular_velocity, (0.1, 8.0, 0.1))
    p = tumble.World.from_scene(str(SCENES / "playground.toml"))
    assert p.body_count == 7 and p.joint_count == 1
    assert isinstance(p.body(p.find_body("pebble")).shape, tumble.ConvexHull)
    assert p.body(p.find_body("gate")).is_sensor
    with pytest.raises(FileNotFoundError):
        tumble.World.from_scene(SCENES / "no_such_scene.toml")


def test_scene_errors_name_file_and_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[[body]]\nname = "b"\nshape = { type = "sphere", radius = -1.0 }\n')
    with pytest.raises(tumble.TumbleValueError, match=r"bad.toml:3: .*radius must be > 0"):
        tumble.World.from_scene(bad)
