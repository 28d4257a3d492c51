//! `chain`: capsules (r = 0.1 m, 0.5 m between joints) on ball joints, the first pinned to a
//! fixed point, starting horizontal along +X and swinging down under gravity so the tip whips;
//! 1,000 steps. No ground. Quality: the largest joint separation over the run.

use super::quality::{max_joint_separation, Metric, Quality};
use super::{world, Probe, Scene, G};
use crate::body::{BodyDef, BodyKind};
use crate::dynamics::joint::{BallJoint, JointDef, JointKind};
use crate::math::{DQuat, DVec3};
use crate::shape::{Capsule, Shape};
use crate::world::World;

/// Capsule radius, m.
pub const RADIUS: f64 = 0.1;
/// Distance between a link's two joints (the capsule's segment length), m.
pub const LINK_LENGTH: f64 = 0.5;
/// Height of the fixed end, m.
pub const PIVOT_HEIGHT: f64 = 100.0;

/// A chain of `links` capsules (100 by default).
pub fn chain(links: usize) -> Scene {
    let mut w = world(G, false);
    let pivot = DVec3::new(0.0, 0.0, PIVOT_HEIGHT);
    let mut previous = w
        .add_body(BodyDef {
            name: "pivot".into(),
            kind: BodyKind::Static,
            position: pivot,
            ..Default::default()
        })
        .expect("a shapeless static body is valid");
    let shape = Shape::Capsule(Capsule::new(RADIUS, 0.5 * LINK_LENGTH).expect("positive sizes"));
    // Capsules lie along their local Z: turn them onto +X.
    let along_x = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
    for i in 0..links {
        let anchor = pivot + DVec3::X * (i as f64 * LINK_LENGTH);
        let link = w
            .add_body(BodyDef {
                shape: Some(shape.clone()),
                position: anchor + DVec3::X * (0.5 * LINK_LENGTH),
                orientation: along_x,
                ..Default::default()
            })
            .expect("a capsule is a valid body");
        w.add_joint(JointDef::new(previous, link, anchor, JointKind::Ball(BallJoint::new())))
            .expect("a ball joint between two bodies is valid");
        previous = link;
    }
    Scene::new("chain", links, w, 1_000, JointSeparation::default())
}

/// The largest anchor separation of any joint, over the run.
#[derive(Default)]
pub(crate) struct JointSeparation {
    pub max: f64,
}

impl Probe for JointSeparation {
    fn observe(&mut self, world: &World) {
        self.max = self.max.max(max_joint_separation(world));
    }

    fn quality(&self, world: &World) -> Quality {
        let max = self.max.max(max_joint_separation(world));
        Quality { metrics: vec![Metric::Length("max joint separation", max)] }
    }
}
