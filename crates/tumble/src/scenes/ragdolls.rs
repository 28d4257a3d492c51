//! `ragdolls`: ragdolls of 11 bodies (boxes, capsules and a sphere) on 10 joints — ball joints
//! with swing cones and twist limits at the neck, waist, shoulders and hips, limited hinges at the
//! elbows and knees — dropped lying down in a pile (5 × 5 per layer, alternate layers head to
//! foot) onto the ground; 600 steps, sleep on. Quality: the largest joint separation over the
//! run, and whether every body is asleep at the end.

use super::chain::JointSeparation;
use super::quality::{Metric, Quality};
use super::{add_ground, world, Probe, Scene, G};
use crate::body::BodyDef;
use crate::dynamics::joint::{BallJoint, HingeJoint, JointDef, JointKind, Limits};
use crate::math::{DQuat, DVec3, Transform};
use crate::shape::{Capsule, Cuboid, Shape, Sphere};
use crate::world::World;

/// How a part hangs from its parent.
#[derive(Clone, Debug)]
pub enum PartJoint {
    /// The pelvis: no parent.
    Root,
    /// A ball joint at `anchor` with cone half-angle `swing` and twist range `twist` about `axis`.
    Ball { parent: usize, anchor: DVec3, axis: DVec3, swing: f64, twist: (f64, f64) },
    /// A hinge at `anchor` about `axis` with angle range `limits`.
    Hinge { parent: usize, anchor: DVec3, axis: DVec3, limits: (f64, f64) },
}

/// One body of a ragdoll standing upright with its feet on z = 0 (the ragdoll's own frame).
#[derive(Clone, Debug)]
pub struct RagdollPart {
    pub name: &'static str,
    pub shape: Shape,
    pub center: DVec3,
    pub joint: PartJoint,
}

fn cuboid(x: f64, y: f64, z: f64) -> Shape {
    Shape::Cuboid(Cuboid::new(DVec3::new(x, y, z)).expect("positive half extents"))
}

fn capsule(radius: f64, half_height: f64) -> Shape {
    Shape::Capsule(Capsule::new(radius, half_height).expect("positive sizes"))
}

