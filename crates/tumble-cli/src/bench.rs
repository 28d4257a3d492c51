//! `tumble bench SCENE`: run one of the shared benchmark scenes (`tumble::scenes`) several times
//! and print steps/s (median of the runs), the settings and the scene's quality result; `--json`
//! prints the same as one JSON object for the runner in `bench/`.
//!
//! Each run builds the scene afresh (not timed) and times `World::step` alone, step by step: the
//! scene's probe, which watches the run for its quality result, looks between the timed steps.

use std::time::{Duration, Instant};

use tumble::scenes::{self, Scene};

pub struct BenchOptions {
    pub threads: usize,
    pub steps: Option<u32>,
    pub runs: usize,
    pub size: Option<usize>,
    /// Overrides the scene's solver substeps.
    pub substeps: Option<u32>,
    /// Overrides of other solver settings, `key=value` (`SolverSettings` field names).
    pub solver: Vec<String>,
    pub json: bool,
}

/// Builds a scene by name with the options' threads and substeps.
fn build_with_options(name: &str, options: &BenchOptions) -> Result<Scene, String> {
    let mut scene = build_scene(name, options.size)?;
    scene.world.set_threads(options.threads).map_err(|e| e.to_string())?;
    if let Some(substeps) = options.substeps {
        let settings = tumble::SolverSettings { substeps, ..scene.world.solver_settings().clone() };
        scene.world.set_solver_settings(settings).map_err(|e| e.to_string())?;
    }
    if !options.solver.is_empty() {
        let settings = with_overrides(scene.world.solver_settings(), &options.solver)?;
        scene.world.set_solver_settings(settings).map_err(|e| e.to_string())?;
    }
    Ok(scene)
}

/// `settings` with each `key=value` of `overrides` applied: the key is a field of
/// `SolverSettings`, the value JSON (a number or `true`/`false`).
fn with_overrides(
    settings: &tumble::SolverSettings,
    overrides: &[String],
) -> Result<tumble::SolverSettings, String> {
    let mut value = serde_json::to_value(settings).map_err(|e| e.to_string())?;
    let fields = value.as_object_mut().ok_or("solver settings are not a JSON object")?;
    for item in overrides {
        let (key, text) =
            item.split_once('=').ok_or_else(|| format!("--solver {item}: expected KEY=VALUE"))?;
        if !fields.contains_key(key) {
            let known: Vec<&str> = fields.keys().map(String::as_str).collect();
            return Err(format!(
                "--solver {item}: no solver setting \"{key}\"; the settings are: {}",
                known.join(", ")
            ));
        }
        let parsed: serde_json::Value =
            serde_json::from_str(text).map_err(|e| format!("--solver {item}: bad value: {e}"))?;
        fields.insert(key.to_string(), parsed);
    }
    serde_json::from_value(value).map_err(|e| format!("--solver: {e}"))
}

/// Builds a scene by name, or says which names there are.
pub fn build_scene(name: &str, size: Option<usize>) -> Result<Scene, String> {
    if size == Some(0) {
        return Err("--size must be at least 1".into());
    }
    scenes::by_name(name, size)
        .ok_or_else(|| format!("no scene named \"{name}\"; the scenes are: {}", scenes::NAMES.join(", ")))
}

/// The solver and thread settings of a scene's world, as printed in every result.
pub fn settings_line(scene: &Scene) -> String {
    let s = scene.world.solver_settings();
    format!(
        "dt {:.6} s, substeps {}, iterations {} solve + {} relax per substep, threads {}",
        scene.dt,
        s.substeps,
        s.solve_iterations,
        s.relax_iterations,
        scene.world.threads()
    )
}

/// The median of `values` (the mean of the middle two for an even count).
pub fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

pub fn bench(name: &str, options: &BenchOptions) -> Result<String, String> {
    if options.runs == 0 {
        return Err("--runs must be at least 1".into());
    }
    let mut rates = Vec::with_capacity(options.runs);
    let mut last = None;
    for _ in 0..options.runs {
        let mut scene = build_with_options(name, options)?;
        let steps = options.steps.unwrap_or(scene.steps);
        let mut stepping = Duration::ZERO;
        for _ in 0..steps {
            let start = Instant::now();
            scene.world.step(scene.dt).map_err(|e| e.to_string())?;
            stepping += start.elapsed();
            scene.observe();
        }
        rates.push(f64::from(steps) / stepping.as_secs_f64().max(f64::MIN_POSITIVE));
        last = Some((scene, steps));
    }
    let (scene, steps) = last.expect("at least one run");
    let quality = scene.quality();
    let (min, max) = rates.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &r| (lo.min(r), hi.max(r)));
    let median = median(&mut rates);
    let s = scene.world.solver_settings();
    if options.json {
        let metrics: serde_json::Map<String, serde_json::Value> =
            quality.metrics.iter().map(|m| (m.name().to_string(), m.value().into())).collect();
        let value = serde_json::json!({
            "engine": "tumble",
            "version": env!("CARGO_PKG_VERSION"),
            "scene": scene.name,
            "size": scene.size,
            "bodies": scene.world.body_count(),
            "joints": scene.world.joint_count(),
            "dt": scene.dt,
            "steps": steps,
            "runs": options.runs,
            "steps_per_second": median,
            "min": min,
            "max": max,
            "substeps": s.substeps,
            "iterations": format!("{} solve + {} relax per substep", s.solve_iterations, s.relax_iterations),
            "threads": scene.world.threads(),
            "quality": quality.to_string(),
            "metrics": metrics,
            // The last run's final state: equal hashes mean the same bits (for comparing builds
            // and thread counts).
            "state_hash": format!("{:016x}", scene.world.state_hash()),
        });
        return Ok(format!("{value}\n"));
    }
    Ok(format!(
        "scene:    {} (size {}: {} bodies, {} joints)\n\
         engine:   tumble {}, {}\n\
         runs:     {} x {} steps\n\
         steps/s:  {:.1} median (min {:.1}, max {:.1})\n\
         quality:  {}\n",
        scene.name,
        scene.size,
        scene.world.body_count(),
        scene.world.joint_count(),
        env!("CARGO_PKG_VERSION"),
        settings_line(&scene),
        options.runs,
        steps,
        median,
        min,
        max,
        quality
    ))
}

/// `tumble run SCENE --profile` for a built-in scene: one run with the per-phase profile.
pub fn profile(name: &str, options: &BenchOptions) -> Result<String, String> {
    let mut scene = build_with_options(name, options)?;
    let steps = options.steps.unwrap_or(scene.steps);
    for _ in 0..steps {
        scene.step();
    }
    Ok(format!(
        "scene:    {} (size {}: {} bodies, {} joints)\n\
         settings: {}\n\
         quality:  {}\n\n{}\n",
        scene.name,
        scene.size,
        scene.world.body_count(),
        scene.world.joint_count(),
        settings_line(&scene),
        scene.quality(),
        scene.world.profile()
    ))
}

#[cfg(test)]
mod tests {
    use super::median;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 2.5);
    }
}
