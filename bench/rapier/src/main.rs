//! Rapier (f64 build) running a benchmark scene exported by `tumble bench SCENE --export`, with
//! Rapier's default integration parameters. Prints one JSON object: steps/s (median of the runs,
//! each step timed on its own), settings and the scene's quality result.
//!
//!     tumble-bench-rapier SCENE.json [--runs N] [--steps N]

use std::time::{Duration, Instant};

use rapier3d_f64::math::{Pose, Rotation, Vector};
use rapier3d_f64::prelude::*;
use serde_json::{json, Value};

fn v3(v: &Value) -> Vector {
    Vector::new(v[0].as_f64().unwrap(), v[1].as_f64().unwrap(), v[2].as_f64().unwrap())
}

fn quat(v: &Value) -> Rotation {
    Rotation::from_xyzw(
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
        v[3].as_f64().unwrap(),
    )
}

/// The rotation taking X onto `axis` (Rapier's twist and hinge axis is the joint frame's X).
fn x_to(axis: Vector) -> Rotation {
    Rotation::from_rotation_arc(Vector::X, axis.normalize())
}

struct Built {
    world: PhysicsWorld,
    bodies: Vec<Option<RigidBodyHandle>>,
    /// Per joint: body a and b (None: the world) and the anchor in each body's frame.
    anchors: Vec<(Option<RigidBodyHandle>, Option<RigidBodyHandle>, Vector, Vector)>,
    start: Vec<Option<Vector>>,
}

fn collider(shape: &Value) -> Option<ColliderBuilder> {
    Some(match shape["type"].as_str()? {
        "sphere" => ColliderBuilder::ball(shape["radius"].as_f64()?),
        "box" => {
            let h = v3(&shape["half_extents"]);
            ColliderBuilder::cuboid(h.x, h.y, h.z)
        }
        "capsule" => ColliderBuilder::capsule_z(shape["half_height"].as_f64()?, shape["radius"].as_f64()?),
        "plane" => ColliderBuilder::halfspace(rapier3d_f64::na::Unit::new_unchecked(
            v3(&shape["normal"]).normalize(),
        )),
        "hull" => {
            let points: Vec<Vector> = shape["points"].as_array()?.iter().map(v3).collect();
            ColliderBuilder::convex_hull(&points)?
        }
        "mesh" => {
            let vertices: Vec<Vector> = shape["vertices"].as_array()?.iter().map(v3).collect();
            let triangles: Vec<[u32; 3]> = shape["triangles"]
                .as_array()?
                .iter()
                .map(|t| [0, 1, 2].map(|k| t[k].as_u64().unwrap() as u32))
                .collect();
            ColliderBuilder::trimesh(vertices, triangles).ok()?
        }
        _ => return None,
    })
}

fn build(scene: &Value) -> Built {
    let mut world = PhysicsWorld::new();
    world.gravity = v3(&scene["gravity"]);
    world.integration_parameters.dt = scene["dt"].as_f64().unwrap();
    let sleep = scene["sleep"].as_bool().unwrap_or(false);
    let mut bodies = Vec::new();
    let mut start = Vec::new();
    let mut poses = Vec::new();
    for b in scene["bodies"].as_array().unwrap() {
        let pose = Pose::from_parts(v3(&b["position"]), quat(&b["orientation"]));
        poses.push(pose);
        let dynamic = b["kind"] == "dynamic";
        if !dynamic && b["shape"].is_null() {
            bodies.push(None);
            start.push(None);
            continue;
        }
        let body = if dynamic {
            RigidBodyBuilder::dynamic()
                .pose(pose)
                .linvel(v3(&b["linear_velocity"]))
                .angvel(v3(&b["angular_velocity"]))
                .can_sleep(sleep)
        } else {
            RigidBodyBuilder::fixed().pose(pose)
        };
        let handle = world.bodies.insert(body);
        if let Some(c) = collider(&b["shape"]) {
            let c = c.density(1000.0).friction(b["friction"].as_f64().unwrap_or(0.6));
            world.colliders.insert_with_parent(c, handle, &mut world.bodies);
        }
        bodies.push(Some(handle));
        start.push(dynamic.then(|| pose.translation));
    }
    let mut anchors = Vec::new();
    for j in scene["joints"].as_array().unwrap() {
        let (ia, ib) = (j["body_a"].as_u64().unwrap() as usize, j["body_b"].as_u64().unwrap() as usize);
        let (anchor, axis) = (v3(&j["anchor"]), v3(&j["axis"]));
        let frame = |pose: &Pose| {
            let inv = pose.inverse();
            Pose::from_parts(inv.transform_point(anchor), inv.rotation * x_to(axis))
        };
        let (fa, fb) = (frame(&poses[ia]), frame(&poses[ib]));
        let builder = match j["type"].as_str().unwrap() {
            "ball" => {
                let mut g = GenericJointBuilder::new(JointAxesMask::LOCKED_SPHERICAL_AXES);
                if let Some(t) = j["twist"].as_array() {
                    g = g.limits(JointAxis::AngX, [t[0].as_f64().unwrap(), t[1].as_f64().unwrap()]);
                }
                // No cone limit in Rapier: the swing is limited about each of the two other axes.
                if let Some(s) = j["swing"].as_f64() {
                    g = g.limits(JointAxis::AngY, [-s, s]).limits(JointAxis::AngZ, [-s, s]);
                }
                g
            }
            _ => {
                let mut g = GenericJointBuilder::new(JointAxesMask::LOCKED_REVOLUTE_AXES);
                if let Some(l) = j["limits"].as_array() {
                    g = g.limits(JointAxis::AngX, [l[0].as_f64().unwrap(), l[1].as_f64().unwrap()]);
                }
                g
            }
        };
        let joint = builder.local_frame1(fa).local_frame2(fb).contacts_enabled(false).build();
        // A shapeless static body is the world: pin to a fixed body at its pose.
        let a = bodies[ia].unwrap_or_else(|| world.bodies.insert(RigidBodyBuilder::fixed().pose(poses[ia])));
        let b = bodies[ib].expect("body b of a joint is a body");
        world.impulse_joints.insert(a, b, joint, true);
        anchors.push((Some(a), Some(b), fa.translation, fb.translation));
    }
    Built { world, bodies, anchors, start }
}