/// Two segments hanging down from `parent` at `x` (mirrored by side).
struct Limb {
    parent: usize,
    x: f64,
    names: [&'static str; 2],
    shapes: [Shape; 2],
    /// Heights of the upper joint, upper centre, lower joint, lower centre.
    z: [f64; 4],
    swing: f64,
    twist: f64,
    bend: (f64, f64),
}

impl Limb {
    fn add(&self, parts: &mut Vec<RagdollPart>, side: f64) {
        let at = |z: f64| DVec3::new(side * self.x, 0.0, z);
        let upper = parts.len();
        parts.push(RagdollPart {
            name: self.names[0],
            shape: self.shapes[0].clone(),
            center: at(self.z[1]),
            joint: PartJoint::Ball {
                parent: self.parent,
                anchor: at(self.z[0]),
                axis: -DVec3::Z,
                swing: self.swing,
                twist: (-self.twist, self.twist),
            },
        });
        parts.push(RagdollPart {
            name: self.names[1],
            shape: self.shapes[1].clone(),
            center: at(self.z[3]),
            joint: PartJoint::Hinge {
                parent: upper,
                anchor: at(self.z[2]),
                axis: DVec3::X,
                limits: self.bend,
            },
        });
    }
}

/// The 11 parts, parents before children.
pub fn ragdoll_parts() -> Vec<RagdollPart> {
    use PartJoint::{Ball, Root};
    let v = DVec3::new;
    let mut parts = vec![
        RagdollPart { name: "pelvis", shape: cuboid(0.15, 0.1, 0.1), center: v(0.0, 0.0, 1.0), joint: Root },
        RagdollPart {
            name: "torso",
            shape: cuboid(0.18, 0.1, 0.25),
            center: v(0.0, 0.0, 1.35),
            joint: Ball {
                parent: 0,
                anchor: v(0.0, 0.0, 1.1),
                axis: DVec3::Z,
                swing: 0.5,
                twist: (-0.4, 0.4),
            },
        },
        RagdollPart {
            name: "head",
            shape: Shape::Sphere(Sphere::new(0.11).expect("positive radius")),
            center: v(0.0, 0.0, 1.73),
            joint: Ball {
                parent: 1,
                anchor: v(0.0, 0.0, 1.6),
                axis: DVec3::Z,
                swing: 0.6,
                twist: (-0.8, 0.8),
            },
        },
    ];
    // Arms hang from the torso's shoulders, legs from the pelvis's hips: a ball joint to the upper
    // segment, a limited hinge (elbow, knee) to the lower one.
    let arm = Limb {
        parent: 1,
        x: 0.25,
        names: ["upper arm", "lower arm"],
        shapes: [capsule(0.05, 0.12), capsule(0.045, 0.11)],
        z: [1.56, 1.44, 1.29, 1.14],
        swing: 1.2,
        twist: 0.5,
        bend: (0.0, 2.3),
    };
    let leg = Limb {
        parent: 0,
        x: 0.09,
        names: ["thigh", "shin"],
        shapes: [capsule(0.07, 0.14), capsule(0.06, 0.16)],
        z: [0.92, 0.71, 0.5, 0.28],
        swing: 1.0,
        twist: 0.3,
        bend: (-2.3, 0.0),
    };
    for limb in [arm, leg] {
        for side in [-1.0, 1.0] {
            limb.add(&mut parts, side);
        }
    }
    parts
}

/// Ragdolls per row and rows per layer of the pile.
pub const PER_ROW: usize = 5;
/// Spacing of the pile along X (head to foot) and Y, and between layers, m.
pub const SPACING: DVec3 = DVec3::new(2.2, 0.8, 0.6);
/// Height of the lowest layer's pelvis, m.
pub const FIRST_LAYER: f64 = 0.5;

/// Where ragdoll `k` lies: on its back along X (turned head to foot on odd layers), in the pile.
pub fn ragdoll_pose(k: usize) -> Transform {
    let per_layer = PER_ROW * PER_ROW;
    let (layer, rest) = (k / per_layer, k % per_layer);
    let (j, i) = (rest / PER_ROW, rest % PER_ROW);
    let offset = 0.5 * (PER_ROW as f64 - 1.0);
    let yaw = if layer % 2 == 0 { 0.0 } else { std::f64::consts::PI };
    // Lying down: the standing ragdoll's Z (up) becomes +X; its pelvis goes to the grid point.
    let lie = DQuat::from_rotation_z(yaw) * DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
    let place = DVec3::new(
        (i as f64 - offset) * SPACING.x,
        (j as f64 - offset) * SPACING.y,
        FIRST_LAYER + layer as f64 * SPACING.z,
    );
    let pelvis = DVec3::new(0.0, 0.0, 1.0);
    Transform::new(place - lie * pelvis, lie)
}

/// `count` ragdolls (100 by default) in a pile.
pub fn ragdolls(count: usize) -> Scene {
    let mut w = world(G, true);
    add_ground(&mut w);
    let parts = ragdoll_parts();
    for k in 0..count {
        let pose = ragdoll_pose(k);
        let mut ids = Vec::with_capacity(parts.len());
        for part in &parts {
            let id = w
                .add_body(BodyDef {
                    name: part.name.into(),
                    shape: Some(part.shape.clone()),
                    position: pose.transform_point(part.center),
                    orientation: pose.rotation,
                    ..Default::default()
                })
                .expect("a ragdoll part is a valid body");
            ids.push(id);
            let def = match part.joint {
                PartJoint::Root => continue,
                PartJoint::Ball { parent, anchor, axis, swing, twist } => JointDef::new(
                    ids[parent],
                    id,
                    pose.transform_point(anchor),
                    JointKind::Ball(BallJoint {
                        swing_limit: Some(swing),
                        twist_limits: Some(Limits::new(twist.0, twist.1)),
                        ..Default::default()
                    }),
                )
                .with_axis(pose.rotation * axis),
                PartJoint::Hinge { parent, anchor, axis, limits } => JointDef::new(
                    ids[parent],
                    id,
                    pose.transform_point(anchor),
                    JointKind::Hinge(HingeJoint {
                        limits: Some(Limits::new(limits.0, limits.1)),
                        ..Default::default()
                    }),
                )
                .with_axis(pose.rotation * axis),
            };
            w.add_joint(def).expect("a ragdoll joint is valid");
        }
    }
    Scene::new("ragdolls", count, w, 600, Pile::default())
}

/// Joint separation over the run, and sleep at the end.
#[derive(Default)]
struct Pile {
    joints: JointSeparation,
}

impl Probe for Pile {
    fn observe(&mut self, world: &World) {
        self.joints.observe(world);
    }

    fn quality(&self, world: &World) -> Quality {
        let mut q = self.joints.quality(world);
        q.metrics.push(Metric::Flag("all asleep", world.awake_body_count() == 0));
        q
    }
}
