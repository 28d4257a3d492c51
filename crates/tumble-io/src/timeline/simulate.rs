//! A timeline by simulating a scene.

use crate::error::IoError;
use crate::scene::Scene;

use super::{Timeline, TimelineRecorder};

/// How long to run and how often to keep a frame.
#[derive(Clone, Copy, Debug)]
pub struct SimulateOptions {
    /// Simulated time, s (default: the scene's `world.duration`).
    pub duration: Option<f64>,
    /// Frames kept per simulated second, at most (one per step when the steps are slower).
    pub fps: f64,
}

impl Default for SimulateOptions {
    fn default() -> Self {
        SimulateOptions { duration: None, fps: 60.0 }
    }
}

impl Timeline {
    /// Runs `scene` for its duration at its time step, keeping about `fps` frames a second (the
    /// first and last always).
    pub fn simulate(scene: &Scene, options: &SimulateOptions) -> Result<Timeline, IoError> {
        let mut built = scene.build_world()?;
        let world = &mut built.world;
        let dt = scene.dt;
        let duration = options.duration.unwrap_or(scene.duration);
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(IoError::AtLine {
                path: scene.path.clone(),
                line: 1,
                message: format!("duration must be finite and >= 0, got {duration}"),
            });
        }
        let steps = step_count(duration, dt);
        let every = if options.fps.is_finite() && options.fps > 0.0 {
            ((1.0 / (options.fps * dt)).floor() as u64).max(1)
        } else {
            1
        };
        let mut recorder = TimelineRecorder::new(world, &scene.path);
        recorder.record(world);
        for step in 1..=steps {
            world.step(dt)?;
            if step % every == 0 || step == steps {
                recorder.record(world);
            }
            let e = world.kinetic_energy();
            if !e.is_finite() {
                return Err(IoError::AtLine {
                    path: scene.path.clone(),
                    line: 1,
                    message: format!(
                        "the simulation blew up: energy became {e} at t = {} s; try a smaller dt",
                        world.time()
                    ),
                });
            }
        }
        Ok(recorder.finish())
    }
}

/// Steps to cover `duration` (an integer multiple up to round-off is not rounded up).
fn step_count(duration: f64, dt: f64) -> u64 {
    let n = duration / dt;
    let nearest = n.round();
    if (n - nearest).abs() <= 1e-9 * nearest.max(1.0) {
        nearest as u64
    } else {
        n.ceil() as u64
    }
}
