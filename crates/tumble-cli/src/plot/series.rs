//! The numbers a plot draws, from either source: a timeline (a simulated scene, or a recording
//! replayed over its scene: masses known) or a bare recording (ω only: a CSV has no masses).

use glam::{DQuat, DVec3};
use tumble_io::{Recording, Timeline};

/// Time series by name; `None` where the source cannot give it.
pub struct PlotData {
    pub t: Vec<f64>,
    /// Per body (in order): its name, and ω (world frame, rad/s) and orientation per frame
    /// (NaN where the frame lacks the body).
    pub omega: Vec<BodyTrack>,
    /// Kinetic and potential energy, J.
    pub energy: Option<(Vec<f64>, Vec<f64>)>,
    /// Linear momentum, kg·m/s.
    pub momentum: Option<Vec<DVec3>>,
    /// Angular momentum about the system's centre of mass, kg·m²/s.
    pub angular_momentum: Option<Vec<DVec3>>,
}

impl PlotData {
    pub fn from_timeline(timeline: &Timeline) -> PlotData {
        let frames = &timeline.frames;
        PlotData {
            t: frames.iter().map(|f| f.t).collect(),
            omega: timeline
                .bodies
                .iter()
                .enumerate()
                .map(|(i, b)| BodyTrack {
                    name: b.name.clone(),
                    omega_world: frames.iter().map(|f| f.bodies[i].angular_velocity).collect(),
                    orientation: frames.iter().map(|f| f.bodies[i].orientation).collect(),
                })
                .collect(),
            energy: Some((
                frames.iter().map(|f| f.kinetic_energy).collect(),
                frames.iter().map(|f| f.potential_energy).collect(),
            )),
            momentum: Some(frames.iter().map(|f| f.linear_momentum).collect()),
            angular_momentum: Some(frames.iter().map(|f| f.angular_momentum).collect()),
        }
    }

    pub fn from_recording(recording: &Recording) -> PlotData {
        let mut names: Vec<String> = Vec::new();
        for frame in &recording.frames {
            for b in &frame.bodies {
                if !names.contains(&b.name) {
                    names.push(b.name.clone());
                }
            }
        }
        let omega = names
            .iter()
            .map(|name| {
                let samples: Vec<_> =
                    recording.frames.iter().map(|f| f.bodies.iter().find(|b| &b.name == name)).collect();
                BodyTrack {
                    name: name.clone(),
                    omega_world: samples
                        .iter()
                        .map(|s| s.map_or(DVec3::NAN, |b| b.angular_velocity))
                        .collect(),
                    orientation: samples
                        .iter()
                        .map(|s| s.map_or(DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0), |b| b.orientation))
                        .collect(),
                }
            })
            .collect();
        PlotData {
            t: recording.frames.iter().map(|f| f.t).collect(),
            omega,
            energy: None,
            momentum: None,
            angular_momentum: None,
        }
    }
}

/// A body's angular velocity and orientation over the frames.
pub struct BodyTrack {
    pub name: String,
    pub omega_world: Vec<DVec3>,
    pub orientation: Vec<DQuat>,
}

impl BodyTrack {
    /// ω in the body frame, `q⁻¹ ω q`: what a rider on the body sees.
    pub fn omega_body(&self) -> Vec<DVec3> {
        self.omega_world.iter().zip(&self.orientation).map(|(w, q)| q.inverse() * *w).collect()
    }
}

/// One line of a panel.
pub struct Line {
    pub label: String,
    pub values: Vec<f64>,
}

/// One chart: a title, a y-axis label with units, and its lines over the shared time axis.
pub struct Panel {
    pub title: String,
    pub y_label: String,
    pub lines: Vec<Line>,
}

/// x, y, z and the magnitude of a vector series, as four lines.
pub fn vector_lines(symbol: &str, values: &[DVec3]) -> Vec<Line> {
    let component = |k: usize, axis: &str| Line {
        label: format!("{symbol}{axis}"),
        values: values.iter().map(|v| v[k]).collect(),
    };
    vec![
        component(0, "x"),
        component(1, "y"),
        component(2, "z"),
        Line { label: format!("|{symbol}|"), values: values.iter().map(|v| v.length()).collect() },
    ]
}
