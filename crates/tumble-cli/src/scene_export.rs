//! `tumble bench SCENE --export FILE.json`: the scene as plain data — bodies (kind, shape, pose,
//! velocities, mass), joints (kind, bodies, anchor and axis in world terms, limits), gravity, dt,
//! steps, sleep — so the peer engines in `bench/` build exactly the same scene from one source.

use serde_json::{json, Value};
use tumble::scenes::Scene;
use tumble::{BodyKind, DVec3, JointKind, Shape};

fn vec3(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

fn shape(s: &Shape) -> Result<Value, String> {
    Ok(match s {
        Shape::Sphere(s) => json!({ "type": "sphere", "radius": s.radius }),
        Shape::Cuboid(c) => json!({ "type": "box", "half_extents": vec3(c.half_extents) }),
        Shape::Capsule(c) => json!({ "type": "capsule", "radius": c.radius, "half_height": c.half_height }),
        Shape::Plane(p) => json!({ "type": "plane", "normal": vec3(p.normal), "offset": p.offset }),
        Shape::ConvexHull(h) => {
            json!({ "type": "hull", "points": h.vertices().iter().map(|&v| vec3(v)).collect::<Vec<_>>() })
        }
        Shape::TriMesh(m) => json!({
            "type": "mesh",
            "vertices": m.vertices().iter().map(|&v| vec3(v)).collect::<Vec<_>>(),
            "triangles": m.triangles(),
        }),
        other => return Err(format!("exporting a {} shape is not supported", other.kind_name())),
    })
}

/// The scene as JSON; body indices in `joints` count the bodies in the order listed.
pub fn export(scene: &Scene) -> Result<String, String> {
    let world = &scene.world;
    let index_of: std::collections::HashMap<_, _> =
        world.bodies().enumerate().map(|(i, (id, _))| (id, i)).collect();
    let mut bodies = Vec::new();
    for (_, b) in world.bodies() {
        let q = b.orientation();
        bodies.push(json!({
            "name": b.name(),
            "kind": match b.kind() { BodyKind::Static => "static", BodyKind::Dynamic => "dynamic", BodyKind::Kinematic => "kinematic" },
            "shape": b.shape().map(shape).transpose()?,
            "position": vec3(b.position()),
            "orientation": [q.x, q.y, q.z, q.w],
            "linear_velocity": vec3(b.linear_velocity()),
            "angular_velocity": vec3(b.angular_velocity()),
            "mass": if b.kind() == BodyKind::Dynamic { b.mass() } else { 0.0 },
            "friction": b.material().friction,
        }));
    }
    let mut joints = Vec::new();
    for (_, j) in world.joints() {
        let (a, _b) = (
            world.body(j.body_a()).map_err(|e| e.to_string())?,
            world.body(j.body_b()).map_err(|e| e.to_string())?,
        );
        let axis = a.orientation() * (j.frame_a_local().rotation * DVec3::Z);
        let mut value = json!({
            "body_a": index_of[&j.body_a()],
            "body_b": index_of[&j.body_b()],
            "anchor": vec3(j.anchor_a_world(a)),
            "axis": vec3(axis),
        });
        let extra = match j.kind() {
            JointKind::Ball(ball) => json!({
                "type": "ball",
                "swing": ball.swing_limit,
                "twist": ball.twist_limits.map(|l| [l.lower, l.upper]),
            }),
            JointKind::Hinge(h) => json!({ "type": "hinge", "limits": h.limits.map(|l| [l.lower, l.upper]) }),
            other => return Err(format!("exporting a {} joint is not supported", other.name())),
        };
        for (k, v) in extra.as_object().expect("an object") {
            value[k] = v.clone();
        }
        joints.push(value);
    }
    let s = world.solver_settings();
    let value = json!({
        "scene": scene.name,
        "size": scene.size,
        "dt": scene.dt,
        "steps": scene.steps,
        "gravity": vec3(world.gravity()),
        "sleep": world.sleep_settings().enabled,
        "tumble_settings": { "substeps": s.substeps, "solve_iterations": s.solve_iterations, "relax_iterations": s.relax_iterations },
        "bodies": bodies,
        "joints": joints,
    });
    Ok(value.to_string())
}
