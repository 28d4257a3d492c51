#!/usr/bin/env python3
"""Tumble's speed-up from one thread to two, measured in alternating rounds.

Each round runs `tumble bench SCENE --runs 1 --threads 1` and then `--threads 2` for every scene
and setting below (the matched settings of `run.py`'s table and the engine defaults), so that the
machine's drift over minutes falls on both thread counts alike. It prints, per scene and setting,
the median steps/s on each thread count, the speed-up of the medians and the range of the
per-round speed-ups, and checks that both thread counts gave the same quality numbers and the
same final state hash (the results are bit-identical for any thread count).

Each round also runs two one-thread copies of the same bench at once: their summed steps/s over
the one-thread rate is what this machine gives two independent copies of the work, the ceiling
for any two-thread speed-up here (on a machine whose two cores share a cache, memory bandwidth or
a physical core, it is under 2).

    python3 bench/speedup.py                 # after `cargo build --release`
    python3 bench/speedup.py --rounds 7 --out bench/results/DATE-speedup-2-threads-….md
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

from run import MATCHED, TABLE_STEPS, TUMBLE, cpu_ticks, machine, stolen_share

SCENES = ["large_pyramid", "rain", "pyramid", "ragdolls"]


def bench_command(scene, settings, threads):
    """One timed run of the scene at the table's step count, printed as JSON."""
    steps = str(TABLE_STEPS[scene])
    return [TUMBLE, "bench", scene, "--steps", steps, "--runs", "1", "--threads", str(threads), *settings, "--json"]


def rate(scene, settings, threads):
    out = subprocess.run(bench_command(scene, settings, threads), capture_output=True, text=True, check=True)
    result = json.loads(out.stdout)
    # The final state's hash with the quality numbers: the two thread counts must agree on both.
    return result["steps_per_second"], (result["metrics"], result["state_hash"])


def copies_rate(scene, settings):
    """Steps/s summed over two one-thread copies of the bench run at once."""
    procs = [subprocess.Popen(bench_command(scene, settings, 1), stdout=subprocess.PIPE, text=True) for _ in range(2)]
    outs = [p.communicate()[0] for p in procs]
    if any(p.returncode != 0 for p in procs):
        sys.exit(f"{scene}: a copy failed")
    return sum(json.loads(out)["steps_per_second"] for out in outs)


def steal_cell(shares):
    if not shares:
        return "n/a"
    return f"{100 * statistics.median(shares):.0f}% ({100 * max(shares):.0f}%)"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--out", help="also write the table (markdown) here")
    args = parser.parse_args()
    # --out is a path from where the script was called; the runs go from the repository's root.
    out = os.path.abspath(args.out) if args.out else None
    os.chdir(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    cases = [(scene, "matched", MATCHED[scene]) for scene in SCENES]
    cases += [(scene, "default", []) for scene in SCENES if scene in ("large_pyramid", "rain")]
    rates = {(scene, name): ([], [], []) for scene, name, _ in cases}
    stolen = {(scene, name): [] for scene, name, _ in cases}
    for r in range(args.rounds):
        print(f"round {r + 1} of {args.rounds}", file=sys.stderr, flush=True)
        for scene, name, settings in cases:
            one, metrics_one = rate(scene, settings, 1)
            before = cpu_ticks()
            two, metrics_two = rate(scene, settings, 2)
            steal = stolen_share(before, cpu_ticks())
            if steal is not None:
                stolen[(scene, name)].append(steal)
            if metrics_one != metrics_two:
                sys.exit(f"{scene} ({name}): one thread gave {metrics_one}, two gave {metrics_two}")
            rates[(scene, name)][0].append(one)
            rates[(scene, name)][1].append(two)
            rates[(scene, name)][2].append(copies_rate(scene, settings) / one)

    uname, cpu, cores = machine()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    lines = [
        f"date: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}",
        f"machine: {uname}",
        f"cpu: {cpu} ({cores} logical cores)",
        "",
        f"{args.rounds} alternating rounds of `tumble bench SCENE --steps N --runs 1 --threads 1` and "
        f"`--threads 2` (`bench/speedup.py`; matched settings as in `bench/run.py`, steps as in the "
        f"peers table), build {commit}. Both thread counts gave the same quality numbers and final state hash in every round. "
        "The ceiling is two one-thread copies run at once: their summed steps/s over the one-thread rate of the round. "
        "Stolen: the share of the machine's CPU time the hypervisor gave to other guests during the two-thread runs "
        "(`/proc/stat`); a thread that loses its core holds up the other wherever it has taken work, so rows with much "
        "stolen time say more about the host than about Tumble.",
        "",
        "| scene | settings | 1 thread (median steps/s) | 2 threads | speed-up (of medians) | per-round range | "
        "ceiling: two copies (median, range) | stolen during 2-thread runs (median, max) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for scene, name, _ in cases:
        one, two, copies = rates[(scene, name)]
        ratios = [b / a for a, b in zip(one, two)]
        m1, m2 = statistics.median(one), statistics.median(two)
        lines.append(
            f"| {scene} | {name} | {m1:.1f} | {m2:.1f} | {m2 / m1:.2f} | {min(ratios):.2f}–{max(ratios):.2f} | "
            f"{statistics.median(copies):.2f} ({min(copies):.2f}–{max(copies):.2f}) | {steal_cell(stolen[(scene, name)])} |"
        )
    text = "\n".join(lines) + "\n"
    print(text)
    if out:
        with open(out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
