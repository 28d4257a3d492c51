//! `tumble`: the command-line face of the Tumble engine.
//!
//! ```text
//! tumble                      run the built-in demo (same as `tumble demo`)
//! tumble demo [--out FILE]    T-handle flipping in zero gravity → out/demo.csv
//! tumble run SCENE [--out FILE.csv] [--every N] [--duration S] [--dt S] [--profile] [--threads N]
//!                  [--checkpoint FILE [--checkpoint-every N]]
//! tumble run --resume FILE    carry on a killed run from its checkpoint
//! tumble bench NAME [--threads N] [--steps N] [--runs N] [--size N] [--substeps N] [--json | --profile]
//! tumble mass MESH [--density D]      mass properties of an OBJ/STL as JSON
//! tumble view SCENE.toml | REC.csv --scene SCENE.toml [-o out.html]   a page that plays it in 3D
//! tumble export SCENE.toml | REC.csv --scene SCENE.toml [-o out.glb]  glTF 2.0 animation
//! tumble plot SCENE.toml | REC.csv [--scene S] [-o out.png|svg] [--what energy,omega:BODY,...]
//! ```
//! Errors go to stderr as `error: …` with exit status 1; the program never ends in a panic
//! message for bad input.

mod bench;
mod checkpoint;
mod demo;
mod export;
mod mass;
mod plot;
mod run;
mod scene_export;
mod source;
mod view;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use source::SourceArgs;

#[derive(Parser)]
#[command(
    name = "tumble",
    version,
    about = "Tumble rigid-body dynamics: run scenes, record them, compute mass properties",
    after_help = "With no command, runs the built-in demo (`tumble demo`)."
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Run the built-in demo: a T-handle flipping in zero gravity (the Dzhanibekov effect).
    Demo {
        /// Where to write the recording (CSV).
        #[arg(long, value_name = "FILE.csv", default_value = "out/demo.csv")]
        out: PathBuf,
    },
    /// Run a scene file, record it to CSV and print a summary with conservation checks.
    Run {
        /// The scene (TOML).
        #[arg(required_unless_present = "resume")]
        scene: Option<PathBuf>,
        /// Where to write the recording [default: out/<scene name>.csv].
        #[arg(long, value_name = "FILE.csv")]
        out: Option<PathBuf>,
        /// Record every N-th step (the initial state is always recorded).
        #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
        every: u64,
        /// Simulated time in seconds, overriding the scene's `world.duration`.
        #[arg(long, value_name = "S", allow_negative_numbers = true)]
        duration: Option<f64>,
        /// Time step in seconds, overriding the scene's `world.dt`.
        #[arg(long, value_name = "S", allow_negative_numbers = true)]
        dt: Option<f64>,
        /// Write a checkpoint to FILE every --checkpoint-every steps, replacing it atomically (a
        /// kill at any moment leaves the previous one whole); `--resume FILE` carries the run on.
        #[arg(long, value_name = "FILE")]
        checkpoint: Option<PathBuf>,
        /// Steps between checkpoints.
        #[arg(long, value_name = "N", default_value_t = 1000, requires = "checkpoint", value_parser = clap::value_parser!(u64).range(1..))]
        checkpoint_every: u64,
        /// Carry on the run that wrote checkpoint FILE: its recording is cut back to the frames the
        /// checkpoint covers and continued, to the same bytes an uninterrupted run writes; new
        /// checkpoints go to FILE.
        #[arg(long, value_name = "FILE", conflicts_with_all = ["scene", "out", "every", "duration", "dt", "checkpoint", "checkpoint_every", "profile", "threads"])]
        resume: Option<PathBuf>,
        /// Print the wall time of each step phase (broad phase, narrow phase, solve, ...), summed
        /// over the run. SCENE may also name a built-in benchmark scene (see `tumble bench`),
        /// which is run for its step count (or --duration) without a recording.
        #[arg(long)]
        profile: bool,
        /// Threads for the collision pipeline and the solver (results are identical for any count).
        #[arg(long, value_name = "N", default_value_t = 1)]
        threads: usize,
    },
    /// Time a built-in benchmark scene (pyramid, large_pyramid, rain, chain, ragdolls,
    /// convex_pile, tumbling): steps/s as the median of the runs, the settings, and the scene's
    /// quality result.
    Bench {
        /// The scene's name.
        scene: String,
        /// Threads for the collision pipeline and the solver (results are identical for any count).
        #[arg(long, value_name = "N", default_value_t = 1)]
        threads: usize,
        /// Steps per run [default: the scene's own count].
        #[arg(long, value_name = "N")]
        steps: Option<u32>,
        /// Runs; steps/s is their median.
        #[arg(long, value_name = "N", default_value_t = 5)]
        runs: usize,
        /// The scene's size: base row of a pyramid, or number of spheres, links, ragdolls, hulls
        /// or bodies [default: the scene's own].
        #[arg(long, value_name = "N")]
        size: Option<usize>,
        /// Solver substeps per step [default: the scene's own, the engine default 8].
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
        substeps: Option<u32>,
        /// Another solver setting, KEY=VALUE (a `SolverSettings` field, e.g. contact_hertz=30);
        /// may be given several times.
        #[arg(long, value_name = "KEY=VALUE")]
        solver: Vec<String>,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// Instead of timing runs, make one run with these settings and print the wall time of
        /// each step phase (as `tumble run SCENE --profile`).
        #[arg(long, conflicts_with_all = ["runs", "json"])]
        profile: bool,
        /// Write the scene (bodies, shapes, joints, settings) as JSON to FILE and exit, for the
        /// peer engines in bench/ to build the same scene.
        #[arg(long, value_name = "FILE.json")]
        export: Option<PathBuf>,
    },
    /// Print the mass properties of a closed mesh (OBJ or STL) as JSON.
    Mass {
        /// The mesh file (.obj or .stl).
        mesh: PathBuf,
        /// Density in kg/m³.
        #[arg(long, value_name = "D", default_value_t = 1000.0, allow_negative_numbers = true)]
        density: f64,
    },
    /// Write one self-contained HTML page that plays a run in 3D (works offline in any current
    /// browser): orbit, scrub, overlays for contacts, joints, frames, ω and L.
    View {
        #[command(flatten)]
        input: Input,
        /// The page to write [default: out/<input name>.html].
        #[arg(short, long, value_name = "FILE.html")]
        out: Option<PathBuf>,
        /// Frames per simulated second kept in the page.
        #[arg(long, value_name = "N", default_value_t = 60.0)]
        fps: f64,
    },
    /// Export a run as binary glTF 2.0 (.glb): a node per body with its mesh, animated (Y up).
    Export {
        #[command(flatten)]
        input: Input,
        /// The file to write [default: out/<input name>.glb].
        #[arg(short, long, value_name = "FILE.glb")]
        out: Option<PathBuf>,
        /// Keyframes per simulated second.
        #[arg(long, value_name = "N", default_value_t = 60.0)]
        fps: f64,
    },
    /// Plot time series of a run (PNG or SVG): energy, momenta, a body's angular velocity.
    Plot {
        #[command(flatten)]
        input: Input,
        /// The image to write, .png or .svg [default: out/<input name>.png].
        #[arg(short, long, value_name = "FILE.png|svg")]
        out: Option<PathBuf>,
        /// Comma-separated panels: energy, momentum, angular_momentum, omega[:BODY] (world frame),
        /// omega_body[:BODY] (body frame)
        /// [default: energy,angular_momentum with masses known, else omega].
        #[arg(long, value_name = "LIST")]
        what: Option<String>,
        /// Image size in pixels, WIDTHxHEIGHT [default: 1000 wide, 360 per panel].
        #[arg(long, value_name = "WxH")]
        size: Option<String>,
    },
}