fn max_joint_separation(built: &Built) -> f64 {
    let at = |h: Option<RigidBodyHandle>, local: Vector| {
        h.map_or(local, |h| built.world.bodies[h].position().transform_point(local))
    };
    built.anchors.iter().map(|&(a, b, la, lb)| (at(a, la) - at(b, lb)).length()).fold(0.0, f64::max)
}

fn max_penetration(world: &PhysicsWorld) -> f64 {
    world
        .narrow_phase
        .contact_pairs()
        .flat_map(|p| p.manifolds().iter())
        .flat_map(|m| m.points.iter())
        .map(|p| -p.dist)
        .fold(0.0, f64::max)
}

fn quality(scene: &Value, built: &Built, joint_max: f64, energy0: f64, mean_penetration: f64) -> Value {
    let world = &built.world;
    let dynamic = || {
        built
            .bodies
            .iter()
            .zip(&built.start)
            .filter_map(|(h, s)| Some((world.bodies[(*h)?].translation(), (*s)?)))
    };
    match scene["scene"].as_str().unwrap() {
        "pyramid" | "large_pyramid" => {
            json!({ "max displacement": dynamic().map(|(p, s)| (p - s).length()).fold(0.0, f64::max) })
        }
        "rain" => json!({
            "escaped": dynamic().filter(|(p, _)| p.x.abs() > 10.0 || p.y.abs() > 10.0 || p.z < 0.0).count(),
            "max penetration": max_penetration(world),
        }),
        "chain" => json!({ "max joint separation": joint_max }),
        "ragdolls" => json!({
            "max joint separation": joint_max,
            "all asleep": built.bodies.iter().flatten().all(|&h| !world.bodies[h].is_dynamic() || world.bodies[h].is_sleeping()),
        }),
        "convex_pile" => json!({
            "max penetration": max_penetration(world),
            "mean max penetration": mean_penetration,
        }),
        "tumbling" => {
            let e: f64 = world.bodies.iter().map(|(_, b)| b.kinetic_energy()).sum();
            json!({ "energy error": (e - energy0).abs() / energy0 })
        }
        _ => json!({}),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).expect("usage: tumble-bench-rapier SCENE.json [--runs N] [--steps N]");
    let option =
        |name: &str| args.iter().position(|a| a == name).and_then(|i| args.get(i + 1)?.parse::<u64>().ok());
    let scene: Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("readable scene")).expect("JSON");
    let runs = option("--runs").unwrap_or(5).max(1);
    let steps = option("--steps").unwrap_or(scene["steps"].as_u64().unwrap());
    let mut rates = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let mut built = build(&scene);
        let energy0: f64 = built.world.bodies.iter().map(|(_, b)| b.kinetic_energy()).sum();
        let mut stepping = Duration::ZERO;
        let mut joint_max = 0.0_f64;
        // The convex pile's largest overlap, summed over the steps.
        let mut penetration_sum = 0.0_f64;
        let pile = scene["scene"].as_str() == Some("convex_pile");
        for _ in 0..steps {
            let t = Instant::now();
            built.world.step();
            stepping += t.elapsed();
            joint_max = joint_max.max(max_joint_separation(&built));
            if pile {
                penetration_sum += max_penetration(&built.world);
            }
        }
        rates.push(steps as f64 / stepping.as_secs_f64());
        let mean_penetration = if steps > 0 { penetration_sum / steps as f64 } else { max_penetration(&built.world) };
        last = Some((built, joint_max, energy0, mean_penetration));
    }
    let (built, joint_max, energy0, mean_penetration) = last.unwrap();
    rates.sort_by(f64::total_cmp);
    let median = if runs % 2 == 1 {
        rates[runs as usize / 2]
    } else {
        0.5 * (rates[runs as usize / 2 - 1] + rates[runs as usize / 2])
    };
    let p = &built.world.integration_parameters;
    println!(
        "{}",
        json!({
            "engine": "rapier3d-f64",
            "version": "0.36",
            "scene": scene["scene"],
            "steps": steps,
            "runs": runs,
            "steps_per_second": median,
            "min": rates[0],
            "max": rates[rates.len() - 1],
            "iterations": format!("{} solver iterations, {} internal PGS", p.num_solver_iterations, p.num_internal_pgs_iterations),
            "threads": 1,
            "metrics": quality(&scene, &built, joint_max, energy0, mean_penetration),
        })
    );
}
