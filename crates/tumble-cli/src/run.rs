//! Running a scene: step it for its duration, record it, and measure how well the invariants of
//! free motion held — the numbers a user looks at to trust (or doubt) a run.
//!
//! The invariants checked, for dynamic bodies:
//! - total energy E = kinetic + gravitational potential is constant;
//! - angular momentum about the system's centre of mass is constant (uniform gravity exerts no
//!   torque about it);
//! - linear momentum changes only by gravity: p(t) = p₀ + t·Σ mᵢ sᵢ g (sᵢ the gravity scale).
//!
//! Contacts and joints will add and remove energy legitimately; until they land, any drift is the
//! integrator's error.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use tumble::{BodyKind, DVec3, World};
use tumble_io::{IoError, RecordingWriter, Scene};

use crate::checkpoint::{self, Drift, RunState};

pub struct RunOptions {
    pub out: PathBuf,
    pub every: u64,
    pub duration: f64,
    pub dt: f64,
    /// Threads for the collision pipeline and the solver.
    pub threads: usize,
    pub checkpoint: Option<Checkpointing>,
}

/// Where and how often a run writes checkpoints (`checkpoint.rs`).
pub struct Checkpointing {
    pub path: PathBuf,
    /// Steps between checkpoints, >= 1.
    pub every: u64,
}

/// What a run did and how well it conserved what it should.
pub struct Summary {
    pub bodies: usize,
    /// Joints in the scene.
    pub joints: usize,
    /// Touching contact manifolds at the end of the run.
    pub contacts: usize,
    /// Dynamic bodies awake / asleep at the end of the run.
    pub awake: usize,
    pub sleeping: usize,
    /// Bodies taken out of the simulation because their state became non-finite.
    pub isolated: usize,
    pub steps: u64,
    pub dt: f64,
    pub simulated_time: f64,
    pub wall_time: Duration,
    /// max |E − E₀| / |E₀| (absolute when E₀ = 0).
    pub energy_drift: f64,
    pub energy_relative: bool,
    /// max |L − L₀| / |L₀| about the system centre of mass (absolute when L₀ = 0).
    pub angular_momentum_drift: f64,
    pub angular_momentum_relative: bool,
    /// max |p − p₀ − t Σ m s g|, kg·m/s.
    pub linear_momentum_drift: f64,
    pub out: PathBuf,
    pub frames: u64,
    pub every: u64,
    /// Wall time per step phase over the run.
    pub profile: tumble::profile::StepProfile,
}

impl Summary {
    pub fn render(&self, scene_label: &str) -> String {
        let wall = self.wall_time.as_secs_f64();
        let rate = if wall > 0.0 { format!("{:.0}", self.steps as f64 / wall) } else { "-".into() };
        let rel = |relative: bool| if relative { "" } else { " (absolute: initial value is 0)" };
        format!(
            "scene:                  {scene_label}\n\
             bodies:                 {} ({} awake, {} sleeping at the end), {} joint{}\n\
             contacts:               {}  touching manifolds at the end\n\
             {}\
             steps:                  {} (dt {} s)\n\
             simulated time:         {} s\n\
             wall time:              {:.3} s\n\
             steps/s:                {rate}\n\
             energy drift:           {:.3e}  max |E-E0|/|E0|, E = kinetic + potential{}\n\
             angular momentum drift: {:.3e}  max |L-L0|/|L0|, about the system centre of mass{}\n\
             linear momentum drift:  {:.3e}  max |p - p0 - M g t|, kg m/s\n\
             output:                 {} ({} frames, every {} step{})\n",
            self.bodies,
            self.awake,
            self.sleeping,
            self.joints,
            if self.joints == 1 { "" } else { "s" },
            self.contacts,
            if self.isolated > 0 {
                format!(
                    "isolated:               {}  bodies whose state became non-finite (left out)\n",
                    self.isolated
                )
            } else {
                String::new()
            },
            self.steps,
            self.dt,
            short(self.simulated_time),
            wall,
            self.energy_drift,
            rel(self.energy_relative),
            self.angular_momentum_drift,
            rel(self.angular_momentum_relative),
            self.linear_momentum_drift,
            self.out.display(),
            self.frames,
            self.every,
            if self.every == 1 { "" } else { "s" },
        )
    }
}

