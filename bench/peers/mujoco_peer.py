"""MuJoCo running a scene exported by `tumble bench SCENE --export`, built as an MJCF XML string.

    python bench/peers/mujoco_peer.py SCENE.json [--runs N] [--steps N]

MuJoCo's defaults (Newton solver, its default iterations, Euler integrator) except the time step
(the scene's dt). Joints make a kinematic tree, so a jointed body is nested in its parent (body a)
with a ball or hinge joint at the anchor; a body with no joint gets a free joint. Ball-joint
limits are a cone (MuJoCo has no twist limit on a ball joint: left out, said in the result).
The static triangle-mesh terrain becomes a height field with the same heights (a MuJoCo mesh
collides as its convex hull). MuJoCo has no sleep: "all asleep" is reported as false.
"""

import math

import mujoco

import common


def _wxyz(q):
    return f"{q[3]!r} {q[0]!r} {q[1]!r} {q[2]!r}"


def _vec(v):
    return " ".join(repr(float(x)) for x in v)


def _quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


class Mjcf:
    def __init__(self, scene):
        self.scene = scene
        self.assets = []
        self.notes = set()

    def geom(self, i, s, friction):
        t = s["type"]
        f = f'friction="{friction} 0.005 0.0001"'
        if t == "sphere":
            return f'<geom type="sphere" size="{s["radius"]}" {f}/>'
        if t == "box":
            return f'<geom type="box" size="{_vec(s["half_extents"])}" {f}/>'
        if t == "capsule":
            return f'<geom type="capsule" size="{s["radius"]} {s["half_height"]}" {f}/>'
        if t == "plane":
            if list(s["normal"]) != [0.0, 0.0, 1.0]:
                raise common.Unsupported("only ground planes with normal +Z")
            return f'<geom type="plane" size="0 0 1" pos="0 0 {s["offset"]}" {f}/>'
        if t == "hull":
            verts = " ".join(_vec(v) for v in s["points"])
            self.assets.append(f'<mesh name="hull{i}" vertex="{verts}"/>')
            return f'<geom type="mesh" mesh="hull{i}" {f}/>'
        if t == "mesh":
            return self.height_field(i, s, f)
        raise common.Unsupported(f"shape {t}")

    def height_field(self, i, s, f):
        """A grid mesh (vertices row by row, y outer, on a square grid) as a height field."""
        verts = s["vertices"]
        n = int(round(math.sqrt(len(verts))))
        if n * n != len(verts):
            raise common.Unsupported("a triangle mesh that is not a square height grid")
        xs = [v[0] for v in verts[:n]]
        ys = [verts[k * n][1] for k in range(n)]
        zs = [v[2] for v in verts]
        lo, hi = min(zs), max(zs)
        rng = max(hi - lo, 1e-9)
        elevation = " ".join(repr((z - lo) / rng) for z in zs)
        rx, ry = 0.5 * (xs[-1] - xs[0]), 0.5 * (ys[-1] - ys[0])
        cx, cy = 0.5 * (xs[-1] + xs[0]), 0.5 * (ys[-1] + ys[0])
        self.assets.append(
            f'<hfield name="terrain{i}" nrow="{n}" ncol="{n}" size="{rx} {ry} {rng} 1" elevation="{elevation}"/>'
        )
        self.notes.add("terrain mesh as a height field")
        return f'<geom type="hfield" hfield="terrain{i}" pos="{cx} {cy} {lo}" {f}/>'

    def xml(self):
        scene = self.scene
        bodies = scene["bodies"]
        parent_of, joint_of = {}, {}
        for k, j in enumerate(scene["joints"]):
            if j["body_b"] in parent_of:
                raise common.Unsupported("a body with two parent joints (a loop)")
            parent_of[j["body_b"]] = j["body_a"]
            joint_of[j["body_b"]] = j
        children = {}
        for child, parent in parent_of.items():
            children.setdefault(parent, []).append(child)

        def body_xml(i, parent_pose):
            b = bodies[i]
            pos, q = b["position"], b["orientation"]
            if parent_pose is not None:
                rel_pos = common.to_local(parent_pose[0], parent_pose[1], pos)
                rel_q = _quat_mul(common.quat_conj(parent_pose[1]), q)
            else:
                rel_pos, rel_q = pos, q
            out = [f'<body name="b{i}" pos="{_vec(rel_pos)}" quat="{_wxyz(rel_q)}">']
            j = joint_of.get(i)
            if j is None:
                out.append("<freejoint/>")
            else:
                anchor = common.to_local(pos, q, j["anchor"])
                axis = common.quat_rotate(common.quat_conj(q), j["axis"])
                if j["type"] == "ball":
                    rng = ""
                    if j.get("swing") is not None:
                        rng = f' limited="true" range="0 {j["swing"]}"'
                    if j.get("twist") is not None:
                        self.notes.add("ball twist limits")
                    out.append(f'<joint type="ball" pos="{_vec(anchor)}" axis="{_vec(axis)}"{rng}/>')
                else:
                    rng = ""
                    if j.get("limits") is not None:
                        lo, hi = j["limits"]
                        rng = f' limited="true" range="{lo} {hi}"'
                    out.append(f'<joint type="hinge" pos="{_vec(anchor)}" axis="{_vec(axis)}"{rng}/>')
            if b["shape"] is not None:
                out.append(self.geom(i, b["shape"], b["friction"]))
            for c in children.get(i, []):
                out.append(body_xml(c, (pos, q)))
            out.append("</body>")
            return "\n".join(out)

        world = []
        for i, b in enumerate(bodies):
            if b["kind"] != "dynamic":
                # Static: geoms of the world body at the body's pose; its jointed children hang from the world.
                if b["shape"] is not None:
                    g = self.geom(i, b["shape"], b["friction"])
                    world.append(f'<body name="b{i}" pos="{_vec(b["position"])}" quat="{_wxyz(b["orientation"])}">{g}</body>')
                for c in children.get(i, []):
                    world.append(body_xml(c, None))
            elif i not in parent_of:
                world.append(body_xml(i, None))
        g = scene["gravity"]
        return f"""<mujoco>
  <compiler angle="radian"/>
  <option timestep="{scene['dt']!r}" gravity="{_vec(g)}"/>
  <size memory="2G"/>
  <default><geom density="1000"/></default>
  <asset>{''.join(self.assets)}</asset>
  <worldbody>
{chr(10).join(world)}
  </worldbody>
</mujoco>"""


