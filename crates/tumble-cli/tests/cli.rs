//! The `tumble` binary as a user runs it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn tumble(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tumble")).args(args).current_dir(cwd).output().expect("tumble runs")
}

fn scenes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes").canonicalize().unwrap()
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The number after `label:` in the summary.
fn summary_value(stdout: &str, label: &str) -> f64 {
    let line =
        stdout.lines().find(|l| l.starts_with(label)).unwrap_or_else(|| panic!("no `{label}` in:\n{stdout}"));
    line[label.len()..].split_whitespace().next().unwrap().parse().unwrap()
}

type Matrix = [[f64; 3]; 3];

fn matrix(value: &serde_json::Value) -> Matrix {
    let rows: Vec<Vec<f64>> = serde_json::from_value(value.clone()).unwrap();
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| rows[r][c]))
}

#[test]
fn mass_prints_json_whose_axes_diagonalise_the_inertia() {
    let dir = tempfile::tempdir().unwrap();
    let handle = scenes().join("handle.obj");
    let out = tumble(&["mass", handle.to_str().unwrap()], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let mass = json["mass"].as_f64().unwrap();
    assert!((mass - 10.0).abs() < 1e-9, "mass {mass}");
    assert!((json["volume"].as_f64().unwrap() - 0.01).abs() < 1e-12);
    let com: Vec<f64> = serde_json::from_value(json["center_of_mass"].clone()).unwrap();
    assert!(com.iter().all(|c| c.abs() < 1e-12), "{com:?}");
    let inertia = matrix(&json["inertia"]);
    let r = matrix(&json["principal_axes"]);
    let m: Vec<f64> = serde_json::from_value(json["principal_moments"].clone()).unwrap();
    assert!(m[0] < m[1] && m[1] < m[2], "ascending and distinct: {m:?}");
    // inertia = R diag(m) Rᵀ, element by element.
    let scale = m[2];
    for i in 0..3 {
        for j in 0..3 {
            let rebuilt: f64 = (0..3).map(|k| r[i][k] * m[k] * r[j][k]).sum();
            assert!(
                (rebuilt - inertia[i][j]).abs() <= 1e-10 * scale,
                "({i},{j}): {rebuilt} vs {}",
                inertia[i][j]
            );
        }
    }
    let det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
        - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
        + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    assert!((det - 1.0).abs() < 1e-12, "det R = {det}");
}

#[test]
fn mass_density_scales_mass_and_bad_input_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let handle = scenes().join("handle.obj");
    let out = tumble(&["mass", handle.to_str().unwrap(), "--density", "2"], dir.path());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!((json["mass"].as_f64().unwrap() - 0.02).abs() < 1e-14);

    let out = tumble(&["mass", handle.to_str().unwrap(), "--density", "-1"], dir.path());
    assert!(!out.status.success());
    assert!(
        text(&out.stderr).starts_with("error: --density must be finite and > 0"),
        "{}",
        text(&out.stderr)
    );

    let out = tumble(&["mass", "missing.obj"], dir.path());
    assert!(!out.status.success());
    let stderr = text(&out.stderr);
    assert!(stderr.starts_with("error: missing.obj: ") && !stderr.contains("panicked"), "{stderr}");
}

#[test]
fn run_on_a_bad_scene_exits_non_zero_with_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    std::fs::write(&scene, "[world]\ndt = 0.01\n\n[[body]]\nname = \"arm\"\nshape = { type = \"sphere\", radius = 0.5 }\ndensity = -2\n")
        .unwrap();
    let out = tumble(&["run", "bad.toml"], dir.path());
    assert!(!out.status.success());
    let stderr = text(&out.stderr);
    assert_eq!(stderr.trim_end(), "error: bad.toml:7: body \"arm\": density must be > 0, got -2");
    assert!(!stderr.contains("panicked"));
    assert!(!dir.path().join("out").exists(), "no output for a scene that failed to load");
}

