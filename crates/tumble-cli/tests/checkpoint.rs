//! `tumble run --checkpoint` / `--resume`: a run killed at any moment carries on from its last
//! checkpoint and writes the same recording, byte for byte, as a run that was never interrupted.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn tumble(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tumble")).args(args).current_dir(cwd).output().expect("tumble runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A pile of boxes and balls dropped, tumbling, onto the ground with sleep off, so that every
/// step has contacts to solve: 4000 steps of 1/240 s.
fn pile_scene() -> String {
    let mut scene = String::from(
        "[world]\ndt = 0.004166666666666667\nduration = 16.666666666666668\nsleep = false\n\n\
         [[body]]\nname = \"ground\"\nkind = \"static\"\n\
         shape = { type = \"box\", half_extents = [10.0, 10.0, 0.5] }\nposition = [0.0, 0.0, -0.5]\n",
    );
    for i in 0..24 {
        let (x, y, z) = ((i % 4) as f64 * 0.9 - 1.4, ((i / 4) % 2) as f64 * 0.9, 0.6 + (i / 8) as f64 * 1.1);
        let shape = if i % 3 == 0 {
            "{ type = \"sphere\", radius = 0.4 }"
        } else {
            "{ type = \"box\", half_extents = [0.4, 0.3, 0.35] }"
        };
        let _ = write!(
            scene,
            "\n[[body]]\nname = \"b{i}\"\nshape = {shape}\nposition = [{x}, {y}, {z}]\n\
             orientation = [0.0, 0.2588190451025208, 0.0, 0.9659258262890683]\n\
             angular_velocity = [{}, 1.0, 0.5]\n",
            i as f64 * 0.3 - 2.0
        );
    }
    scene
}

fn setup() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("pile.toml");
    std::fs::write(&scene, pile_scene()).unwrap();
    (dir, scene)
}

#[test]
fn a_killed_run_resumes_to_the_same_recording() {
    let (dir, _) = setup();
    let cwd = dir.path();
    let reference = tumble(&["run", "pile.toml", "--out", "reference.csv"], cwd);
    assert!(reference.status.success(), "{}", text(&reference.stderr));

    // Run with checkpoints every 100 steps; kill it once a second checkpoint has replaced the
    // first (so the kill lands mid-run, between or during checkpoint writes).
    let checkpoint = cwd.join("run.ckpt");
    let mut child = Command::new(env!("CARGO_BIN_EXE_tumble"))
        .args(["run", "pile.toml", "--out", "killed.csv", "--checkpoint", "run.ckpt"])
        .args(["--checkpoint-every", "100"])
        .current_dir(cwd)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    let mut first_seen = None;
    let killed_mid_run = loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success());
            break false;
        }
        if let Ok(meta) = std::fs::metadata(&checkpoint) {
            let modified = meta.modified().unwrap();
            match first_seen {
                None => first_seen = Some(modified),
                Some(first) if modified != first => {
                    child.kill().unwrap();
                    child.wait().unwrap();
                    break true;
                }
                _ => {}
            }
        }
        assert!(started.elapsed() < Duration::from_secs(120), "no checkpoint appeared");
        std::thread::sleep(Duration::from_millis(2));
    };
    let killed = std::fs::read(cwd.join("killed.csv")).unwrap();
    let full = std::fs::read(cwd.join("reference.csv")).unwrap();
    eprintln!("killed mid-run: {killed_mid_run}, after {} of {} bytes", killed.len(), full.len());
    if killed_mid_run {
        assert!(killed.len() < full.len(), "the kill came before the end");
    }
    // A machine crash can leave part of a frame; the resume must cut it off.
    let mut torn = killed.clone();
    torn.extend_from_slice(b"0.1,b3,1.5,0.0");
    std::fs::write(cwd.join("killed.csv"), torn).unwrap();

    let resumed = tumble(&["run", "--resume", "run.ckpt"], cwd);
    assert!(resumed.status.success(), "{}", text(&resumed.stderr));
    let resumed_csv = std::fs::read(cwd.join("killed.csv")).unwrap();
    assert!(resumed_csv == full, "the resumed recording differs from the uninterrupted one");
    assert!(text(&resumed.stdout).contains("steps:                  4000"), "{}", text(&resumed.stdout));
}

#[test]
fn resuming_a_damaged_checkpoint_says_which_file_and_what() {
    let (dir, _) = setup();
    let cwd = dir.path();
    let run = tumble(
        &["run", "pile.toml", "--duration", "0.5", "--checkpoint", "run.ckpt", "--checkpoint-every", "60"],
        cwd,
    );
    assert!(run.status.success(), "{}", text(&run.stderr));
    let bytes = std::fs::read(cwd.join("run.ckpt")).unwrap();

    let mut flipped = bytes.clone();
    let last = flipped.len() - 1;
    flipped[last] ^= 0x40;
    let cases: [(&str, Vec<u8>, &str); 4] = [
        ("truncated.ckpt", bytes[..bytes.len() / 2].to_vec(), "truncated"),
        ("flipped.ckpt", flipped, "damaged"),
        ("empty.ckpt", Vec::new(), "not a tumble checkpoint"),
        ("scene.ckpt", pile_scene().into_bytes(), "not a tumble checkpoint"),
    ];
    for (name, contents, why) in cases {
        std::fs::write(cwd.join(name), contents).unwrap();
        let out = tumble(&["run", "--resume", name], cwd);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{name}: resumed from a bad checkpoint");
        assert!(stderr.contains(name) && stderr.contains(why), "{name}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    let missing = tumble(&["run", "--resume", "nowhere.ckpt"], cwd);
    assert!(!missing.status.success() && text(&missing.stderr).contains("nowhere.ckpt"));
}

#[test]
fn resume_needs_the_recording_it_continues() {
    let (dir, _) = setup();
    let cwd = dir.path();
    let run = tumble(
        &[
            "run",
            "pile.toml",
            "--duration",
            "0.5",
            "--out",
            "gone.csv",
            "--checkpoint",
            "run.ckpt",
            "--checkpoint-every",
            "60",
        ],
        cwd,
    );
    assert!(run.status.success(), "{}", text(&run.stderr));
    std::fs::write(cwd.join("gone.csv"), "t,body\n").unwrap();
    let out = tumble(&["run", "--resume", "run.ckpt"], cwd);
    let stderr = text(&out.stderr);
    assert!(!out.status.success() && stderr.contains("gone.csv") && stderr.contains("run.ckpt"), "{stderr}");
}
