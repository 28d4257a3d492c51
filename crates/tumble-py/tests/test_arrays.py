"""The flat state arrays: shapes, dtypes, order, round trips, and writing them."""

import numpy as np
import pytest

import tumble


def make_world(n=4):
    w = tumble.World(gravity=(0, 0, 0))
    ids = []
    for i in range(n):
        q = np.array([0.1 * i, 0.2, -0.1, 1.0])
        ids.append(
            w.add_body(
                tumble.Box((0.1, 0.2, 0.3)),
                position=(i, 2.0 * i, -i),
                orientation=q / np.linalg.norm(q),
                linear_velocity=(i, 0, 1),
                angular_velocity=(0, i, 0),
                name=f"b{i}",
            )
        )
    return w, ids


ARRAYS = {"positions": 3, "orientations": 4, "linear_velocities": 3, "angular_velocities": 3}


@pytest.mark.parametrize("name,cols", ARRAYS.items())
def test_shapes_and_dtypes(name, cols):
    w, _ = make_world(5)
    a = getattr(w, name)
    assert isinstance(a, np.ndarray)
    assert a.shape == (5, cols) and a.dtype == np.float64
    assert a.flags["C_CONTIGUOUS"]
    empty = getattr(tumble.World(), name)
    assert empty.shape == (0, cols) and empty.dtype == np.float64


def test_rows_follow_body_ids_and_match_body_views():
    w, ids = make_world(4)
    assert w.body_ids == ids
    for i, b in enumerate(w.body_ids):
        body = w.body(b)
        np.testing.assert_array_equal(w.positions[i], body.position)
        np.testing.assert_array_equal(w.orientations[i], body.orientation)
        np.testing.assert_array_equal(w.linear_velocities[i], body.linear_velocity)
        np.testing.assert_array_equal(w.angular_velocities[i], body.angular_velocity)
    np.testing.assert_array_equal(w.positions[2], [2.0, 4.0, -2.0])
    # Removing a body: later rows move up; the next body reuses the freed slot.
    w.remove_body(ids[1])
    assert w.body_ids == [ids[0], ids[2], ids[3]]
    np.testing.assert_array_equal(w.positions[1], [2.0, 4.0, -2.0])
    new = w.add_body(tumble.Sphere(0.1), position=(9, 9, 9))
    assert new.index == ids[1].index and new.generation == ids[1].generation + 1
    assert w.body_ids == [ids[0], new, ids[2], ids[3]]
    np.testing.assert_array_equal(w.positions[1], [9, 9, 9])


@pytest.mark.parametrize("name", ARRAYS)
def test_round_trip(name):
    w, _ = make_world(3)
    before = getattr(w, name)
    setattr(w, name, before)
    np.testing.assert_allclose(getattr(w, name), before, rtol=1e-15, atol=1e-15)
    # A copy: changing the returned array does not change the world.
    before[:] = 123.0
    assert not np.any(getattr(w, name) == 123.0)


def test_setting_arrays_changes_the_world():
    w, ids = make_world(3)
    pos = np.arange(9, dtype=float).reshape(3, 3)
    w.positions = pos
    np.testing.assert_array_equal(w.positions, pos)
    np.testing.assert_array_equal(w.body(ids[2]).position, [6, 7, 8])

    q = np.array([[0, 0, 0, 1], [0, 0, 1, 0], [0.6, 0, 0, 0.8]], dtype=float)
    w.orientations = q
    np.testing.assert_allclose(w.orientations, q, atol=1e-15)
    np.testing.assert_allclose(w.positions, pos, atol=1e-15)  # poses keep their origin

    w.linear_velocities = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]  # lists and int dtypes are fine
    w.angular_velocities = np.zeros((3, 3), dtype=np.float32)
    w.step(0.5)
    np.testing.assert_allclose(w.positions, pos + 0.5 * np.eye(3), atol=1e-14)
    np.testing.assert_array_equal(w.angular_velocities, np.zeros((3, 3)))


def test_setting_one_body_through_its_view():
    w, ids = make_world(2)
    body = w.body(ids[0])
    body.position = (5, 6, 7)
    body.orientation = (0, 0, 0, 1)
    body.linear_velocity = np.array([1.0, 2.0, 3.0])
    body.angular_velocity = [0, 0, 1]
    np.testing.assert_array_equal(w.positions[0], [5, 6, 7])
    np.testing.assert_array_equal(w.orientations[0], [0, 0, 0, 1])
    np.testing.assert_array_equal(w.linear_velocities[0], [1, 2, 3])
    np.testing.assert_array_equal(w.angular_velocities[0], [0, 0, 1])
    w.set_pose(ids[1], (1, 1, 1), (0, 0, 0, 2.0))  # normalised, as the core does
    np.testing.assert_array_equal(w.orientations[1], [0, 0, 0, 1])


def test_static_bodies_keep_zero_velocity():
    w = tumble.World()
    s = w.add_body(kind="static", position=(0, 0, -1))
    d = w.add_body(tumble.Sphere(0.5))
    w.linear_velocities = [[1, 1, 1], [2, 2, 2]]
    np.testing.assert_array_equal(w.linear_velocities, [[0, 0, 0], [2, 2, 2]])
    assert w.body(s).kind == "static" and w.body(d).kind == "dynamic"
    assert w.find_body("") == s
