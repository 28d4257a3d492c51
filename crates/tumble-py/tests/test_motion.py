"""Physics through the Python API: free fall (closed form) and torque-free tumbling (F2)."""

import numpy as np
import pytest

import tumble


def test_free_fall_matches_closed_form():
    g = np.array([0.0, 0.0, -9.81])
    w = tumble.World(gravity=g, substeps=4)
    x0 = np.array([1.0, -2.0, 3.0])
    v0 = np.array([4.0, 1.5, 20.0])
    b = w.add_body(tumble.Box((0.1, 0.2, 0.3)), density=500.0, position=x0, linear_velocity=v0)
    dt, steps = 1.0 / 60.0, 120
    h = dt / w.substeps
    for k in range(1, 4):
        w.step(dt, n=steps)
        n = k * steps * w.substeps
        t = n * h
        # Semi-implicit Euler over the substeps, summed exactly.
        x_discrete = x0 + n * h * v0 + h * h * g * n * (n + 1) / 2
        v_discrete = v0 + n * h * g
        np.testing.assert_allclose(w.body(b).center_of_mass, x_discrete, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(w.body(b).linear_velocity, v_discrete, rtol=1e-12, atol=1e-12)
        # The continuous closed form, within the scheme's O(h) offset ½|g| h t.
        x_exact = x0 + v0 * t + 0.5 * g * t * t
        err = np.linalg.norm(w.positions[0] - x_exact)
        assert err <= 0.5 * 9.81 * h * t * (1 + 1e-9)
        assert w.time == pytest.approx(t, rel=1e-12)


def test_f2_torque_free_tumbling_conserves_angular_momentum():
    """VALIDATION F2: I = (1, 2, 3), ω₀ ≈ (0.01, 5, 0.01) about the unstable middle axis."""
    w = tumble.World(gravity=(0, 0, 0), sleep=False)
    q = np.array([0.1, -0.2, 0.3, 0.9])
    q /= np.linalg.norm(q)
    mp = tumble.MassProperties(mass=1.0, inertia=(1.0, 2.0, 3.0))
    b = w.add_body(mass_properties=mp, orientation=q)
    # ω₀ in body axes, rotated into the world: set through the flat array.
    body = w.body(b)
    R = np.array(
        [
            [1 - 2 * (q[1] ** 2 + q[2] ** 2), 2 * (q[0] * q[1] - q[2] * q[3]), 2 * (q[0] * q[2] + q[1] * q[3])],
            [2 * (q[0] * q[1] + q[2] * q[3]), 1 - 2 * (q[0] ** 2 + q[2] ** 2), 2 * (q[1] * q[2] - q[0] * q[3])],
            [2 * (q[0] * q[2] - q[1] * q[3]), 2 * (q[1] * q[2] + q[0] * q[3]), 1 - 2 * (q[0] ** 2 + q[1] ** 2)],
        ]
    )
    w.angular_velocities = (R @ np.array([0.01, 5.0, 0.01]))[None, :]
    np.testing.assert_allclose(body.inertia, R @ np.diag([1.0, 2.0, 3.0]) @ R.T, atol=1e-14)

    L0 = w.angular_momentum()
    E0 = w.kinetic_energy()
    dt = 1.0 / 240.0
    worst_L, worst_E = 0.0, 0.0
    omega_body_y = []
    for _ in range(60):  # 30 s, sampled every 0.5 s
        w.step(dt, n=120)
        worst_L = max(worst_L, np.linalg.norm(w.angular_momentum() - L0) / np.linalg.norm(L0))
        worst_E = max(worst_E, abs(w.kinetic_energy() - E0) / E0)
        Rb = _rotation(w.orientations[0])
        omega_body_y.append((Rb.T @ w.angular_velocities[0])[1])
    assert worst_L < 1e-10, worst_L  # VALIDATION.md F2: constant to 1e-10 relative
    assert worst_E < 1e-4, worst_E  # bounded below 1e-4 relative
    # The intermediate-axis (Dzhanibekov) flip happens: ω_y changes sign.
    assert min(omega_body_y) < -4.0 < 4.0 < max(omega_body_y)


def _rotation(q):
    x, y, z, s = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * s), 2 * (x * z + y * s)],
            [2 * (x * y + z * s), 1 - 2 * (x * x + z * z), 2 * (y * z - x * s)],
            [2 * (x * z - y * s), 2 * (y * z + x * s), 1 - 2 * (x * x + y * y)],
        ]
    )


def test_impulse_and_inverse_mass_matrix_agree():
    w = tumble.World(gravity=(0, 0, 0))
    q = np.array([0.2, 0.1, -0.3, 0.9])
    q /= np.linalg.norm(q)
    b = w.add_body(tumble.Box((0.3, 0.2, 0.1)), mass=2.0, position=(1, 2, 3), orientation=q)
    com = w.body(b).center_of_mass
    r1, r2 = np.array([0.1, -0.2, 0.05]), np.array([-0.3, 0.1, 0.2])
    j = np.array([0.5, -1.0, 2.0])
    K = w.inverse_mass_matrix(b, r1, r2)
    assert K.shape == (3, 3) and K.dtype == np.float64
    before = w.point_velocity(b, com + r2)
    w.apply_impulse(b, j, point=com + r1)
    after = w.point_velocity(b, com + r2)
    np.testing.assert_allclose(after - before, K @ j, atol=1e-13)
    np.testing.assert_allclose(w.linear_momentum(), j, atol=1e-13)
    # Angular momentum about the origin: r × p + I ω, from the impulse at com + r1.
    np.testing.assert_allclose(w.angular_momentum(), np.cross(com + r1, j), atol=1e-12)
    np.testing.assert_allclose(
        w.angular_momentum(about=com), np.cross(r1, j), atol=1e-12
    )


def test_forces_act_for_one_step():
    w = tumble.World(gravity=(0, 0, 0), substeps=1)
    b = w.add_body(tumble.Sphere(0.5), mass=2.0)
    w.apply_force(b, (4.0, 0, 0))
    np.testing.assert_array_equal(w.body(b).force, [4.0, 0, 0])
    w.step(0.5)
    np.testing.assert_allclose(w.body(b).linear_velocity, [1.0, 0, 0])
    np.testing.assert_array_equal(w.body(b).force, [0, 0, 0])
    w.step(0.5)
    np.testing.assert_allclose(w.body(b).linear_velocity, [1.0, 0, 0])
    w.apply_torque(b, (0, 0, 1.0))
    np.testing.assert_array_equal(w.body(b).torque, [0, 0, 1.0])
    assert w.kinetic_energy() == pytest.approx(1.0)


def test_ball_joint_pendulum_keeps_its_anchor():
    w = tumble.World()
    ground = w.add_body(kind="static", name="ground")
    bob = w.add_body(tumble.Sphere(0.1), mass=1.0, position=(1.0, 0, 0), name="bob")
    j = w.add_ball_joint(ground, bob, (0, 0, 0), name="pivot")
    joint = w.joint(j)
    assert (joint.kind, joint.name, joint.body_a, joint.body_b) == ("ball", "pivot", ground, bob)
    for _ in range(120):
        w.step(1 / 240)
        assert np.linalg.norm(w.body(bob).position) == pytest.approx(1.0, abs=1e-3)
    np.testing.assert_allclose(joint.anchor_a, joint.anchor_b, atol=1e-3)
    assert w.body(bob).position[2] < -0.1  # it swings down
    w.remove_body(bob)
    with pytest.raises(tumble.StaleHandleError):
        joint.kind
    assert w.joint_count == 0
