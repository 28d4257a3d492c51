"""The Dzhanibekov effect: Tumble's demo T-handle spinning about its intermediate axis.

Builds the demo scene, steps it for 20 s and plots the angular velocity in the body frame to
out/handle_omega.png (needs Matplotlib: `pip install matplotlib`).

    python examples/python/tumbling_handle.py [--seconds 20] [--out out/handle_omega.png]
"""

import argparse
import os
import sys

import numpy as np

import tumble

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def rotation(q):
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--out", default=os.path.join("out", "handle_omega.png"))
    args = parser.parse_args()
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("tumbling_handle.py needs Matplotlib for its plot: pip install matplotlib")

    w = tumble.World.from_scene(os.path.join(ROOT, "scenes", "demo.toml"))
    handle = w.find_body("handle")
    dt = 1.0 / 240.0
    times, omegas = [], []
    while w.time < args.seconds - 1e-9:
        w.step(dt)
        body = w.body(handle)
        times.append(w.time)
        omegas.append(rotation(body.orientation).T @ body.angular_velocity)
    omegas = np.array(omegas)
    flips = np.nonzero(np.diff(np.sign(omegas[:, 1])) != 0)[0]
    print(f"{len(times)} steps, ω_y changed sign {len(flips)} times at t = "
          + ", ".join(f"{times[i]:.2f}" for i in flips) + " s")

    fig, ax = plt.subplots(figsize=(9, 4))
    for k, label in enumerate(("ω_x", "ω_y", "ω_z")):
        ax.plot(times, omegas[:, k], label=label)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("ω, body frame (rad/s)")
    ax.set_title("Tumbling T-handle (Dzhanibekov effect)")
    ax.legend()
    ax.grid(True, alpha=0.3)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=120, bbox_inches="tight")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
