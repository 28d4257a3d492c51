//! The soak run, shared by the `soak` example (long runs) and `tests/soak.rs` (the short one CI
//! runs): step a scene for a wall-clock budget and watch for slow failures — energy creeping up,
//! bodies leaking out of the scene, memory growing.

use std::time::{Duration, Instant};

use tumble::scenes;
use tumble::{BodyKind, World};

/// What a soak run saw.
#[derive(Clone, Debug)]
pub struct SoakReport {
    pub scene: &'static str,
    pub bodies: usize,
    pub duration: Duration,
    pub steps: u64,
    /// Total energy (kinetic + gravitational potential, zero at z = 0) at the start and its
    /// largest value over the run, J.
    pub initial_energy: f64,
    pub max_energy: f64,
    /// Dynamic bodies outside the scene at the end (outside the bin for `rain`, below the ground or
    /// far off for `ragdolls`), and the most seen at any check.
    pub escaped: usize,
    pub max_escaped: usize,
    /// Bodies isolated for non-finite state.
    pub isolated: usize,
    /// Resident memory before the first step, after the warm-up (the first tenth of the run, when
    /// contacts and caches reach their working size) and at the end, bytes.
    pub rss_start: u64,
    pub rss_warm: u64,
    pub rss_end: u64,
}

impl std::fmt::Display for SoakReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
        write!(
            f,
            "{}: {} bodies, {:.1} s wall, {} steps ({:.1} steps/s), energy start {:.6e} J max {:.6e} J, \
             escaped {} (max {}), isolated {}, RSS start {:.1} MiB, after warm-up {:.1} MiB, end {:.1} MiB",
            self.scene,
            self.bodies,
            self.duration.as_secs_f64(),
            self.steps,
            self.steps as f64 / self.duration.as_secs_f64(),
            self.initial_energy,
            self.max_energy,
            self.escaped,
            self.max_escaped,
            self.isolated,
            mib(self.rss_start),
            mib(self.rss_warm),
            mib(self.rss_end),
        )
    }
}

/// Resident set size of this process, bytes (from `/proc/self/status`; 0 where there is none).
pub fn rss_bytes() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// Half the inside width of the `rain` scene's bin, m (`rain::BIN_HALF_WIDTH`, which the scenes
/// module keeps private).
const RAIN_BIN_HALF_WIDTH: f64 = 10.0;

fn energy(world: &World) -> f64 {
    world.kinetic_energy() + world.potential_energy()
}

/// Dynamic bodies that left the scene: for `rain`, outside the bin's walls or below the floor; for
/// the others, below the ground or more than 100 m from the origin horizontally.
fn escaped(scene: &str, world: &World) -> usize {
    let half = if scene == "rain" { RAIN_BIN_HALF_WIDTH } else { 100.0 };
    world
        .bodies()
        .filter(|(_, b)| b.kind() == BodyKind::Dynamic)
        .filter(|(_, b)| {
            let p = b.com_world();
            !(p.x.abs() <= half && p.y.abs() <= half && p.z >= -0.1)
        })
        .count()
}

/// Steps `name` (a scene of `tumble::scenes`, at its default size unless `size`) for `budget` of
/// wall time, checking energy after every step and escapes every `check_every` steps.
pub fn soak(name: &str, size: Option<usize>, budget: Duration) -> SoakReport {
    let rss_start = rss_bytes();
    let mut scene = scenes::by_name(name, size).unwrap_or_else(|| panic!("no scene called {name}"));
    let initial_energy = energy(&scene.world);
    let (mut max_energy, mut max_escaped, mut steps) = (initial_energy, 0, 0_u64);
    let mut rss_warm = None;
    let start = Instant::now();
    while start.elapsed() < budget {
        scene.world.step(scene.dt).expect("valid time step");
        steps += 1;
        max_energy = max_energy.max(energy(&scene.world));
        if steps.is_multiple_of(60) {
            max_escaped = max_escaped.max(escaped(scene.name, &scene.world));
        }
        if rss_warm.is_none() && start.elapsed() >= budget / 10 {
            rss_warm = Some(rss_bytes());
        }
    }
    let rss_end = rss_bytes();
    let escaped_now = escaped(scene.name, &scene.world);
    SoakReport {
        scene: scene.name,
        bodies: scene.world.body_count(),
        duration: start.elapsed(),
        steps,
        initial_energy,
        max_energy,
        escaped: escaped_now,
        max_escaped: max_escaped.max(escaped_now),
        isolated: scene.world.isolated_bodies().count(),
        rss_start,
        rss_warm: rss_warm.unwrap_or(rss_end),
        rss_end,
    }
}

/// What is wrong with a soak run, if anything: energy above its start by more than 1% of its
/// size (contacts and joints only take energy out; the bodies start at rest), any escape or
/// isolation, or resident memory after the warm-up growing by more than 10% + 16 MiB.
pub fn problems(r: &SoakReport) -> Vec<String> {
    let mut problems = Vec::new();
    let allowed = r.initial_energy + 0.01 * r.initial_energy.abs().max(1.0);
    // NaN energy fails too.
    if r.max_energy > allowed || r.max_energy.is_nan() {
        problems.push(format!("energy rose to {:.6e} J from {:.6e} J", r.max_energy, r.initial_energy));
    }
    if r.max_escaped > 0 {
        problems.push(format!("{} bodies escaped", r.max_escaped));
    }
    if r.isolated > 0 {
        problems.push(format!("{} bodies isolated for non-finite state", r.isolated));
    }
    let limit = r.rss_warm + r.rss_warm / 10 + 16 * 1024 * 1024;
    if r.rss_end > limit {
        problems.push(format!("memory grew from {} to {} bytes after the warm-up", r.rss_warm, r.rss_end));
    }
    problems
}
