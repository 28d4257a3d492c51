//! Builds the viewer page's script (`viewer/`: three.js and the page code, bundled by esbuild)
//! into OUT_DIR/viewer.js, which `src/view.rs` embeds. It runs `npm ci` in `viewer/` when the
//! installed packages are missing or older than `package-lock.json`, then `node build.mjs`.
//!
//! Without node and npm (or without the npm registry) the binary is still built, with a stub in
//! place of the script: `tumble view` then says how to get the real one, and everything else works.
//! TUMBLE_VIEWER_JS=FILE uses a prebuilt bundle instead.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant, SystemTime};

/// What `src/view.rs` looks for to tell the stub from the real script.
const STUB_MARKER: &str = "TUMBLE_VIEWER_NOT_BUILT";

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let viewer = manifest.join("../../viewer");
    let out = PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("viewer.js");
    for input in ["src", "build.mjs", "package.json", "package-lock.json", "template.html"] {
        println!("cargo:rerun-if-changed={}", viewer.join(input).display());
    }
    println!("cargo:rerun-if-env-changed=TUMBLE_VIEWER_JS");

    let result = match std::env::var_os("TUMBLE_VIEWER_JS") {
        Some(file) => std::fs::copy(&file, &out).map(|_| ()).map_err(|e| format!("TUMBLE_VIEWER_JS: {e}")),
        None => build_bundle(&viewer, &out),
    };
    if let Err(reason) = result {
        println!(
            "cargo:warning=the viewer page's script was not built ({reason}); `tumble view` will explain"
        );
        let stub = format!("/* {STUB_MARKER}: {} */", reason.replace("*/", "* /"));
        std::fs::write(&out, stub).expect("write the viewer stub");
    }
}

fn build_bundle(viewer: &Path, out: &Path) -> Result<(), String> {
    let _lock = DirLock::acquire(&viewer.join(".build-lock"))?;
    if needs_install(viewer) {
        run(Command::new("npm").args(["ci", "--no-audit", "--no-fund"]).current_dir(viewer), "npm ci")?;
    }
    run(Command::new("node").arg("build.mjs").arg(out).current_dir(viewer), "node build.mjs")
}

/// True when `node_modules` is missing or older than the lock file.
fn needs_install(viewer: &Path) -> bool {
    let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    let installed = modified(&viewer.join("node_modules/.package-lock.json"));
    let wanted = modified(&viewer.join("package-lock.json")).unwrap_or(SystemTime::UNIX_EPOCH);
    let stale = match installed {
        Some(t) => t < wanted,
        None => true,
    };
    stale || !viewer.join("node_modules/three").exists()
}

fn run(command: &mut Command, what: &str) -> Result<(), String> {
    let output = command.output().map_err(|e| format!("{what}: {e}; is Node.js with npm installed?"))?;
    if output.status.success() {
        Ok(())
    } else {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let tail: Vec<&str> = stderr.lines().rev().take(5).collect();
        Err(format!("{what} failed: {}", tail.into_iter().rev().collect::<Vec<_>>().join(" | ")))
    }
}

/// A lock directory, so two builds (say a dev and a test profile in one `cargo` run) never run
/// `npm ci` in the same folder at once. A lock older than ten minutes is taken to be left over.
struct DirLock(PathBuf);

impl DirLock {
    fn acquire(path: &Path) -> Result<DirLock, String> {
        let start = Instant::now();
        loop {
            match std::fs::create_dir(path) {
                Ok(()) => return Ok(DirLock(path.to_owned())),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let age = std::fs::metadata(path)
                        .and_then(|m| m.modified())
                        .ok()
                        .and_then(|t| t.elapsed().ok())
                        .unwrap_or_default();
                    if age > Duration::from_secs(600) {
                        let _ = std::fs::remove_dir(path);
                    } else if start.elapsed() > Duration::from_secs(900) {
                        return Err(format!("{} is held by another build", path.display()));
                    }
                    std::thread::sleep(Duration::from_millis(200));
                }
                Err(e) => return Err(format!("{}: {e}", path.display())),
            }
        }
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir(&self.0);
    }
}