/// `x` to 9 decimals without trailing zeros: the accumulated time 19.999999999999186 reads as 20.
fn short(x: f64) -> String {
    let s = format!("{x:.9}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// `tumble run`: read, check overrides, run.
#[allow(clippy::too_many_arguments)]
pub fn run_scene_file(
    path: &Path,
    out: Option<PathBuf>,
    every: u64,
    duration: Option<f64>,
    dt: Option<f64>,
    profile: bool,
    threads: usize,
    checkpoint: Option<Checkpointing>,
) -> Result<String, String> {
    let scene = Scene::from_file(path).map_err(|e| e.to_string())?;
    if let Some(dt) = dt.filter(|&dt| !(dt.is_finite() && dt > 0.0)) {
        return Err(format!("--dt must be finite and > 0, got {dt}"));
    }
    if let Some(d) = duration.filter(|&d| !(d.is_finite() && d >= 0.0)) {
        return Err(format!("--duration must be finite and >= 0, got {d}"));
    }
    let out = out.unwrap_or_else(|| {
        let stem = path.file_stem().map_or("run".into(), |s| s.to_string_lossy().into_owned());
        PathBuf::from("out").join(format!("{stem}.csv"))
    });
    let options = RunOptions {
        out,
        every,
        duration: duration.unwrap_or(scene.duration),
        dt: dt.unwrap_or(scene.dt),
        threads,
        checkpoint,
    };
    let summary = run_scene(&scene, &options).map_err(|e| e.to_string())?;
    let mut text = summary.render(&path.display().to_string());
    if profile {
        text.push_str(&format!("\n{}\n", summary.profile));
    }
    Ok(text)
}

/// `tumble run --resume FILE`: carries on the run that wrote the checkpoint `FILE`, cutting its
/// recording back to what the checkpoint covers, and checkpointing to `FILE` as before.
pub fn resume_from_checkpoint(path: &Path) -> Result<String, String> {
    let (mut run, mut world) = checkpoint::read(path)?;
    let mut recording =
        RecordingWriter::resume(&run.out_absolute, run.every, run.frames, run.recording_bytes)
            .map_err(|e| format!("resuming from checkpoint {}: {e}", path.display()))?;
    let checkpointing = (run.checkpoint_every > 0).then_some(path);
    let summary = run_loop(&mut world, &mut run, &mut recording, checkpointing)?;
    Ok(summary.render(&run.scene.display().to_string()))
}

/// Number of steps to cover `duration`: rounds when `duration / dt` is an integer up to
/// round-off (20 s at 1/240 s is 4800 steps, not 4801), otherwise covers it fully.
pub fn step_count(duration: f64, dt: f64) -> u64 {
    let n = duration / dt;
    let nearest = n.round();
    if (n - nearest).abs() <= 1e-9 * nearest.max(1.0) {
        nearest as u64
    } else {
        n.ceil() as u64
    }
}

/// Total gravity force on the dynamic bodies, Σ mᵢ sᵢ g.
fn gravity_force(world: &World) -> DVec3 {
    world
        .bodies()
        .filter(|(_, b)| b.kind() == BodyKind::Dynamic)
        .map(|(_, b)| b.mass() * b.gravity_scale() * world.gravity())
        .sum()
}

pub fn run_scene(scene: &Scene, options: &RunOptions) -> Result<Summary, String> {
    let mut built = scene.build_world().map_err(|e| e.to_string())?;
    let world = &mut built.world;
    world.set_threads(options.threads).map_err(|e| format!("{}: {e}", scene.path.display()))?;
    let mut recording = RecordingWriter::create(&options.out, options.every).map_err(|e| e.to_string())?;
    recording.write_frame(world).map_err(|e| e.to_string())?;

    let energy = energy(world);
    let out_absolute =
        std::path::absolute(&options.out).map_err(|e| format!("{}: {e}", options.out.display()))?;
    let mut run = RunState {
        scene: scene.path.clone(),
        bodies: built.bodies.len(),
        out: options.out.clone(),
        out_absolute,
        every: options.every,
        dt: options.dt,
        steps: world.step_count() + step_count(options.duration, options.dt),
        checkpoint_every: options.checkpoint.as_ref().map_or(0, |c| c.every),
        frames: recording.frames_written(),
        recording_bytes: recording.bytes_written(),
        drift: Drift {
            e0: energy,
            l0: world.angular_momentum_about_com(),
            p0: world.linear_momentum(),
            weight: gravity_force(world),
            max_de: 0.0,
            max_dl: 0.0,
            max_dp: 0.0,
        },
        wall_seconds: 0.0,
    };
    let checkpoint_path = options.checkpoint.as_ref().map(|c| c.path.as_path());
    run_loop(world, &mut run, &mut recording, checkpoint_path)
}

/// E = kinetic + gravitational potential.
fn energy(world: &World) -> f64 {
    world.kinetic_energy() + world.potential_energy()
}

/// Steps `world` until `run.steps`, recording, measuring drift and writing checkpoints to
/// `checkpoint` every `run.checkpoint_every` steps; then the summary.
fn run_loop(
    world: &mut World,
    run: &mut RunState,
    recording: &mut RecordingWriter,
    checkpoint: Option<&Path>,
) -> Result<Summary, String> {
    let io = |e: IoError| e.to_string();
    let start = Instant::now();
    let show_progress = std::io::stderr().is_terminal();
    let mut progress: Option<indicatif::ProgressBar> = None;
    let first_step = world.step_count();
    while world.step_count() < run.steps {
        world.step(run.dt).map_err(|e| e.to_string())?;
        recording.record_step(world).map_err(io)?;
        let step = world.step_count();

        let e = energy(world);
        if !e.is_finite() {
            return Err(IoError::AtLine {
                path: run.scene.clone(),
                line: 1,
                message: format!(
                    "the simulation blew up: energy became {e} at t = {} s (step {step}); try a smaller dt",
                    world.time(),
                ),
            }
            .to_string());
        }
        let drift = &mut run.drift;
        drift.max_de = drift.max_de.max((e - drift.e0).abs());
        drift.max_dl = drift.max_dl.max((world.angular_momentum_about_com() - drift.l0).length());
        drift.max_dp =
            drift.max_dp.max((world.linear_momentum() - drift.p0 - drift.weight * world.time()).length());

        if let Some(path) = checkpoint.filter(|_| step.is_multiple_of(run.checkpoint_every.max(1))) {
            // The recording must be on disk up to the point the checkpoint says it is.
            recording.sync().map_err(io)?;
            run.frames = recording.frames_written();
            run.recording_bytes = recording.bytes_written();
            let wall_before = run.wall_seconds;
            run.wall_seconds += start.elapsed().as_secs_f64();
            checkpoint::write(path, run, world)?;
            run.wall_seconds = wall_before;
        }

        // A bar only for runs long enough to wonder about, and only for a person watching.
        if show_progress && (step - first_step) % 256 == 1 {
            if progress.is_none() && start.elapsed() > Duration::from_secs(1) {
                let bar = indicatif::ProgressBar::new(run.steps);
                bar.set_style(
                    indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} steps  eta {eta}")
                        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
                );
                progress = Some(bar);
            }
            if let Some(bar) = &progress {
                bar.set_position(step);
            }
        }
    }
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    let wall_time = Duration::from_secs_f64(run.wall_seconds) + start.elapsed();
    let frames = recording.frames_written();

    let drift = &run.drift;
    let relative = |drift: f64, scale: f64| if scale > 0.0 { (drift / scale, true) } else { (drift, false) };
    let (energy_drift, energy_relative) = relative(drift.max_de, drift.e0.abs());
    let (angular_momentum_drift, angular_momentum_relative) = relative(drift.max_dl, drift.l0.length());
    let dynamic = world.bodies().filter(|(_, b)| b.kind() == BodyKind::Dynamic).count();
    let awake = world.awake_body_count();
    let isolated = world.isolated_bodies().count();
    Ok(Summary {
        bodies: run.bodies,
        joints: world.joint_count(),
        contacts: world.contact_count(),
        awake,
        sleeping: dynamic - awake - isolated,
        isolated,
        steps: world.step_count(),
        dt: run.dt,
        simulated_time: world.time(),
        wall_time,
        energy_drift,
        energy_relative,
        angular_momentum_drift,
        angular_momentum_relative,
        linear_momentum_drift: drift.max_dp,
        out: run.out.clone(),
        frames,
        every: run.every,
        profile: *world.profile(),
    })
}

#[cfg(test)]
mod tests {
    use super::step_count;

    #[test]
    fn step_count_rounds_exact_multiples_and_covers_the_rest() {
        assert_eq!(step_count(20.0, 1.0 / 240.0), 4800);
        assert_eq!(step_count(1.0, 0.3), 4);
        assert_eq!(step_count(0.0, 0.01), 0);
    }
}
