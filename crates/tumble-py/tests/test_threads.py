"""Stepping releases the GIL; step_many steps worlds in parallel with the same results."""

import threading
import time

import numpy as np
import pytest

import tumble


def chain_world(links=40, seed=0):
    """A hanging chain of boxes on ball joints: enough work per step to measure."""
    rng = np.random.default_rng(seed)
    w = tumble.World(sleep=False)
    prev = w.add_body(kind="static")
    for i in range(links):
        b = w.add_body(
            tumble.Box((0.05, 0.05, 0.1)),
            position=(0.0, 0.0, -0.2 * i - 0.1),
            angular_velocity=rng.normal(size=3),
            linear_velocity=rng.normal(size=3),
        )
        w.add_ball_joint(prev, b, (0.0, 0.0, -0.2 * i))
        prev = b
    return w


def test_step_releases_the_gil():
    w = chain_world()
    # Size the run to take a noticeable time.
    t0 = time.perf_counter()
    w.step(1 / 240, n=20)
    per_step = (time.perf_counter() - t0) / 20
    n = max(20, int(0.5 / per_step))

    count = 0
    stop = threading.Event()
    started = threading.Event()

    def spin():
        nonlocal count
        started.set()
        while not stop.is_set():
            count += 1

    thread = threading.Thread(target=spin)
    thread.start()
    started.wait()
    before = count
    t0 = time.perf_counter()
    w.step(1 / 240, n=n)  # the main thread is inside Rust for the whole call
    elapsed = time.perf_counter() - t0
    during = count - before
    stop.set()
    thread.join()
    assert elapsed > 0.2
    # With the GIL held, the other thread could not run a single iteration during the call;
    # released, it spins freely (millions of iterations per second).
    assert during > 10_000, (during, elapsed)


def test_step_many_matches_sequential_stepping():
    parallel = [chain_world(10, seed=s) for s in range(6)]
    sequential = [chain_world(10, seed=s) for s in range(6)]
    tumble.step_many(parallel, 1 / 240, n=200)
    for w in sequential:
        w.step(1 / 240, n=200)
    for p, s in zip(parallel, sequential):
        for name in ("positions", "orientations", "linear_velocities", "angular_velocities"):
            np.testing.assert_array_equal(getattr(p, name), getattr(s, name))
        assert p.time == s.time and p.step_count == s.step_count == 200
    # Any iterable of worlds; empty is fine.
    tumble.step_many(iter(parallel[:2]), 1 / 240)
    tumble.step_many([], 1 / 240)


def test_step_many_rejects_duplicates_and_non_worlds():
    w = chain_world(3)
    before = w.positions
    with pytest.raises(tumble.TumbleValueError, match=r"worlds\[1\] appears twice"):
        tumble.step_many([w, w], 1 / 60)
    with pytest.raises(TypeError, match=r"worlds\[1\] is not a tumble.World"):
        tumble.step_many([w, "world"], 1 / 60)
    np.testing.assert_array_equal(w.positions, before)
    tumble.step_many([w], 1 / 60, n=2)  # still usable: the borrows were released
    assert w.step_count == 2


def test_touching_a_stepping_world_from_another_thread_raises():
    w = chain_world()
    errors = []

    def run():
        w.step(1 / 240, n=3000)

    thread = threading.Thread(target=run)
    thread.start()
    while thread.is_alive():
        try:
            w.positions
        except RuntimeError as e:  # borrowed by the stepping thread: an error, never a race
            errors.append(e)
            break
        time.sleep(0.001)
    thread.join()
    assert errors, "the step finished before it could be observed"
    assert w.step_count == 3000
    assert w.positions.shape == (41, 3)
