"""PyBullet running a scene exported by `tumble bench SCENE --export`.

    python bench/peers/pybullet_peer.py SCENE.json [--runs N] [--steps N]

PyBullet's defaults except the time step (the scene's dt, no internal substeps): its solver
iterations are reported as read back from the engine. Bodies are single-link multibodies. Joints
are point-to-point constraints (`createConstraint`, JOINT_POINT2POINT): PyBullet has no hinge or
limits for constraints between free bodies, so hinges and the ragdolls' limits are left out (said
in the result). Sleep follows the scene (disabled per body where the scene has sleep off).
"""

import math

import pybullet as p

import common


def _shape(client, s):
    t = s["type"]
    if t == "sphere":
        return p.createCollisionShape(p.GEOM_SPHERE, radius=s["radius"], physicsClientId=client)
    if t == "box":
        return p.createCollisionShape(p.GEOM_BOX, halfExtents=s["half_extents"], physicsClientId=client)
    if t == "capsule":
        return p.createCollisionShape(
            p.GEOM_CAPSULE, radius=s["radius"], height=2.0 * s["half_height"], physicsClientId=client
        )
    if t == "plane":
        return p.createCollisionShape(p.GEOM_PLANE, planeNormal=s["normal"], physicsClientId=client)
    if t == "hull":
        return p.createCollisionShape(p.GEOM_MESH, vertices=s["points"], physicsClientId=client)
    if t == "mesh":
        indices = [i for tri in s["triangles"] for i in tri]
        return p.createCollisionShape(
            p.GEOM_MESH,
            vertices=s["vertices"],
            indices=indices,
            flags=p.GEOM_FORCE_CONCAVE_TRIMESH,
            physicsClientId=client,
        )
    raise common.Unsupported(f"shape {t}")


class Engine:
    def __init__(self, scene):
        self.scene = scene
        self.client = c = p.connect(p.DIRECT)
        p.setGravity(*scene["gravity"], physicsClientId=c)
        p.setPhysicsEngineParameter(fixedTimeStep=scene["dt"], numSubSteps=0, physicsClientId=c)
        self.ids = []
        for b in scene["bodies"]:
            if b["shape"] is None:
                self.ids.append(None)
                continue
            uid = p.createMultiBody(
                baseMass=b["mass"],
                baseCollisionShapeIndex=_shape(c, b["shape"]),
                basePosition=b["position"],
                baseOrientation=b["orientation"],
                physicsClientId=c,
            )
            p.changeDynamics(uid, -1, lateralFriction=b["friction"], restitution=0.0, physicsClientId=c)
            if b["kind"] == "dynamic":
                p.resetBaseVelocity(uid, b["linear_velocity"], b["angular_velocity"], physicsClientId=c)
                if not scene["sleep"]:
                    p.changeDynamics(
                        uid, -1, activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING, physicsClientId=c
                    )
            self.ids.append(uid)
        self.left_out = set()
        for j, (a, b, la, lb) in zip(scene["joints"], common.joint_anchors(scene)):
            if j["type"] != "ball":
                self.left_out.add(f"{j['type']} joints as ball joints")
            if j.get("swing") is not None or j.get("twist") is not None or j.get("limits") is not None:
                self.left_out.add("joint limits")
            if self.ids[a] is None:
                # Pinned to the world: PyBullet takes the world as the child, its frame in world terms.
                cid = p.createConstraint(
                    self.ids[b], -1, -1, -1, p.JOINT_POINT2POINT, [0, 0, 0], lb, j["anchor"], physicsClientId=c
                )
            else:
                cid = p.createConstraint(
                    self.ids[a], -1, self.ids[b], -1, p.JOINT_POINT2POINT, [0, 0, 0], la, lb, physicsClientId=c
                )
            p.changeConstraint(cid, maxForce=1e12, physicsClientId=c)
        self.energy0 = self.energy()

    def step_function(self):
        client = self.client
        return lambda: p.stepSimulation(physicsClientId=client)

    def step(self):
        p.stepSimulation(physicsClientId=self.client)

    def pose(self, i):
        uid = self.ids[i]
        if uid is None:
            return None
        return p.getBasePositionAndOrientation(uid, physicsClientId=self.client)

    def max_penetration(self):
        points = p.getContactPoints(physicsClientId=self.client)
        return max([0.0] + [-pt[8] for pt in points])

    def all_asleep(self):
        # PyBullet reports no sleep state through its API: a body asleep has zero velocity.
        for i, b in enumerate(self.scene["bodies"]):
            if b["kind"] == "dynamic":
                v, w = p.getBaseVelocity(self.ids[i], physicsClientId=self.client)
                if any(abs(x) > 0.0 for x in list(v) + list(w)):
                    return False
        return True

    def energy(self):
        e = 0.0
        for i, b in enumerate(self.scene["bodies"]):
            if b["kind"] == "dynamic":
                info = p.getDynamicsInfo(self.ids[i], -1, physicsClientId=self.client)
                mass, inertia = info[0], info[2]
                v, w = p.getBaseVelocity(self.ids[i], physicsClientId=self.client)
                _, q = p.getBasePositionAndOrientation(self.ids[i], physicsClientId=self.client)
                wl = common.quat_rotate(common.quat_conj(q), w)
                e += 0.5 * mass * sum(x * x for x in v) + 0.5 * sum(inertia[k] * wl[k] ** 2 for k in range(3))
        return e

    def energy_error(self):
        return abs(self.energy() - self.energy0) / self.energy0 if self.energy0 else math.nan

    def settings(self):
        params = p.getPhysicsEngineParameters(physicsClientId=self.client)
        out = {
            "iterations": f"{params['numSolverIterations']} solver iterations",
            "substeps": params["numSubSteps"],
            "threads": 1,
        }
        if self.left_out:
            out["note"] = "left out: " + ", ".join(sorted(self.left_out))
        return out

    def close(self):
        p.disconnect(physicsClientId=self.client)


if __name__ == "__main__":
    from importlib.metadata import version

    common.main("pybullet", version("pybullet"), Engine)
