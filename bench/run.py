#!/usr/bin/env python3
"""Tumble and its peers side by side on the shared benchmark scenes (BENCHMARKS.md).

    python3 bench/run.py                      # the table: every scene, 5 runs per engine
    python3 bench/run.py --scenes pyramid,chain --runs 7
    python3 bench/run.py --scaling            # Tumble's steps/s against body count
    python3 bench/run.py --skip-install       # reuse bench/.venv and the built binaries

It installs what it runs: a virtualenv in bench/.venv with PyBullet and MuJoCo from PyPI, the
Rapier peer (bench/rapier, its own cargo project) and the `tumble` binary, both built --release.
Each scene is exported once by `tumble bench SCENE --export` and every engine builds it from that
file, so all of them run the same bodies, shapes, joints and settings.

Runs alternate engine by engine: round 1 runs each engine once, then round 2, and so on, so a
change in the machine's load falls on every engine alike. The table gives the median steps/s of
the rounds, the ratio Tumble/peer, the quality result and the settings. Python peers are timed
over one plain loop of step calls; their quality result comes from one more, untimed run.
An engine whose run takes longer than --timeout seconds is reported as not finishing.
"""

import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BENCH = os.path.join(ROOT, "bench")
VENV = os.path.join(BENCH, ".venv")
WORK = os.path.join(ROOT, "target", "bench")
TUMBLE = os.path.join(ROOT, "target", "release", "tumble")
RAPIER = os.path.join(BENCH, "rapier", "target", "release", "tumble-bench-rapier")
ENGINES = ["tumble", "tumble-matched", "rapier", "pybullet", "mujoco"]

# "tumble-matched": Tumble at the fewest substeps whose quality result still beats the best peer's
# on that scene (measured 2026-12-01 with --substeps 1..8 and a few --solver settings; the table
# prints both quality results, so the match can be checked). The "tumble" rows run the engine
# defaults (8 substeps).
MATCHED = {
    # 2 substeps of two solve passes and no relax pass, with stiffer damping, hold the pyramid
    # within 1.5 cm, well within Rapier's 2.7 cm, and stay there for damping ratios 12-22
    # (1.26-2.64 cm, measured 2026-12-06; 2.26 cm after 3,000 steps, where 4 substeps of one solve
    # and one relax at ratio 22 had reached 3.48 cm). They cost four passes a step where that
    # took eight. Without the relax pass a pass's bias velocity is not taken back before the next
    # substep; both settings leave the pyramid rocking at about 1 cm/s (the defaults: 10 um/s).
    # At 3 substeps of one solve and one relax the drift is chaotic and sits around Rapier's
    # (ratios 16-30: 2.0-3.4 cm, median 3.0), and with one solve pass and no relax the pyramid
    # falls (3 substeps: 0.3-0.6 m).
    "pyramid": [
        "--substeps",
        "2",
        "--solver",
        "solve_iterations=2",
        "--solver",
        "relax_iterations=0",
        "--solver",
        "contact_damping_ratio=16",
    ],
    # Without the relax pass: 0.54 m at 5 substeps, against Rapier's 0.50 m (2026-12-07).
    "large_pyramid": ["--substeps", "5"],
    # Without the relax pass the rain's deepest overlap, over nine damping ratios within 1e-7 to
    # 1e-4 of 10, is 0.74-1.03 cm (median 0.95), about Rapier's 0.99 cm; with it 0.59-0.83 cm.
    "rain": ["--substeps", "3"],
    # The joint trees' position projection holds the chain within 0.14 mm at one substep.
    "chain": ["--substeps", "1"],
    # Without the relax pass: 7.8 cm, against Rapier's 6.9 cm (2026-12-07). At 3 substeps the
    # largest joint separation is chaotic: over eleven damping ratios within 1e-6 of 10 it spans
    # 4.8-6.4 cm, median 5.7, the default 6.37 (2026-12-07); Rapier 6.86 cm. With the lanes'
    # sines and cosines (new last bits wherever bodies turn) the default gives 6.72 cm, and eleven
    # ratios within 1e-6 of 10 span 5.29-6.96 cm (median 6.28). These are the ragdolls solved
    # row by row (joint_tree_limits=false): every ragdoll joint has limits, and by default the
    # joint trees now take limit rows in (docs/joint-tree.md, "Limits in the tree"), which holds
    # every joint within 0.01 cm at 2 to 8 substeps but costs more than Rapier's quality needs (2
    # substeps: 88 steps/s, against 161 row by row at 3; 2026-12-08). Row by row, more passes
    # help (3 substeps of 2 solve passes: 3.3 cm; 4 substeps: 2.8 cm); 2 substeps of 3 solve
    # passes and no relax pass span only 5.98-6.55 cm over the same ratios, but ran 0.74x as
    # fast (the narrow phase of a livelier pile: 370 against 226 ms over 120 steps); 2 substeps
    # of 2 solve passes and a relax pass, 6.49-6.55 cm, 0.81x.
    "ragdolls": ["--substeps", "3", "--solver", "joint_tree_limits=false"],
    # 3 substeps of one solve pass and no relax pass: six passes a step where 4 substeps of a
    # solve and a relax took twelve (the substeps' time halves; the step at 120 steps, where the
    # narrow phase of the landing hulls is most of it, 1.05-1.2x). The deepest contact at the last
    # step alone is chaotic: over 18 settings within 1e-7 to 1e-4 of the defaults (damping
    # ratio, steady_load_time, ...) it spanned 2.2-10.7 cm, median 3.2 (2026-12-07); so the scene
    # is judged by that depth averaged over the steps. At 120 steps (2026-12-07, after the GJK
    # closest features for pairs apart): this setting 9.9 cm, 2 substeps without a relax pass
    # 11.1, with one 10.6, the defaults 7.6; Rapier 10.8, PyBullet 11.3, MuJoCo 13.9.
    "convex_pile": ["--substeps", "3", "--solver", "relax_iterations=0"],
    "tumbling": ["--substeps", "1"],
}