#[test]
fn run_rejects_bad_overrides_without_panicking() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scenes().join("projectile.toml");
    for args in [["--dt", "0"], ["--duration", "-1"], ["--every", "0"]] {
        let out = tumble(&["run", scene.to_str().unwrap(), args[0], args[1]], dir.path());
        assert!(!out.status.success(), "{args:?}");
        let stderr = text(&out.stderr);
        assert!(stderr.contains("error") && !stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn run_writes_every_nth_step_and_reports_conservation() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scenes().join("projectile.toml");
    let out = tumble(
        &[
            "run",
            scene.to_str().unwrap(),
            "--out",
            "p.csv",
            "--every",
            "10",
            "--duration",
            "1",
            "--dt",
            "0.01",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert_eq!(summary_value(&stdout, "steps:"), 100.0);
    // Not asserted tightly: the core's linear update is first order (symplectic Euler), so under
    // gravity its energy error grows like m g² dt t / 2 (about 1% here). Rotation is what the
    // demo checks.
    assert!(summary_value(&stdout, "energy drift:") < 0.05, "{stdout}");
    assert!(summary_value(&stdout, "angular momentum drift:") < 1e-9, "{stdout}");
    assert!(summary_value(&stdout, "linear momentum drift:") < 1e-9, "{stdout}");
    let recording = tumble_io::Recording::read(dir.path().join("p.csv")).unwrap();
    assert_eq!(recording.frames.len(), 11, "t = 0 and every 10th of 100 steps");
    assert!((recording.frames[10].t - 1.0).abs() < 1e-12);
}

#[test]
fn demo_writes_out_demo_csv_with_exact_header_and_small_energy_drift() {
    let dir = tempfile::tempdir().unwrap();
    let out = tumble(&[], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let csv = std::fs::read_to_string(dir.path().join("out/demo.csv")).unwrap();
    assert_eq!(csv.lines().next().unwrap(), "t,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz");
    assert_eq!(summary_value(&stdout, "steps:"), 4800.0);
    assert_eq!(summary_value(&stdout, "simulated time:"), 20.0);
    let energy = summary_value(&stdout, "energy drift:");
    assert!(energy < 1e-4, "energy drift {energy}:\n{stdout}");
    assert!(summary_value(&stdout, "angular momentum drift:") < 1e-9, "{stdout}");
    assert!(stdout.contains("out/demo.csv"), "{stdout}");
    assert_eq!(csv.lines().count(), 1 + 4801);

    // The handle really flips: the spin axis (body Y) turns over and comes back.
    let recording = tumble_io::Recording::read(dir.path().join("out/demo.csv")).unwrap();
    let flips = recording
        .body_track("handle")
        .map(|(_, s)| (s.orientation * tumble::DVec3::Y).y)
        .collect::<Vec<_>>()
        .windows(2)
        .filter(|w| (w[0] > 0.0) != (w[1] > 0.0))
        .count();
    assert!(flips >= 3, "expected the handle to flip at least three times in 20 s, saw {flips} sign changes");
}

#[test]
fn demo_command_takes_an_output_path() {
    let dir = tempfile::tempdir().unwrap();
    let out = tumble(&["demo", "--out", "elsewhere/d.csv"], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(dir.path().join("elsewhere/d.csv").exists());
}

#[test]
fn run_reports_contacts_and_sleeping_bodies() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scenes().join("playground.toml");
    let out = tumble(&["run", scene.to_str().unwrap(), "--out", "play.csv"], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    // Ground–lower box, lower–upper box, ground–pebble at least.
    assert!(summary_value(&stdout, "contacts:") >= 3.0, "{stdout}");
    let bodies = stdout.lines().find(|l| l.starts_with("bodies:")).unwrap();
    assert!(
        bodies.contains("7 (") && bodies.contains("sleeping at the end") && bodies.contains("1 joint"),
        "{bodies}"
    );
    // The stack and the pebble come to rest and sleep; the pendulum keeps swinging.
    let sleeping: usize =
        bodies.split(", ").nth(1).unwrap().split_whitespace().next().unwrap().parse().unwrap();
    assert!(sleeping >= 3, "{bodies}");
}

/// `tumble bench SCENE --profile` makes one run with the given settings and prints the phases,
/// whose shares add up to the step; `--profile` with `--json` is refused.
#[test]
fn bench_profile_runs_the_given_settings_and_prints_the_phases() {
    let dir = tempfile::tempdir().unwrap();
    let out = tumble(
        &["bench", "pyramid", "--size", "4", "--steps", "7", "--substeps", "3", "--profile"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("substeps 3"), "{stdout}");
    assert!(stdout.contains("7 steps,"), "{stdout}");
    let share = |label: &str| -> f64 {
        let line =
            stdout.lines().find(|l| l.starts_with(label)).unwrap_or_else(|| panic!("no {label}:\n{stdout}"));
        line.split_whitespace().last().unwrap().trim_end_matches('%').parse().unwrap()
    };
    let phases = [
        "proxies",
        "broad phase",
        "narrow phase",
        "islands/wake",
        "solve set-up",
        "substeps",
        "solve store",
        "continuous",
        "finalize proxies",
        "sleep",
        "other",
    ];
    let sum: f64 = phases.iter().map(|p| share(p)).sum();
    assert!((sum - 100.0).abs() < 0.1 * phases.len() as f64, "shares add to {sum}%:\n{stdout}");
    assert_eq!(share("step"), 100.0);
    let refused = tumble(&["bench", "pyramid", "--profile", "--json"], dir.path());
    assert!(!refused.status.success());
}
