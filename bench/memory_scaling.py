#!/usr/bin/env python3
"""How much a second thread adds to streaming through memory on this machine.

Each thread adds 1.0 to every element of its own float64 array, over and over (`np.add` with
`out=`, which releases the GIL), for several array sizes per thread: from one that stays in a
core's L2 cache to one far larger than any cache. It prints the bytes read and written per second
on one thread and on two, and the ratio.

A stage of the solver that streams through more data than the caches hold cannot run faster on
two threads than this ratio allows, whatever its partitioning; `bench/results/README.md` uses it
to explain the 2-thread speed-up of the `rain` scene.

    bench/.venv/bin/python bench/memory_scaling.py            # after bench/run.py has made the venv
    bench/.venv/bin/python bench/memory_scaling.py --out FILE  # also write the table (markdown)
"""

import argparse
import threading
import time

import numpy as np

from run import machine

SIZES_MB = [1, 4, 16, 64]
# Bytes moved per element and pass: one read and one write of 8 bytes.
BYTES_PER_ELEMENT = 16
# Total bytes each measurement streams per thread, so that every size runs about as long.
BYTES_PER_THREAD = 8e9


def stream(array, passes, barrier, times, index):
    barrier.wait()
    start = time.perf_counter()
    for _ in range(passes):
        np.add(array, 1.0, out=array)
    times[index] = time.perf_counter() - start


def bandwidth(size_mb, threads):
    """Bytes per second over all threads, best of three."""
    elements = size_mb * 1024 * 1024 // 8
    passes = max(1, int(BYTES_PER_THREAD / (elements * BYTES_PER_ELEMENT)))
    arrays = [np.zeros(elements) for _ in range(threads)]
    best = 0.0
    for _ in range(3):
        barrier = threading.Barrier(threads)
        times = [0.0] * threads
        workers = [
            threading.Thread(target=stream, args=(arrays[i], passes, barrier, times, i)) for i in range(threads)
        ]
        for w in workers:
            w.start()
        for w in workers:
            w.join()
        moved = threads * passes * elements * BYTES_PER_ELEMENT
        best = max(best, moved / max(times))
    return best


def machine_line():
    uname, cpu, cpus = machine()
    return f"{uname}; {cpu}; {cpus} CPUs"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default=None, help="write the table (markdown) here too")
    args = parser.parse_args()
    lines = [
        f"# Memory streaming, 1 and 2 threads ({time.strftime('%Y-%m-%d')})",
        "",
        f"Machine: {machine_line()}",
        "",
        "| array per thread | 1 thread, GB/s | 2 threads, GB/s | 2 / 1 |",
        "|---|---|---|---|",
    ]
    for size in SIZES_MB:
        one, two = bandwidth(size, 1), bandwidth(size, 2)
        lines.append(f"| {size} MB | {one / 1e9:.1f} | {two / 1e9:.1f} | {two / one:.2f} |")
        print(lines[-1], flush=True)
    report = "\n".join(lines) + "\n"
    if args.out:
        with open(args.out, "w") as f:
            f.write(report)
    else:
        print(report)


if __name__ == "__main__":
    main()