# Steps per run in the table: the scene's own count where the whole table stays under ~20 minutes
# on a 2-core machine, fewer for the big scenes (their quality result is then after these steps).
TABLE_STEPS = {
    "pyramid": 1000,
    "large_pyramid": 20,
    "rain": 120,
    "chain": 1000,
    "ragdolls": 120,
    "convex_pile": 120,
    "tumbling": 200,
}
SCALING = [("pyramid", [10, 20, 40, 100], 100), ("rain", [500, 2000, 8000], 100)]


def sh(cmd, **kw):
    print("+", " ".join(cmd), file=sys.stderr, flush=True)
    return subprocess.run(cmd, check=True, **kw)


def install(skip):
    python = os.path.join(VENV, "bin", "python")
    if skip:
        return python
    if not os.path.exists(python):
        sh([sys.executable, "-m", "venv", VENV])
    sh([python, "-m", "pip", "install", "-q", "pybullet", "mujoco"])
    sh(["cargo", "build", "--release", "--locked", "-p", "tumble-cli"], cwd=ROOT)
    # From the root, so that both take its .cargo/config.toml (built for this processor).
    sh(["cargo", "build", "--release", "--manifest-path", os.path.join(BENCH, "rapier", "Cargo.toml")], cwd=ROOT)
    return python


def machine():
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    uname = subprocess.run(["uname", "-a"], capture_output=True, text=True).stdout.strip()
    return uname, cpu, os.cpu_count()


def cpu_ticks():
    """The machine's CPU time so far as (stolen, total) clock ticks, from /proc/stat (Linux), or
    None. Stolen time is what the hypervisor gave other guests while this one had work: on a
    shared virtual machine it slows a run on threads that wait for each other far more than a
    run on one thread."""
    try:
        with open("/proc/stat") as f:
            fields = [int(x) for x in f.readline().split()[1:]]
    except (OSError, ValueError):
        return None
    # user nice system idle iowait irq softirq steal [guest guest_nice, already in user and nice]
    return fields[7], sum(fields[:8])


def stolen_share(before, after):
    """The share of the CPU time between two `cpu_ticks` readings that was stolen, or None."""
    if before is None or after is None or after[1] <= before[1]:
        return None
    return (after[0] - before[0]) / (after[1] - before[1])