class Engine:
    def __init__(self, scene):
        self.scene = scene
        mjcf = Mjcf(scene)
        xml = mjcf.xml()
        self.notes = mjcf.notes
        self.model = mujoco.MjModel.from_xml_string(xml)
        self.data = mujoco.MjData(self.model)
        # Initial velocities of free bodies (world frame linear, local frame angular in qvel).
        for i, b in enumerate(scene["bodies"]):
            if b["kind"] != "dynamic":
                continue
            body = self.model.body(f"b{i}")
            if body.jntnum[0] == 1 and self.model.jnt_type[body.jntadr[0]] == mujoco.mjtJoint.mjJNT_FREE:
                adr = self.model.jnt_dofadr[body.jntadr[0]]
                self.data.qvel[adr : adr + 3] = b["linear_velocity"]
                w_local = common.quat_rotate(common.quat_conj(b["orientation"]), b["angular_velocity"])
                self.data.qvel[adr + 3 : adr + 6] = w_local
        mujoco.mj_forward(self.model, self.data)
        self.energy0 = self.energy()

    def step_function(self):
        model, data, step = self.model, self.data, mujoco.mj_step
        return lambda: step(model, data)

    def step(self):
        mujoco.mj_step(self.model, self.data)

    def pose(self, i):
        b = self.scene["bodies"][i]
        if b["kind"] != "dynamic":
            return None
        body = self.data.body(f"b{i}")
        w, x, y, z = body.xquat
        return tuple(body.xpos), (x, y, z, w)

    def max_penetration(self):
        n = self.data.ncon
        return max([0.0] + [-self.data.contact[k].dist for k in range(n)])

    def all_asleep(self):
        return False

    def extra_metrics(self):
        """MuJoCo resets the state when accelerations blow up: say so, with how often."""
        n = int(self.data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number)
        return {"diverged (state reset)": n} if n else {}

    def energy(self):
        mujoco.mj_energyVel(self.model, self.data)
        return float(self.data.energy[1])

    def energy_error(self):
        self.model.opt.enableflags |= mujoco.mjtEnableBit.mjENBL_ENERGY
        return abs(self.energy() - self.energy0) / self.energy0 if self.energy0 else math.nan

    def settings(self):
        o = self.model.opt
        out = {
            "iterations": f"{o.iterations} solver iterations ({mujoco.mjtSolver(o.solver).name}), {o.ls_iterations} line search",
            "substeps": 1,
            "threads": 1,
        }
        if self.notes:
            out["note"] = "approximated: " + ", ".join(sorted(self.notes))
        return out

    def close(self):
        pass


if __name__ == "__main__":
    common.main("mujoco", mujoco.__version__, Engine)
