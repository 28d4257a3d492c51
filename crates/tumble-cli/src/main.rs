//! `tumble`: the command-line face of the Tumble engine.
//!
//! ```text
//! tumble                      run the built-in demo (same as `tumble demo`)
//! tumble demo [--out FILE]    T-handle flipping in zero gravity → out/demo.csv
//! tumble run SCENE [--out FILE.csv] [--every N] [--duration S] [--dt S]
//! tumble mass MESH [--density D]      mass properties of an OBJ/STL as JSON
//! ```
//! Errors go to stderr as `error: …` with exit status 1; the program never ends in a panic
//! message for bad input.

mod demo;
mod mass;
mod run;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

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
        scene: PathBuf,
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
    },
    /// Print the mass properties of a closed mesh (OBJ or STL) as JSON.
    Mass {
        /// The mesh file (.obj or .stl).
        mesh: PathBuf,
        /// Density in kg/m³.
        #[arg(long, value_name = "D", default_value_t = 1000.0, allow_negative_numbers = true)]
        density: f64,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => demo::run_demo(&PathBuf::from(demo::DEFAULT_OUT)),
        Some(Command::Demo { out }) => demo::run_demo(&out),
        Some(Command::Run { scene, out, every, duration, dt }) => {
            run::run_scene_file(&scene, out, every, duration, dt)
        }
        Some(Command::Mass { mesh, density }) => mass::print_mass(&mesh, density),
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
