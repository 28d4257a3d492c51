"""Python overhead: the same 1,000-box scene stepped from Python and from Rust, and
`tumble.step_many` of two worlds against stepping them one after the other.

    python bench/python_overhead.py [--steps 120]

The Rust side is `crates/tumble/examples/falling_boxes.rs` (built here with
`cargo build --release -p tumble --example falling_boxes`); both sides build the identical
scene, which the matching final state hashes confirm. Timings are wall clock on whatever else
the machine is doing: expect noise on a shared machine.
"""

import argparse
import os
import platform
import subprocess
import time

# NumPy's OpenBLAS keeps its own worker threads spinning after any BLAS call; on a 2-core
# machine they take a core from `step_many` (measured: 1.36x instead of 1.81x on two free-motion
# worlds). Quiet them before NumPy is imported; a user's own setting wins.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import tumble  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DT = 1.0 / 60.0


def build():
    """The scene of falling_boxes.rs: 10 × 10 × 10 boxes above a static ground."""
    w = tumble.World()
    w.add_body(tumble.Box((20.0, 20.0, 0.5)), kind="static", position=(0, 0, -0.5))
    box = tumble.Box((0.2, 0.2, 0.2))
    for k in range(10):
        for j in range(10):
            for i in range(10):
                w.add_body(box, position=((i - 4.5) * 0.5, (j - 4.5) * 0.5, 0.5 + k * 0.5))
    return w


def machine():
    model = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"nproc {os.cpu_count()}, {model}, Python {platform.python_version()}, tumble {tumble.__version__}"


def rust_side(steps):
    subprocess.run(["cargo", "build", "--release", "--quiet", "-p", "tumble", "--example", "falling_boxes"],
                   cwd=ROOT, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    exe = os.path.join(target, "release", "examples", "falling_boxes")
    out = subprocess.run([exe], env={**os.environ, "STEPS": str(steps)}, capture_output=True, text=True,
                         check=True).stdout
    fields = dict(line.split(" ", 1) for line in out.splitlines() if " " in line)
    return float(fields["seconds_per_step"]), int(fields["state_hash"], 16)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=120)
    args = parser.parse_args()
    steps = args.steps
    print(machine())
    print(f"scene: 1,000 boxes falling onto a ground, {steps} steps of 1/60 s")

    w = build()
    t0 = time.perf_counter()
    for _ in range(steps):
        w.step(DT)
    py_loop = (time.perf_counter() - t0) / steps
    py_hash = w.state_hash()

    w = build()
    t0 = time.perf_counter()
    w.step(DT, n=steps)
    py_n = (time.perf_counter() - t0) / steps

    rust, rust_hash = rust_side(steps)
    same = "identical" if rust_hash == py_hash else "DIFFERENT"
    print(f"Rust                   {1e3 * rust:8.3f} ms/step")
    print(f"Python, step() loop    {1e3 * py_loop:8.3f} ms/step   ratio {py_loop / rust:.3f}")
    print(f"Python, step(n=...)    {1e3 * py_n:8.3f} ms/step   ratio {py_n / rust:.3f}")
    print(f"final state hashes Rust vs Python: {same}")

    a, b = build(), build()
    t0 = time.perf_counter()
    a.step(DT, n=steps)
    b.step(DT, n=steps)
    sequential = time.perf_counter() - t0
    c, d = build(), build()
    t0 = time.perf_counter()
    tumble.step_many([c, d], DT, n=steps)
    parallel = time.perf_counter() - t0
    same = a.state_hash() == c.state_hash() == b.state_hash() == d.state_hash()
    print(f"2 worlds one by one    {sequential:8.3f} s")
    print(f"2 worlds step_many     {parallel:8.3f} s   speed-up {sequential / parallel:.2f}x"
          f"   results {'identical' if same else 'DIFFERENT'}")


if __name__ == "__main__":
    main()
