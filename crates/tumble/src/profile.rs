//! Where a step's time goes: wall time per pipeline phase, summed over the steps since the world
//! was made (or since `World::reset_profile`). Reading the clock changes nothing in the
//! simulation, so a profiled run is bit-identical to an unprofiled one.

use std::fmt;
use std::time::{Duration, Instant};

/// The phases of `World::step`, in pipeline order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Moving the broad-phase proxies of awake bodies to their poses before the pair search.
    Proxies,
    /// Finding new candidate pairs and making contacts of them.
    BroadPhase,
    /// Updating every contact's manifold (and dropping the contacts whose boxes parted).
    NarrowPhase,
    /// Island links from touching contacts; waking sleeping islands that awake bodies touch.
    Wake,
    /// The solve's set-up: the solver bodies gathered, joints and contacts prepared, the
    /// contacts coloured, the joint trees built.
    SolveSetUp,
    /// The solve's substeps: velocities, joints, contacts and positions.
    Substeps,
    /// After the substeps: impulses kept for the next step's warm start, joint forces, the
    /// bodies written back (and their proxies' moves planned), non-finite bodies isolated.
    SolveStore,
    /// Sweeping bullets against static geometry and moving back those that went through.
    Continuous,
    /// Moving the proxies to the solved poses, so queries between steps see them.
    Finalize,
    /// Sleep timers, islands and putting islands to sleep.
    Sleep,
}

impl Phase {
    pub const ALL: [Phase; 10] = [
        Phase::Proxies,
        Phase::BroadPhase,
        Phase::NarrowPhase,
        Phase::Wake,
        Phase::SolveSetUp,
        Phase::Substeps,
        Phase::SolveStore,
        Phase::Continuous,
        Phase::Finalize,
        Phase::Sleep,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Phase::Proxies => "proxies",
            Phase::BroadPhase => "broad phase",
            Phase::NarrowPhase => "narrow phase",
            Phase::Wake => "islands/wake",
            Phase::SolveSetUp => "solve set-up",
            Phase::Substeps => "substeps",
            Phase::SolveStore => "solve store",
            Phase::Continuous => "continuous",
            Phase::Finalize => "finalize proxies",
            Phase::Sleep => "sleep",
        }
    }
}

/// Wall time per phase, summed over steps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepProfile {
    /// Steps summed.
    pub steps: u64,
    /// Time per phase, indexed like [`Phase::ALL`].
    pub phases: [Duration; 10],
    /// Whole steps, including what no phase covers (argument checks, clearing forces, the clock).
    pub total: Duration,
}

impl StepProfile {
    pub fn get(&self, phase: Phase) -> Duration {
        self.phases[phase as usize]
    }

    /// Adds the time since `*since` to `phase` and restarts the clock.
    pub(crate) fn lap(&mut self, phase: Phase, since: &mut Instant) {
        let now = Instant::now();
        self.phases[phase as usize] += now - *since;
        *since = now;
    }
}

impl fmt::Display for StepProfile {
    /// A table: phase, total ms, µs per step, share of the step.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let steps = self.steps.max(1) as f64;
        let total = self.total.as_secs_f64().max(f64::MIN_POSITIVE);
        writeln!(f, "{:<18} {:>11} {:>12} {:>7}", "phase", "total ms", "us/step", "share")?;
        let mut covered = Duration::ZERO;
        let rows = Phase::ALL.iter().map(|&p| (p.name(), self.get(p)));
        for (name, d) in rows {
            covered += d;
            row(f, name, d, steps, total)?;
        }
        row(f, "other", self.total.saturating_sub(covered), steps, total)?;
        row(f, "step", self.total, steps, total)?;
        write!(f, "{} steps, {:.1} steps/s", self.steps, steps / total)
    }
}

fn row(f: &mut fmt::Formatter<'_>, name: &str, d: Duration, steps: f64, total: f64) -> fmt::Result {
    let s = d.as_secs_f64();
    writeln!(f, "{name:<18} {:>11.2} {:>12.2} {:>6.1}%", s * 1e3, s * 1e6 / steps, 100.0 * s / total)
}