def run_json(cmd, timeout):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    t0 = time.perf_counter()
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return {"error": f"did not finish within {timeout:.0f} s"}
    if out.returncode != 0:
        tail = (out.stderr.strip().splitlines() or ["?"])[-1]
        return {"error": f"failed: {tail[:120]}"}
    try:
        result = json.loads(out.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        return {"error": "no result"}
    result["wall"] = time.perf_counter() - t0
    return result


def command(engine, python, scene_file, scene, steps, runs, quality, threads):
    if engine == "tumble":
        return [TUMBLE, "bench", scene, "--json", "--runs", str(runs), "--steps", str(steps), "--threads", str(threads)]
    if engine == "tumble-matched":
        return command("tumble", python, scene_file, scene, steps, runs, quality, threads) + MATCHED.get(scene, [])
    if engine == "rapier":
        return [RAPIER, scene_file, "--runs", str(runs), "--steps", str(steps)]
    script = os.path.join(BENCH, "peers", f"{engine}_peer.py")
    cmd = [python, script, scene_file, "--runs", str(runs), "--steps", str(steps)]
    return cmd + (["--quality-only"] if quality else ["--no-quality"])


def bench_scene(scene, engines, python, steps, rounds, timeout, threads, size=None):
    scene_file = os.path.join(WORK, f"{scene}{'' if size is None else '-' + str(size)}.json")
    export = [TUMBLE, "bench", scene, "--export", scene_file] + ([] if size is None else ["--size", str(size)])
    sh(export, stdout=subprocess.DEVNULL)
    results = {e: {"rates": [], "last": None, "error": None} for e in engines}
    for r in range(rounds):
        for e in engines:
            res = results[e]
            if res["error"]:
                continue
            cmd = command(e, python, scene_file, scene, steps, 1, False, threads)
            if size is not None and e.startswith("tumble"):
                cmd += ["--size", str(size)]
            out = run_json(cmd, timeout)
            if "error" in out or "unsupported" in out:
                res["error"] = out.get("error") or "cannot build the scene: " + out["unsupported"]
                continue
            res["rates"].append(out["steps_per_second"])
            res["last"] = out
            print(f"  {scene} round {r + 1}: {e} {out['steps_per_second']:.1f} steps/s", file=sys.stderr, flush=True)
    for e in engines:
        res = results[e]
        if e in ("pybullet", "mujoco") and res["last"] is not None:
            q = run_json(command(e, python, scene_file, scene, steps, 0, True, threads), timeout * 2)
            res["last"]["metrics"] = q.get("metrics", {"quality run": q.get("error", "?")})
    return results


def fmt_metrics(metrics):
    parts = []
    for k, v in (metrics or {}).items():
        if isinstance(v, bool):
            parts.append(f"{k} {'yes' if v else 'no'}")
        elif isinstance(v, (int,)) and not isinstance(v, bool):
            parts.append(f"{k} {v}")
        elif isinstance(v, float):
            if "error" in k:
                parts.append(f"{k} {v:.2e}")
            elif abs(v) < 0.1:
                parts.append(f"{k} {v * 100:.2f} cm")
            else:
                parts.append(f"{k} {v:.3f} m")
        else:
            parts.append(f"{k} {v}")
    return ", ".join(parts)


def table(all_results, engines, steps_of):
    lines = [
        "| scene | steps | engine | steps/s (median) | Tumble / engine | Tumble matched / engine | quality | settings |",
        "|---|---|---|---|---|---|---|---|",
    ]

    def median_of(results, engine):
        r = results.get(engine)
        return statistics.median(r["rates"]) if r and r["rates"] else None

    for scene, results in all_results.items():
        t_rate, m_rate = median_of(results, "tumble"), median_of(results, "tumble-matched")
        for e in engines:
            res = results[e]
            if res["rates"]:
                rate = statistics.median(res["rates"])
                last = res["last"]
                ratio = f"{t_rate / rate:.2f}" if t_rate else "—"
                matched = f"{m_rate / rate:.2f}" if m_rate else "—"
                settings = last.get("iterations", "")
                if "substeps" in last:
                    settings += f"; substeps {last['substeps']}"
                settings += f"; threads {last.get('threads', 1)}; {len(res['rates'])} runs"
                if res["error"]:
                    settings += f" (the next {res['error']})"
                if e == "tumble-matched" and "--solver" in MATCHED.get(scene, []):
                    settings += "; " + ", ".join(a for a in MATCHED[scene] if "=" in a)
                if last.get("note"):
                    settings += f"; {last['note']}"
                version = last.get("version", "")
                lines.append(
                    f"| {scene} | {steps_of(scene)} | {e} {version} | {rate:,.1f} | {ratio} | {matched} | "
                    f"{last.get('quality') or fmt_metrics(last.get('metrics'))} | {settings} |"
                )
            else:
                lines.append(f"| {scene} | {steps_of(scene)} | {e} | — | — | — | {res['error']} | |")
    return "\n".join(lines)


# The quality results each scene is judged by, all "lower is better"; a peer whose state blew up
# and was reset (MuJoCo's "diverged") is worse than any finished run. The target (BENCHMARKS.md):
# Tumble at least twice the fastest peer's steps/s, at equal or better quality.
QUALITY_KEYS = {
    "pyramid": ["max displacement"],
    "large_pyramid": ["max displacement"],
    "rain": ["escaped", "max penetration"],
    "chain": ["max joint separation"],
    "ragdolls": ["max joint separation"],
    # The overlap at the end is one sample of a pile still landing (2-10 cm from step to step in
    # the first 120); averaged over the run's steps it is a measure.
    "convex_pile": ["mean max penetration"],
    "tumbling": ["energy error"],
}
TARGET = 2.0


def at_least_as_good(scene, ours, theirs):
    """Whether the quality metrics `ours` are equal to or better than `theirs` on `scene`."""
    if theirs.get("diverged (state reset)"):
        return True
    keys = QUALITY_KEYS.get(scene, [])
    if any(k not in ours or k not in theirs for k in keys):
        return False
    # A flag such as "all asleep" counts only when the peer has it and Tumble does not.
    if theirs.get("all asleep") is True and not ours.get("all asleep"):
        return False
    return all(float(ours[k]) <= float(theirs[k]) for k in keys)


def targets(all_results, engines):
    """Per scene: the fastest peer, the fastest Tumble run at equal or better quality than it, the
    ratio, and whether the 2x target is met (or by how much it is missed)."""
    lines = [
        "| scene | fastest peer | its steps/s | its quality | Tumble at equal or better quality | steps/s | ratio | target 2x |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for scene, results in all_results.items():
        peers = [(statistics.median(r["rates"]), e) for e, r in results.items() if not e.startswith("tumble") and r["rates"]]
        if not peers:
            continue
        peer_rate, peer = max(peers)
        theirs = results[peer]["last"].get("metrics") or {}
        candidates = [
            (statistics.median(r["rates"]), e)
            for e, r in results.items()
            if e.startswith("tumble") and r["rates"] and at_least_as_good(scene, r["last"].get("metrics") or {}, theirs)
        ]
        peer_quality = fmt_metrics(theirs)
        if not candidates:
            lines.append(f"| {scene} | {peer} | {peer_rate:,.1f} | {peer_quality} | none | — | — | no Tumble run at that quality |")
            continue
        rate, engine = max(candidates)
        ratio = rate / peer_rate
        verdict = "met" if ratio >= TARGET else f"missed: {TARGET / ratio:.2f}x short"
        lines.append(
            f"| {scene} | {peer} | {peer_rate:,.1f} | {peer_quality} | {engine} | {rate:,.1f} | {ratio:.2f} | {verdict} |"
        )
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenes", default=",".join(TABLE_STEPS), help="comma-separated scene names")
    parser.add_argument("--engines", default=",".join(ENGINES))
    parser.add_argument("--runs", type=int, default=5, help="rounds (timed runs per engine)")
    parser.add_argument("--steps", type=int, default=None, help="steps per run for every scene")
    parser.add_argument("--threads", type=int, default=1, help="Tumble's collision threads")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds one run may take")
    parser.add_argument("--scaling", action="store_true", help="Tumble's steps/s against body count instead")
    parser.add_argument("--skip-install", action="store_true")
    parser.add_argument("--out", default=None, help="write the report (markdown) here too")
    args = parser.parse_args()
    os.makedirs(WORK, exist_ok=True)
    python = install(args.skip_install)
    uname, cpu, cores = machine()
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    header = f"date: {date}\nmachine: {uname}\ncpu: {cpu} ({cores} logical cores)\n"
    if args.scaling:
        rows = ["| scene | size | bodies | steps | steps/s (median) | body-steps/s | quality |", "|---|---|---|---|---|---|---|"]
        for scene, sizes, steps in SCALING:
            for size in sizes:
                res = bench_scene(scene, ["tumble"], python, steps, args.runs, args.timeout, args.threads, size)
                t = res["tumble"]
                if t["rates"]:
                    rate = statistics.median(t["rates"])
                    bodies = t["last"]["bodies"]
                    rows.append(
                        f"| {scene} | {size} | {bodies} | {steps} | {rate:,.1f} | {rate * bodies:,.0f} | {t['last']['quality']} |"
                    )
                else:
                    rows.append(f"| {scene} | {size} | | {steps} | — | — | {t['error']} |")
        report = header + f"Tumble, threads {args.threads}, {args.runs} runs each\n\n" + "\n".join(rows) + "\n"
    else:
        engines = args.engines.split(",")
        scenes = args.scenes.split(",")
        steps_of = lambda s: args.steps or TABLE_STEPS.get(s, 100)  # noqa: E731
        all_results = {}
        for scene in scenes:
            all_results[scene] = bench_scene(scene, engines, python, steps_of(scene), args.runs, args.timeout, args.threads)
        report = (
            header
            + "dt 1/60 s; steps per run as listed\n\n"
            + table(all_results, engines, steps_of)
            + "\n\nTargets: Tumble against the fastest peer, at equal or better quality (`QUALITY_KEYS`)\n\n"
            + targets(all_results, engines)
            + "\n"
        )
    print(report)
    if args.out:
        with open(args.out, "w") as f:
            f.write(report)


if __name__ == "__main__":
    main()
