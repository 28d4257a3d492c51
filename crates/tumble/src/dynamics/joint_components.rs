//! The solved joints grouped by the dynamic bodies they connect, so that the joint stages of the
//! substeps run on all the step's threads with the numbers of one thread.
//!
//! A joint's warm start, solve and relax read and write only the joint and its two bodies. Two
//! joints that share no dynamic body therefore never see each other's work within a stage, and
//! neither do two *components* — the sets of joints joined through dynamic bodies (a ragdoll, a
//! chain, a robot). A body that is not dynamic (the ground, a kinematic or sleeping body) takes
//! no impulse: the solver hands each joint a private copy of it (`SolveData::joints_with_bodies`),
//! so it joins nothing. Solving the components one after the other, each in slot order, is then
//! the same arithmetic as the whole slot-ordered sweep, and splitting the components between
//! threads changes nothing either: the result is the same bits for any thread count.
//!
//! A scene of many figures splits into many components; a single figure stays on one thread, as
//! before.

use crate::dynamics::island::UnionFind;
use crate::dynamics::joint::Joint;
use crate::dynamics::solver_body::SolverBody;
use crate::id::SlotPool;
use std::ops::Range;

/// Marks a body slot that is not (yet) the root of a component.
const NONE: u32 = u32::MAX;

/// The solved joints' slots, component by component.
#[derive(Clone, Debug, Default)]
pub(crate) struct JointComponents {
    /// Joint slots: each component's together, in slot order, the components in the order of
    /// their lowest joint slot.
    order: Vec<u32>,
    /// Where each component starts in `order`, then `order.len()`.
    starts: Vec<u32>,
    /// Scratch: the union–find over body slots, then the counting sort's next place per
    /// component.
    parent: Vec<u32>,
    /// Per body slot that roots a component: the component's index (`NONE` otherwise).
    component_of_root: Vec<u32>,
    /// Per solved joint in slot order: its component.
    component_of_joint: Vec<u32>,
}

impl JointComponents {
    /// Groups the joints marked `solving` by the dynamic bodies (`bodies`, by slot) they connect.
    pub fn build(&mut self, joints: &SlotPool<Joint>, bodies: &[SolverBody]) {
        let solving = || joints.iter().filter(|(_, joint)| joint.solving);
        let dynamic = |slot: usize| bodies[slot].is_dynamic();
        let mut sets = UnionFind::new(bodies.len(), &mut self.parent);
        for (_, joint) in solving() {
            let (a, b) = (joint.body_a.index(), joint.body_b.index());
            if dynamic(a) && dynamic(b) {
                sets.union(a as u32, b as u32);
            }
        }
        // Number the components in the order of their first joint; a joint with no dynamic body
        // is a component of its own.
        self.component_of_root.clear();
        self.component_of_root.resize(bodies.len(), NONE);
        self.component_of_joint.clear();
        let mut components = 0u32;
        for (_, joint) in solving() {
            let (a, b) = (joint.body_a.index(), joint.body_b.index());
            let end = if dynamic(a) {
                Some(a)
            } else if dynamic(b) {
                Some(b)
            } else {
                None
            };
            let component = match end {
                Some(end) => {
                    let root = sets.find(end as u32) as usize;
                    if self.component_of_root[root] == NONE {
                        self.component_of_root[root] = components;
                        components += 1;
                    }
                    self.component_of_root[root]
                }
                None => {
                    components += 1;
                    components - 1
                }
            };
            self.component_of_joint.push(component);
        }
        // Counting sort of the joints by component, stable (slot order within each).
        self.starts.clear();
        self.starts.resize(components as usize + 1, 0);
        for &c in &self.component_of_joint {
            self.starts[c as usize + 1] += 1;
        }
        for c in 0..components as usize {
            self.starts[c + 1] += self.starts[c];
        }
        self.order.clear();
        self.order.resize(self.component_of_joint.len(), 0);
        // The union–find is done with: its buffer holds the next place of each component.
        let mut next = std::mem::take(&mut self.parent);
        next.clear();
        next.extend_from_slice(&self.starts[..components as usize]);
        for ((id, _), &c) in solving().zip(&self.component_of_joint) {
            self.order[next[c as usize] as usize] = id.index() as u32;
            next[c as usize] += 1;
        }
        self.parent = next;
    }

