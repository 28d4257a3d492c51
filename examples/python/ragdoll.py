"""A ragdoll of 11 capsules and boxes dropped on a static box.

Hips, shoulders, waist and neck are ball joints with swing (cone) and twist limits; knees and
elbows are hinges with limits. Prints whether every joint held together (anchors within 3 cm).

    python examples/python/ragdoll.py [--seconds 4]
"""

import argparse
import math

import numpy as np

import tumble


def build(drop=1.0):
    w = tumble.World(gravity=(0, 0, -9.81), substeps=8)
    w.add_body(tumble.Box((2.0, 2.0, 0.25)), kind="static", position=(0, 0, -0.25), name="table")
    z0 = drop  # feet height
    parts = {}

    def part(name, shape, x, z, density=1000.0):
        parts[name] = w.add_body(shape, density=density, position=(x, 0.0, z0 + z), name=name, friction=0.7)
        return parts[name]

    part("pelvis", tumble.Box((0.15, 0.10, 0.08)), 0.0, 1.00)
    part("torso", tumble.Box((0.17, 0.10, 0.20)), 0.0, 1.28)
    part("head", tumble.Capsule(0.10, 0.03), 0.0, 1.61)
    for side, sx in (("left", 1.0), ("right", -1.0)):
        part(f"{side}_thigh", tumble.Capsule(0.07, 0.16), 0.09 * sx, 0.69)
        part(f"{side}_shin", tumble.Capsule(0.06, 0.16), 0.09 * sx, 0.23)
        part(f"{side}_upper_arm", tumble.Capsule(0.05, 0.11), 0.25 * sx, 1.27)
        part(f"{side}_forearm", tumble.Capsule(0.045, 0.11), 0.25 * sx, 0.93)

    up = (0.0, 0.0, 1.0)
    side_axis = (1.0, 0.0, 0.0)

    def ball(a, b, x, z, swing, twist):
        w.add_ball_joint(parts[a], parts[b], (x, 0.0, z0 + z), axis=up, swing_limit=swing,
                         twist_limits=(-twist, twist), name=f"{a}-{b}")

    def hinge(a, b, x, z, limits):
        w.add_hinge_joint(parts[a], parts[b], (x, 0.0, z0 + z), side_axis, limits=limits, name=f"{a}-{b}")

    ball("pelvis", "torso", 0.0, 1.08, 0.5, 0.4)
    ball("torso", "head", 0.0, 1.50, 0.6, 0.8)
    for side, sx in (("left", 1.0), ("right", -1.0)):
        ball("pelvis", f"{side}_thigh", 0.09 * sx, 0.92, 1.2, 0.5)
        hinge(f"{side}_thigh", f"{side}_shin", 0.09 * sx, 0.46, (-2.4, 0.0))
        ball("torso", f"{side}_upper_arm", 0.25 * sx, 1.44, 1.5, 0.8)
        hinge(f"{side}_upper_arm", f"{side}_forearm", 0.25 * sx, 1.10, (0.0, 2.5))

    # A small push so it topples instead of landing on its feet.
    torso = w.body(parts["torso"])
    torso.angular_velocity = (1.5, 0.5, 0.0)
    return w


def worst_gap(w):
    gaps = [np.linalg.norm(w.joint(j).anchor_a - w.joint(j).anchor_b) for j in w.joint_ids]
    return max(gaps)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=4.0)
    args = parser.parse_args()
    w = build()
    dt = 1.0 / 120.0
    worst = 0.0
    for _ in range(max(1, round(args.seconds / dt))):
        w.step(dt)
        worst = max(worst, worst_gap(w))
    lowest = float(w.positions[1:, 2].min())
    print(f"ragdoll: {len(w) - 1} bodies, {w.joint_count} joints, {args.seconds:g} s simulated")
    print(f"largest joint separation: {1e3 * worst:.1f} mm; lowest body centre z = {lowest:.3f} m")
    connected = math.isfinite(worst) and worst < 0.03
    print("stays connected: " + ("yes" if connected else "NO"))
    if not connected:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
