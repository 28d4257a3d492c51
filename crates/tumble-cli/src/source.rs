//! What `view`, `export` and `plot` read: a scene to simulate, or a recording replayed over the
//! scene it came from (a CSV has only poses and velocities; the scene gives shapes and masses).

use std::path::{Path, PathBuf};

use tumble_io::{Recording, Scene, SimulateOptions, Timeline};

/// The input of a picture command.
pub struct SourceArgs<'a> {
    pub input: &'a Path,
    pub scene: Option<&'a Path>,
    pub duration: Option<f64>,
    /// Frames kept per simulated second (None: every step or every recorded frame).
    pub fps: Option<f64>,
}

pub enum InputKind {
    Scene,
    Recording,
}

pub fn input_kind(path: &Path) -> Result<InputKind, String> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("toml") => Ok(InputKind::Scene),
        Some("csv") => Ok(InputKind::Recording),
        _ => Err(format!(
            "{}: expected a scene (.toml) to simulate or a recording (.csv) with --scene",
            path.display()
        )),
    }
}

/// Reads a recording with a message that says what went wrong and where.
pub fn read_recording(path: &Path) -> Result<Recording, String> {
    let recording = Recording::read(path).map_err(|e| format!("cannot read the recording: {e}"))?;
    if recording.frames.is_empty() {
        return Err(format!("{}: the recording has no frames (only a header)", path.display()));
    }
    Ok(recording)
}

/// The timeline of a scene (simulated) or of a recording with its scene (replayed).
pub fn load_timeline(args: &SourceArgs) -> Result<Timeline, String> {
    if let Some(d) = args.duration.filter(|d| !(d.is_finite() && *d >= 0.0)) {
        return Err(format!("--duration must be finite and >= 0, got {d}"));
    }
    if let Some(f) = args.fps.filter(|f| !(f.is_finite() && *f > 0.0)) {
        return Err(format!("--fps must be finite and > 0, got {f}"));
    }
    match input_kind(args.input)? {
        InputKind::Scene => {
            if let Some(scene) = args.scene {
                return Err(format!(
                    "--scene {} is only for recordings; {} is itself a scene",
                    scene.display(),
                    args.input.display()
                ));
            }
            let scene = Scene::from_file(args.input).map_err(|e| e.to_string())?;
            let options = SimulateOptions { duration: args.duration, fps: args.fps.unwrap_or(f64::INFINITY) };
            Timeline::simulate(&scene, &options).map_err(|e| e.to_string())
        }
        InputKind::Recording => {
            let Some(scene_path) = args.scene else {
                return Err(format!(
                    "{} is a recording, which holds only poses and velocities: pass the scene it was \
                     made from with --scene SCENE.toml (or give the scene itself to simulate it)",
                    args.input.display()
                ));
            };
            let recording = read_recording(args.input)?;
            let scene = Scene::from_file(scene_path).map_err(|e| e.to_string())?;
            let mut timeline = Timeline::replay(&scene, &recording, args.input).map_err(|e| e.to_string())?;
            if let Some(d) = args.duration {
                let end = timeline.frames[0].t + d;
                timeline.frames.retain(|f| f.t <= end + 1e-9);
            }
            if let Some(fps) = args.fps {
                timeline.thin_to_rate(fps);
            }
            Ok(timeline)
        }
    }
}

/// `out/<input stem>.<ext>` when no output was given.
pub fn default_output(input: &Path, ext: &str) -> PathBuf {
    let stem = input.file_stem().map_or("tumble".into(), |s| s.to_string_lossy().into_owned());
    PathBuf::from("out").join(format!("{stem}.{ext}"))
}

/// Creates the folder `path` goes in.
pub fn create_parent(path: &Path) -> Result<(), String> {
    match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display())),
        None => Ok(()),
    }
}
