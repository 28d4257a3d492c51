"""Plane and HeightField: construction, round trip through a body, resting contact, bad input."""

import math

import numpy as np
import pytest

import tumble


def test_plane_round_trips_and_normalises():
    p = tumble.Plane((0, 0, 2.0), 0.5)
    assert p.kind == "plane"
    np.testing.assert_allclose(p.normal, (0, 0, 1))
    assert p.offset == 0.5
    w = tumble.World()
    b = w.add_body(p, kind="static")
    back = w.body(b).shape
    assert isinstance(back, tumble.Plane)
    assert back == p


def test_heightfield_round_trips():
    h = np.arange(12.0).reshape(3, 4) * 0.01
    hf = tumble.HeightField(h, (0.5, 0.25, 2.0))
    assert hf.kind == "heightfield"
    assert (hf.rows, hf.cols) == (3, 4)
    np.testing.assert_array_equal(hf.heights, h)
    np.testing.assert_array_equal(hf.scale, (0.5, 0.25, 2.0))
    w = tumble.World()
    b = w.add_body(hf, kind="static")
    back = w.body(b).shape
    assert isinstance(back, tumble.HeightField)
    assert back == hf


def test_ball_comes_to_rest_on_a_plane():
    r = 0.25
    w = tumble.World(gravity=(0, 0, -9.81))
    w.add_body(tumble.Plane((0, 0, 1), 0.0), kind="static")
    b = w.add_body(tumble.Sphere(r), density=1000.0, position=(0, 0, 1.0))
    w.step(1 / 60, n=240)
    z = w.body(b).position[2]
    assert abs(z - r) < 2e-3, z
    assert np.linalg.norm(w.body(b).linear_velocity) < 0.05


def test_sphere_rests_on_a_heightfield():
    r = 0.3
    rows, cols = 21, 21
    y, x = np.mgrid[0:rows, 0:cols]
    # Bumpy terrain with a flat 1.5 m × 1.5 m patch at height 0.1 m in the middle.
    heights = 0.1 + 0.05 * np.sin(0.9 * x) * np.cos(0.7 * y)
    heights[7:14, 7:14] = 0.1
    w = tumble.World(gravity=(0, 0, -9.81))
    w.add_body(tumble.HeightField(heights, (0.25, 0.25, 1.0)), kind="static")
    b = w.add_body(tumble.Sphere(r), density=1000.0, position=(0.1, 0.05, 1.0))
    w.step(1 / 60, n=240)
    body = w.body(b)
    assert np.linalg.norm(body.linear_velocity) < 0.05
    z = body.position[2]
    assert math.isfinite(z)
    assert abs(z - (0.1 + r)) < 2e-3, z  # resting on the patch, not sunk into it
    assert np.linalg.norm(body.position[:2] - (0.1, 0.05)) < 0.01  # and it did not roll away


def test_bad_planes_and_heightfields_raise_value_errors():
    with pytest.raises(ValueError):
        tumble.Plane((0, 0, 0), 0.0)
    with pytest.raises(tumble.TumbleValueError):
        tumble.Plane((0, 0, 1), float("nan"))
    with pytest.raises(ValueError):
        tumble.Plane((0, float("nan"), 1), 0.0)
    with pytest.raises(ValueError):
        tumble.HeightField([[0.0, 1.0], [2.0]], (1, 1, 1))  # ragged
    with pytest.raises(tumble.TumbleValueError):
        tumble.HeightField([[0.0, float("nan")], [0.0, 0.0]], (1, 1, 1))
    with pytest.raises(ValueError):
        tumble.HeightField([[0.0, 1.0], [2.0, 3.0]], (1, -1, 1))
    with pytest.raises(ValueError):
        tumble.HeightField([[0.0, 1.0]], (1, 1, 1))  # one row is too small
    with pytest.raises(ValueError):
        tumble.HeightField([0.0, 1.0, 2.0], (1, 1, 1))  # not 2-D


def test_plane_on_a_dynamic_body_is_refused():
    w = tumble.World()
    with pytest.raises(ValueError):
        w.add_body(tumble.Plane(), density=1000.0)