/// The input of `view`, `export` and `plot`.
#[derive(Args)]
struct Input {
    /// A scene (.toml) to simulate, or a recording (.csv) made from the scene given by --scene.
    #[arg(value_name = "SCENE_OR_RECORDING")]
    input: PathBuf,
    /// The scene a recording was made from (it gives the shapes and masses).
    #[arg(long, value_name = "SCENE.toml")]
    scene: Option<PathBuf>,
    /// Simulated (or replayed) time in seconds [default: the scene's `world.duration`, or the
    /// whole recording].
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    duration: Option<f64>,
}

impl Input {
    fn source(&self, fps: Option<f64>) -> SourceArgs<'_> {
        SourceArgs { input: &self.input, scene: self.scene.as_deref(), duration: self.duration, fps }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => demo::run_demo(&PathBuf::from(demo::DEFAULT_OUT)),
        Some(Command::Demo { out }) => demo::run_demo(&out),
        Some(Command::Run {
            scene,
            out,
            every,
            duration,
            dt,
            profile,
            threads,
            checkpoint,
            checkpoint_every,
            resume,
        }) => {
            match (resume, scene) {
                (Some(resume), _) => run::resume_from_checkpoint(&resume),
                (None, Some(scene)) => {
                    let name = scene.to_string_lossy();
                    if !scene.exists() && tumble::scenes::NAMES.contains(&name.as_ref()) {
                        // A built-in scene runs its own step count, or as many steps as cover
                        // --duration.
                        let steps = duration.map(|d| run::step_count(d.max(0.0), tumble::scenes::DT) as u32);
                        let options = bench::BenchOptions {
                            threads,
                            steps,
                            runs: 1,
                            size: None,
                            substeps: None,
                            solver: Vec::new(),
                            json: false,
                        };
                        bench::profile(&name, &options)
                    } else {
                        let checkpoint =
                            checkpoint.map(|path| run::Checkpointing { path, every: checkpoint_every });
                        run::run_scene_file(&scene, out, every, duration, dt, profile, threads, checkpoint)
                    }
                }
                (None, None) => Err("give a scene to run, or --resume CHECKPOINT".into()),
            }
        }
        Some(Command::Bench {
            scene,
            threads,
            steps,
            runs,
            size,
            substeps,
            solver,
            json,
            profile,
            export,
        }) => {
            let options = bench::BenchOptions { threads, steps, runs, size, substeps, solver, json };
            match export {
                Some(path) => {
                    bench::build_scene(&scene, size).and_then(|s| scene_export::export(&s)).and_then(|text| {
                        std::fs::write(&path, text)
                            .map(|()| format!("wrote {}\n", path.display()))
                            .map_err(|e| format!("cannot write {}: {e}", path.display()))
                    })
                }
                None if profile => bench::profile(&scene, &options),
                None => bench::bench(&scene, &options),
            }
        }
        Some(Command::Mass { mesh, density }) => mass::print_mass(&mesh, density),
        Some(Command::View { input, out, fps }) => view::view(&input.source(Some(fps)), out),
        Some(Command::Export { input, out, fps }) => export::export(&input.source(Some(fps)), out),
        Some(Command::Plot { input, out, what, size }) => {
            let out = out.unwrap_or_else(|| plot::default_plot_output(&input.input));
            plot::plot(&input.source(None), &out, what.as_deref(), size.as_deref())
        }
    };
    match result {
        Ok(text) => {
            // A closed pipe (`tumble mass x.obj | head -1`) is not an error worth reporting.
            let _ = std::io::stdout().lock().write_all(text.as_bytes());
            ExitCode::SUCCESS
        }
        Err(message) => {
            let _ = writeln!(std::io::stderr().lock(), "error: {message}");
            ExitCode::FAILURE
        }
    }
}
