"""What the Python peers share: reading a scene exported by `tumble bench SCENE --export`, the
quality results (the same definitions as `tumble::scenes`), and the timing protocol.

Timing: each run builds the scene afresh (not timed), then times one plain loop of `steps` calls
to the engine's step function, with no other Python work per step. The quality result comes from
one more run, not timed, that looks at the world after every step (for the joint separation
taken over the run).
"""

import json
import math
import statistics
import time

BIN_HALF_WIDTH = 10.0  # tumble::scenes::rain::BIN_HALF_WIDTH


def load(path):
    with open(path) as f:
        return json.load(f)


def quat_rotate(q, v):
    """Rotates v by the unit quaternion q = (x, y, z, w)."""
    x, y, z, w = q
    # t = 2 q_vec × v; v' = v + w t + q_vec × t
    tx = 2.0 * (y * v[2] - z * v[1])
    ty = 2.0 * (z * v[0] - x * v[2])
    tz = 2.0 * (x * v[1] - y * v[0])
    return (
        v[0] + w * tx + (y * tz - z * ty),
        v[1] + w * ty + (z * tx - x * tz),
        v[2] + w * tz + (x * ty - y * tx),
    )


def quat_conj(q):
    return (-q[0], -q[1], -q[2], q[3])


def to_local(position, orientation, point):
    d = (point[0] - position[0], point[1] - position[1], point[2] - position[2])
    return quat_rotate(quat_conj(orientation), d)


def to_world(position, orientation, local):
    r = quat_rotate(orientation, local)
    return (position[0] + r[0], position[1] + r[1], position[2] + r[2])


def distance(a, b):
    return math.sqrt(sum((a[i] - b[i]) ** 2 for i in range(3)))


def joint_anchors(scene):
    """Per joint: (body a, body b, anchor in a's frame, anchor in b's frame)."""
    bodies = scene["bodies"]
    out = []
    for j in scene["joints"]:
        a, b = bodies[j["body_a"]], bodies[j["body_b"]]
        out.append(
            (
                j["body_a"],
                j["body_b"],
                to_local(a["position"], a["orientation"], j["anchor"]),
                to_local(b["position"], b["orientation"], j["anchor"]),
            )
        )
    return out


class Quality:
    """Watches a run through an engine adapter with `pose(i) -> (position, orientation xyzw)`
    (None for a body the engine does not have), `max_penetration()` and `all_asleep()`."""

    def __init__(self, scene, engine):
        self.scene, self.engine = scene, engine
        self.anchors = joint_anchors(scene)
        self.joint_max = 0.0
        # The convex pile's largest overlap, summed over the steps observed.
        self.penetration_sum, self.steps = 0.0, 0

    def observe(self):
        if self.anchors:
            self.joint_max = max(self.joint_max, self.joint_separation())
        if self.scene["scene"] == "convex_pile":
            self.penetration_sum += self.engine.max_penetration()
            self.steps += 1

    def joint_separation(self):
        worst = 0.0
        for a, b, la, lb in self.anchors:
            pa, pb = self.engine.pose(a), self.engine.pose(b)
            wa = to_world(pa[0], pa[1], la) if pa else self.scene["joints"][0]["anchor"]
            wb = to_world(pb[0], pb[1], lb)
            if pa is None:  # pinned to the world: the anchor stays where it was made
                wa = to_world(self.scene["bodies"][a]["position"], self.scene["bodies"][a]["orientation"], la)
            worst = max(worst, distance(wa, wb))
        return worst

    def dynamic(self):
        for i, b in enumerate(self.scene["bodies"]):
            if b["kind"] == "dynamic":
                yield i, b

    def result(self):
        name = self.scene["scene"]
        if name in ("pyramid", "large_pyramid"):
            d = max(distance(self.engine.pose(i)[0], b["position"]) for i, b in self.dynamic())
            return {"max displacement": d}
        if name == "rain":
            escaped = 0
            for i, _ in self.dynamic():
                p = self.engine.pose(i)[0]
                if abs(p[0]) > BIN_HALF_WIDTH or abs(p[1]) > BIN_HALF_WIDTH or p[2] < 0.0:
                    escaped += 1
            return {"escaped": escaped, "max penetration": self.engine.max_penetration()}
        if name == "chain":
            return {"max joint separation": max(self.joint_max, self.joint_separation())}
        if name == "ragdolls":
            return {
                "max joint separation": max(self.joint_max, self.joint_separation()),
                "all asleep": self.engine.all_asleep(),
            }
        if name == "convex_pile":
            now = self.engine.max_penetration()
            mean = self.penetration_sum / self.steps if self.steps else now
            return {"max penetration": now, "mean max penetration": mean}
        if name == "tumbling":
            return {"energy error": self.engine.energy_error()}
        return {}


def bench(scene, make_engine, runs, steps, quality=True):
    """Steps/s of `runs` timed runs (median, min, max) and the quality result of one observed run."""
    engine = make_engine(scene)
    metrics = {}
    if quality:
        watch = Quality(scene, engine)
        for _ in range(steps):
            engine.step()
            watch.observe()
        metrics = watch.result()
        metrics.update(getattr(engine, "extra_metrics", dict)())
    settings = engine.settings()
    engine.close()
    rates = []
    for _ in range(runs):
        engine = make_engine(scene)
        step = engine.step_function()
        t0 = time.perf_counter()
        for _ in range(steps):
            step()
        rates.append(steps / (time.perf_counter() - t0))
        engine.close()
    return {
        "scene": scene["scene"],
        "steps": steps,
        "runs": runs,
        "steps_per_second": statistics.median(rates) if rates else None,
        "min": min(rates, default=None),
        "max": max(rates, default=None),
        "metrics": metrics,
        **settings,
    }


def main(engine_name, version, make_engine):
    import argparse

    parser = argparse.ArgumentParser(description=f"{engine_name} on a scene exported by `tumble bench --export`")
    parser.add_argument("scene", help="the scene JSON")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--steps", type=int, default=None, help="steps per run [default: the scene's]")
    parser.add_argument("--no-quality", action="store_true", help="timed runs only")
    parser.add_argument("--quality-only", action="store_true", help="the observed run only")
    args = parser.parse_args()
    scene = load(args.scene)
    steps = args.steps if args.steps is not None else scene["steps"]
    runs = 0 if args.quality_only else max(1, args.runs)
    try:
        result = bench(scene, make_engine, runs, steps, quality=not args.no_quality)
    except Unsupported as e:
        result = {"scene": scene["scene"], "unsupported": str(e)}
    result.update({"engine": engine_name, "version": version})
    print(json.dumps(result))


class Unsupported(Exception):
    """The engine cannot build this scene (the message says why)."""
