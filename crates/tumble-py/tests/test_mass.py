"""Shapes and mass properties."""

import numpy as np
import pytest

import tumble

CUBE_VERTICES = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float
)
# Outward-wound (counter-clockwise seen from outside).
CUBE_TRIANGLES = np.array(
    [
        [0, 2, 1], [0, 3, 2],  # bottom z = 0
        [4, 5, 6], [4, 6, 7],  # top z = 1
        [0, 1, 5], [0, 5, 4],  # y = 0
        [2, 3, 7], [2, 7, 6],  # y = 1
        [1, 2, 6], [1, 6, 5],  # x = 1
        [0, 4, 7], [0, 7, 3],  # x = 0
    ]
)


def test_unit_cube_mesh():
    mp = tumble.mass_properties(CUBE_VERTICES, CUBE_TRIANGLES, density=3.0)
    assert mp.volume == pytest.approx(1.0, rel=1e-14)
    assert mp.mass == pytest.approx(3.0, rel=1e-14)
    np.testing.assert_allclose(mp.center_of_mass, [0.5, 0.5, 0.5], rtol=1e-14)
    np.testing.assert_allclose(mp.inertia, np.eye(3) * 3.0 / 6.0, atol=1e-14)
    np.testing.assert_allclose(mp.principal_moments, [0.5, 0.5, 0.5], rtol=1e-13)
    axes = mp.principal_axes
    np.testing.assert_allclose(axes @ axes.T, np.eye(3), atol=1e-14)
    assert mp.center_of_mass.shape == (3,) and mp.inertia.shape == (3, 3)
    # Default density 1; lists work as well as arrays.
    assert tumble.mass_properties(CUBE_VERTICES.tolist(), CUBE_TRIANGLES.tolist()).mass == pytest.approx(1.0)


def test_bad_meshes_raise_the_core_message():
    with pytest.raises(tumble.TumbleValueError, match="mesh is open"):
        tumble.mass_properties(CUBE_VERTICES, CUBE_TRIANGLES[:-1])
    with pytest.raises(ValueError, match="inside out"):
        tumble.mass_properties(CUBE_VERTICES, CUBE_TRIANGLES[:, ::-1])
    with pytest.raises(ValueError, match="refers to vertex 8"):
        tumble.mass_properties(CUBE_VERTICES, np.where(CUBE_TRIANGLES == 7, 8, CUBE_TRIANGLES))
    with pytest.raises(ValueError, match=r"triangles\[0\]\[1\] must be a non-negative whole"):
        tumble.mass_properties(CUBE_VERTICES, [[0, 1.5, 2]])
    with pytest.raises(ValueError, match="shape"):
        tumble.mass_properties(CUBE_VERTICES[:, :2], CUBE_TRIANGLES)
    with pytest.raises(ValueError, match="density must be finite and > 0, got -1"):
        tumble.mass_properties(CUBE_VERTICES, CUBE_TRIANGLES, density=-1.0)


def test_primitive_shapes():
    box = tumble.Box((0.5, 1.0, 1.5))
    assert isinstance(box, tumble.Shape) and box.kind == "box"
    np.testing.assert_array_equal(box.half_extents, [0.5, 1.0, 1.5])
    assert box.mass_properties(density=2.0).mass == pytest.approx(2.0 * 1 * 2 * 3)
    s = tumble.Sphere(2.0)
    assert s.radius == 2.0
    assert s.mass_properties(1.0).volume == pytest.approx(4 / 3 * np.pi * 8)
    for cls, kind in [(tumble.Capsule, "capsule"), (tumble.Cylinder, "cylinder"), (tumble.Cone, "cone")]:
        shape = cls(0.5, 1.0)
        assert (shape.kind, shape.radius, shape.half_height) == (kind, 0.5, 1.0)
    cyl = tumble.Cylinder(0.5, 1.0).mass_properties(1.0)
    assert cyl.volume == pytest.approx(np.pi * 0.25 * 2.0)
    with pytest.raises(tumble.TumbleValueError, match="sphere radius must be finite and > 0, got -1"):
        tumble.Sphere(-1.0)
    with pytest.raises(ValueError, match="box half extent y"):
        tumble.Box((1.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="half_extents must have shape"):
        tumble.Box((1.0, 1.0))


def test_trimesh_and_compound_bodies():
    mesh = tumble.TriMesh(CUBE_VERTICES, CUBE_TRIANGLES)
    assert mesh.vertices.shape == (8, 3) and mesh.triangles.shape == (12, 3)
    w = tumble.World()
    b = w.add_body(mesh, density=10.0)
    body = w.body(b)
    assert body.mass == pytest.approx(10.0)
    np.testing.assert_allclose(body.center_of_mass_local, [0.5, 0.5, 0.5])
    assert body.shape == mesh and isinstance(body.shape, tumble.TriMesh)

    half = tumble.Box((0.5, 0.5, 0.5))
    dumbbell = tumble.Compound([(half, (-1, 0, 0)), (half, (1, 0, 0), (0, 0, 0, 1))])
    parts = dumbbell.parts
    assert len(parts) == 2 and isinstance(parts[0][0], tumble.Box)
    np.testing.assert_array_equal(parts[1][1], [1, 0, 0])
    mp = dumbbell.mass_properties(1.0)
    assert mp.mass == pytest.approx(2.0)
    # Each cube: 1/6 about its centre, + m d² = 1 off the y and z axes.
    np.testing.assert_allclose(np.diag(mp.inertia), [2 / 6, 2 / 6 + 2, 2 / 6 + 2])
    with pytest.raises(ValueError, match="compound has no parts"):
        tumble.Compound([])
    with pytest.raises(ValueError, match=r"parts\[0\] must be"):
        tumble.Compound([(half,)])
    with pytest.raises(ValueError, match="unit quaternion"):
        tumble.Compound([(half, (0, 0, 0), (0, 0, 0, 2))])


def test_body_mass_options():
    w = tumble.World()
    a = w.add_body(tumble.Box((0.5, 0.5, 0.5)), density=1000.0)
    b = w.add_body(tumble.Box((0.5, 0.5, 0.5)), mass=3.0)
    c = w.add_body(mass_properties=tumble.MassProperties(2.0, np.diag([1.0, 2.0, 3.0]), center_of_mass=(0, 0, 1)))
    assert w.body(a).mass == pytest.approx(1000.0)
    assert w.body(b).mass == pytest.approx(3.0)
    assert w.body(b).inverse_mass == pytest.approx(1 / 3)
    np.testing.assert_allclose(w.body(c).principal_moments, [1.0, 2.0, 3.0])
    np.testing.assert_allclose(w.body(c).center_of_mass, [0, 0, 1])
    np.testing.assert_allclose(w.body(c).position, [0, 0, 0])
    assert w.body(c).mass_properties.mass == 2.0
