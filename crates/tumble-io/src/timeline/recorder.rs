//! Capturing frames of a live [`World`] into a [`Timeline`].

use std::collections::HashMap;
use std::path::Path;

use tumble::{BodyId, BodyKind, World};

use super::{BodyFrame, BodyInfo, ContactMark, JointInfo, Timeline, TimelineFrame};

/// Builds a timeline from a world: make it once the world has its bodies and joints, then call
/// [`TimelineRecorder::record`] at every frame wanted. Bodies added later are not drawn.
pub struct TimelineRecorder {
    timeline: Timeline,
    ids: Vec<BodyId>,
}

impl TimelineRecorder {
    pub fn new(world: &World, source: impl AsRef<Path>) -> TimelineRecorder {
        let mut ids = Vec::new();
        let mut bodies = Vec::new();
        for (id, body) in world.bodies() {
            ids.push(id);
            bodies.push(BodyInfo {
                name: body.name().to_string(),
                kind: body.kind(),
                shape: body.shape().cloned(),
                mass: if body.kind() == BodyKind::Dynamic { body.mass() } else { 0.0 },
                com_local: body.com_local(),
            });
        }
        let index: HashMap<BodyId, usize> = ids.iter().enumerate().map(|(i, &id)| (id, i)).collect();
        let joints = world
            .joints()
            .filter_map(|(_, j)| {
                Some(JointInfo {
                    name: j.name().to_string(),
                    kind: j.kind().name(),
                    body_a: *index.get(&j.body_a())?,
                    body_b: *index.get(&j.body_b())?,
                    frame_a_local: j.frame_a_local(),
                    frame_b_local: j.frame_b_local(),
                })
            })
            .collect();
        let timeline = Timeline {
            source: source.as_ref().to_owned(),
            gravity: world.gravity(),
            bodies,
            joints,
            frames: Vec::new(),
            simulated: true,
        };
        TimelineRecorder { timeline, ids }
    }

    /// Captures the world as it is now.
    pub fn record(&mut self, world: &World) {
        let bodies = self
            .ids
            .iter()
            .filter_map(|&id| world.body(id).ok())
            .map(|b| BodyFrame {
                position: b.position(),
                orientation: b.orientation(),
                linear_velocity: b.linear_velocity(),
                angular_velocity: b.angular_velocity(),
                angular_momentum: b.angular_momentum_about_com(),
                awake: b.kind() == BodyKind::Dynamic && b.is_awake(),
            })
            .collect::<Vec<_>>();
        let contacts = world
            .contacts()
            .iter()
            .filter(|c| !c.sensor)
            .flat_map(|c| {
                c.points.iter().map(move |p| ContactMark {
                    point: p.point,
                    normal: c.normal,
                    separation: p.separation,
                    impulse: p.normal_impulse,
                })
            })
            .collect();
        self.timeline.frames.push(TimelineFrame {
            t: world.time(),
            awake: bodies.iter().filter(|b| b.awake).count(),
            bodies,
            contacts,
            kinetic_energy: world.kinetic_energy(),
            potential_energy: world.potential_energy(),
            linear_momentum: world.linear_momentum(),
            angular_momentum: world.angular_momentum_about_com(),
        });
    }

    /// Marks the timeline as replayed (no contacts, sleep unknown).
    pub(super) fn set_replayed(&mut self) {
        self.timeline.simulated = false;
    }

    pub(super) fn ids(&self) -> &[BodyId] {
        &self.ids
    }

    pub(super) fn last_frame_mut(&mut self) -> Option<&mut super::TimelineFrame> {
        self.timeline.frames.last_mut()
    }

    pub fn finish(self) -> Timeline {
        self.timeline
    }
}
