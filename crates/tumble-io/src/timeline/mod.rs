//! A timeline: everything a picture of a run needs, frame by frame — the bodies' shapes and mass
//! properties once, then at each frame their poses, velocities, angular momenta and sleep state,
//! the contact points, and the world's energy and momenta. The viewer page, the glTF export and
//! the plots are all drawn from one.
//!
//! A timeline comes from simulating a scene ([`Timeline::simulate`], with contacts and sleep) or
//! from replaying a recording over its scene ([`Timeline::replay`]: a CSV holds only poses and
//! velocities, so the scene supplies the shapes and masses and the energies are recomputed; there
//! are no contacts and every body counts as awake). Any program can also build one from its own
//! world with [`TimelineRecorder`].

mod recorder;
mod replay;
mod simulate;

pub use recorder::TimelineRecorder;
pub use simulate::SimulateOptions;

use std::path::PathBuf;

use tumble::{BodyKind, DQuat, DVec3, Shape, Transform};

/// A body as drawn: what does not change over the run.
#[derive(Clone, Debug)]
pub struct BodyInfo {
    pub name: String,
    pub kind: BodyKind,
    pub shape: Option<Shape>,
    /// kg (0 for static and kinematic bodies).
    pub mass: f64,
    /// Centre of mass in the body frame.
    pub com_local: DVec3,
}

/// A joint as drawn: its two frames (origin at the anchor, Z along the axis) in its bodies'
/// frames; body indices are into [`Timeline::bodies`].
#[derive(Clone, Debug)]
pub struct JointInfo {
    pub name: String,
    pub kind: &'static str,
    pub body_a: usize,
    pub body_b: usize,
    pub frame_a_local: Transform,
    pub frame_b_local: Transform,
}

/// One body at one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyFrame {
    /// Body-frame origin, world.
    pub position: DVec3,
    pub orientation: DQuat,
    /// Of the centre of mass.
    pub linear_velocity: DVec3,
    /// World frame, rad/s.
    pub angular_velocity: DVec3,
    /// `I ω` about the body's centre of mass, world frame, kg·m²/s.
    pub angular_momentum: DVec3,
    pub awake: bool,
}

/// One contact point at one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactMark {
    pub point: DVec3,
    /// Unit, from the first body towards the second.
    pub normal: DVec3,
    /// Negative when the bodies overlap, m.
    pub separation: f64,
    /// Normal impulse of the step, N·s.
    pub impulse: f64,
}

/// The world at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct TimelineFrame {
    /// s
    pub t: f64,
    /// In the order of [`Timeline::bodies`].
    pub bodies: Vec<BodyFrame>,
    pub contacts: Vec<ContactMark>,
    /// J, of the dynamic bodies.
    pub kinetic_energy: f64,
    /// J, gravitational, zero at the origin.
    pub potential_energy: f64,
    /// kg·m/s
    pub linear_momentum: DVec3,
    /// About the system's centre of mass, kg·m²/s.
    pub angular_momentum: DVec3,
    /// Dynamic bodies awake.
    pub awake: usize,
}

/// What `tumble view`, `export` and `plot` draw.
#[derive(Clone, Debug)]
pub struct Timeline {
    /// The scene the run came from (for titles).
    pub source: PathBuf,
    pub gravity: DVec3,
    pub bodies: Vec<BodyInfo>,
    pub joints: Vec<JointInfo>,
    pub frames: Vec<TimelineFrame>,
    /// True when simulated here (contacts and sleep are known); false when replayed.
    pub simulated: bool,
}

impl Timeline {
    /// The index of the body called `name`.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// Keeps frames at most `fps` per simulated second (always the first and the last).
    pub fn thin_to_rate(&mut self, fps: f64) {
        if !(fps.is_finite() && fps > 0.0) || self.frames.len() < 3 {
            return;
        }
        let min_gap = 1.0 / fps - 1e-9;
        let last = self.frames.len() - 1;
        let mut kept_t = f64::NEG_INFINITY;
        let mut index = 0;
        self.frames.retain(|f| {
            let keep = index == 0 || index == last || f.t - kept_t >= min_gap;
            if keep {
                kept_t = f.t;
            }
            index += 1;
            keep
        });
    }

    /// Simulated time covered, s.
    pub fn duration(&self) -> f64 {
        match (self.frames.first(), self.frames.last()) {
            (Some(a), Some(b)) => b.t - a.t,
            _ => 0.0,
        }
    }
}
