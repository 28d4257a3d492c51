"""A pyramid of boxes (base 10, 55 boxes) settling on a ground box.

Prints the stepping speed and the largest drift of any box from where it was placed.

    python examples/python/pyramid.py [--seconds 5] [--base 10]
"""

import argparse
import time

import numpy as np

import tumble


def build(base, half=0.25, gap=0.01):
    w = tumble.World(gravity=(0, 0, -9.81), substeps=4)
    w.add_body(tumble.Box((20.0, 20.0, 0.5)), kind="static", position=(0, 0, -0.5), name="ground")
    for row in range(base):
        n = base - row
        for i in range(n):
            x = (i - (n - 1) / 2) * (2 * half + gap)
            z = half + row * 2 * half
            w.add_body(tumble.Box((half, half, half)), density=500.0, position=(x, 0.0, z), friction=0.8)
    return w


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--base", type=int, default=10)
    args = parser.parse_args()
    w = build(args.base)
    start = w.positions
    dt = 1.0 / 60.0
    steps = max(1, round(args.seconds / dt))
    t0 = time.perf_counter()
    w.step(dt, n=steps)
    elapsed = time.perf_counter() - t0
    drift = np.linalg.norm(w.positions - start, axis=1).max()
    print(f"pyramid of {len(w) - 1} boxes (base {args.base}), {steps} steps of {dt:.4f} s")
    print(f"{steps / elapsed:.0f} steps/s ({1e3 * elapsed / steps:.3f} ms/step)")
    print(f"largest drift: {1e3 * drift:.2f} mm")
    if not np.isfinite(drift) or drift > 0.25:
        raise SystemExit(f"the pyramid fell apart (drift {drift:.3f} m)")


if __name__ == "__main__":
    main()
