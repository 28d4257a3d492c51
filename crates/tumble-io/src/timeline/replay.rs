//! A timeline by replaying a recording over its scene: the scene gives the shapes and masses, the
//! recording the poses and velocities; energies and momenta are recomputed from both.

use std::collections::HashMap;

use crate::error::IoError;
use crate::recording::Recording;
use crate::scene::Scene;

use super::{Timeline, TimelineRecorder};

impl Timeline {
    /// Every frame of `recording` (whose path is `recording_path`, for messages) drawn with the
    /// bodies of `scene`. Each body named in the recording must be in the scene; scene bodies the
    /// recording lacks stay where the scene puts them.
    pub fn replay(
        scene: &Scene,
        recording: &Recording,
        recording_path: &std::path::Path,
    ) -> Result<Timeline, IoError> {
        let mut built = scene.build_world()?;
        let world = &mut built.world;
        let mut recorder = TimelineRecorder::new(world, &scene.path);
        recorder.set_replayed();
        let by_name: HashMap<String, tumble::BodyId> = recorder
            .ids()
            .iter()
            .filter_map(|&id| Some((world.body(id).ok()?.name().to_string(), id)))
            .collect();
        let bad = |message: String| IoError::AtLine { path: recording_path.to_owned(), line: 1, message };
        if recording.frames.is_empty() {
            return Err(bad("the recording has no frames".into()));
        }
        for frame in &recording.frames {
            for sample in &frame.bodies {
                let id = *by_name.get(&sample.name).ok_or_else(|| {
                    bad(format!(
                        "body \"{}\" (at t = {} s) is not in the scene {}",
                        sample.name,
                        frame.t,
                        scene.path.display()
                    ))
                })?;
                world
                    .set_pose(id, sample.position, sample.orientation)
                    .and_then(|_| world.set_linear_velocity(id, sample.linear_velocity))
                    .and_then(|_| world.set_angular_velocity(id, sample.angular_velocity))
                    .map_err(|e| bad(format!("body \"{}\" at t = {} s: {e}", sample.name, frame.t)))?;
            }
            recorder.record(world);
            // The world's clock did not move; the frame's time is the recording's.
            if let Some(last) = recorder.last_frame_mut() {
                last.t = frame.t;
            }
        }
        Ok(recorder.finish())
    }
}