    /// Whether there are joints to solve.
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// The number of components.
    pub fn count(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }

    /// The joint slots of the components `components` (a piece of a joint stage: whole
    /// components, each on one thread).
    pub fn slots(&self, components: Range<usize>) -> &[u32] {
        &self.order[self.starts[components.start] as usize..self.starts[components.end] as usize]
    }

    /// The components, each a list of joint slots (for tests).
    #[cfg(test)]
    pub fn components(&self) -> Vec<&[u32]> {
        self.starts.windows(2).map(|w| &self.order[w[0] as usize..w[1] as usize]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::joint::{BallJoint, JointDef, JointKind};
    use crate::math::DVec3;
    use crate::shape::{Shape, Sphere};
    use crate::{BodyDef, BodyId, BodyKind, World};

    /// A world of a static ground, seven dynamic balls (the seventh asleep: a fixed solver body)
    /// and a kinematic one, and joints (in slot order) `b1–b2, ground–b3, b2–b3, b4–b5,
    /// kinematic–b7, b6–ground, b5–b6`, all solved.
    fn world_of_figures() -> (World, Vec<SolverBody>) {
        let mut world = World::new(Default::default()).unwrap();
        let body = |world: &mut World, kind: BodyKind, x: f64| -> BodyId {
            let shape = Some(Shape::Sphere(Sphere::new(0.1).unwrap()));
            let position = DVec3::new(x, 0.0, 1.0);
            world.add_body(BodyDef { kind, shape, position, ..Default::default() }).unwrap()
        };
        let ground = body(&mut world, BodyKind::Static, 0.0);
        let balls: Vec<_> = (1..=6).map(|k| body(&mut world, BodyKind::Dynamic, k as f64)).collect();
        let kinematic = body(&mut world, BodyKind::Kinematic, 7.0);
        let asleep = body(&mut world, BodyKind::Dynamic, 8.0);
        let ball = |k: usize| balls[k - 1];
        let pairs = [
            (ball(1), ball(2)),
            (ground, ball(3)),
            (ball(2), ball(3)),
            (ball(4), ball(5)),
            (kinematic, asleep),
            (ball(6), ground),
            (ball(5), ball(6)),
        ];
        for (a, b) in pairs {
            world.add_joint(JointDef::new(a, b, DVec3::ZERO, JointKind::Ball(BallJoint::new()))).unwrap();
        }
        for (_, joint) in world.joints.iter_mut() {
            joint.solving = true;
        }
        let mut bodies = vec![SolverBody::FIXED; world.bodies.capacity_index()];
        for (id, b) in world.bodies.iter() {
            bodies[id.index()] = SolverBody::from_body(b);
        }
        bodies[asleep.index()] = SolverBody::FIXED;
        (world, bodies)
    }

    #[test]
    fn joints_join_through_dynamic_bodies_only() {
        let (world, bodies) = world_of_figures();
        let mut components = JointComponents::default();
        components.build(&world.joints, &bodies);
        // The ground joins nothing (joint 1 is with the first figure through ball 3, joint 5
        // with the second through ball 6), and the joint between the kinematic body and the
        // sleeping one moves no dynamic body: a component of its own.
        assert_eq!(components.components(), [&[0, 1, 2][..], &[3, 5, 6], &[4]]);
        // Joints not solved are left out, and a figure cut at its middle joint falls apart.
        let mut world = world;
        for slot in [1, 2] {
            let id = world.joints.id_of_slot(slot).unwrap();
            world.joints.get_mut(id).unwrap().solving = false;
        }
        components.build(&world.joints, &bodies);
        assert_eq!(components.components(), [&[0][..], &[3, 5, 6], &[4]]);
    }

    #[test]
    fn pieces_of_components_are_their_joints_in_order() {
        let (world, bodies) = world_of_figures();
        let mut components = JointComponents::default();
        components.build(&world.joints, &bodies);
        let whole = components.components();
        assert_eq!(components.count(), whole.len());
        assert_eq!(components.slots(0..components.count()), [0, 1, 2, 3, 5, 6, 4]);
        for start in 0..whole.len() {
            for end in start..=whole.len() {
                assert_eq!(components.slots(start..end), whole[start..end].concat(), "{start}..{end}");
            }
        }
    }
}
