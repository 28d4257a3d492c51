//! Soak test: steps the `rain` (2,000 spheres into a walled bin) and `ragdolls` (100 jointed
//! ragdolls in a pile) scenes for a wall-clock time and prints duration, steps, the largest total
//! energy, bodies that escaped, and resident memory at the start, after warm-up and at the end.
//!
//! ```text
//! cargo run --release -p tumble --example soak -- [--seconds S] [--scene rain|ragdolls|both] [--size N]
//! ```
//! Default: one hour per scene, both scenes. Exit status 1 if energy rose above its start by more
//! than 1%, a body escaped, a body was isolated, or memory after warm-up grew by more than 10%
//! (+16 MiB).

mod run;

use std::time::Duration;

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| args.iter().position(|a| a == flag).and_then(|i| args.get(i + 1)).cloned();
    let seconds: f64 = value("--seconds").map_or(3600.0, |s| s.parse().expect("--seconds takes a number"));
    let size: Option<usize> = value("--size").map(|s| s.parse().expect("--size takes a whole number"));
    let scenes: Vec<&str> = match value("--scene").as_deref() {
        None | Some("both") => vec!["rain", "ragdolls"],
        Some("rain") => vec!["rain"],
        Some("ragdolls") => vec!["ragdolls"],
        Some(other) => panic!("--scene: rain, ragdolls or both, not {other}"),
    };
    let mut ok = true;
    for name in scenes {
        let report = run::soak(name, size, Duration::from_secs_f64(seconds));
        println!("{report}");
        let problems = run::problems(&report);
        for p in &problems {
            println!("  FAIL: {p}");
        }
        ok &= problems.is_empty();
    }
    if ok {
        std::process::ExitCode::SUCCESS
    } else {
        std::process::ExitCode::FAILURE
    }
}
