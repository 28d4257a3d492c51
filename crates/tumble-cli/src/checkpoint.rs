//! Checkpoints of `tumble run`: everything needed to carry a run on after it was killed, so that
//! the resumed run writes the same recording, byte for byte, as one that was never interrupted.
//!
//! A checkpoint holds the world's snapshot (`World::snapshot`: every bit that decides the future)
//! and the run loop's own state ([`RunState`]): the step count to reach, the recording's settings
//! and how much of it was written (frames and bytes, so a resume cuts off anything written after
//! the checkpoint), and the accumulators of the summary's conservation checks.
//!
//! File format: the snapshot envelope (`tumble::snapshot::seal`: magic `TUMBLECP`, format
//! version, length, FNV-1a checksum) around the `postcard` encoding of [`Checkpoint`]. A file is
//! replaced atomically: written to `FILE.tmp`, flushed to disk (`fsync`), then renamed over `FILE`
//! (and the folder flushed), so a kill or a crash at any moment leaves either the previous
//! checkpoint or the new one, never a mix.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use tumble::{DVec3, SnapshotError, World};

const MAGIC: &[u8; 8] = b"TUMBLECP";
/// Bumped whenever [`Checkpoint`] changes shape (including the world inside it). 2: bodies carry
/// the `bullet` flag.
const VERSION: u32 = 2;

/// Running maxima of the conservation checks and the reference values they compare with.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Drift {
    pub e0: f64,
    pub l0: DVec3,
    pub p0: DVec3,
    /// Σ mᵢ sᵢ g over the dynamic bodies.
    pub weight: DVec3,
    pub max_de: f64,
    pub max_dl: f64,
    pub max_dp: f64,
}

/// The run loop's state besides the world.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct RunState {
    /// The scene as named on the command line, for the summary and messages.
    pub scene: PathBuf,
    pub bodies: usize,
    /// The recording as named on the command line (for the summary) and as an absolute path (to
    /// find it again from another folder).
    pub out: PathBuf,
    pub out_absolute: PathBuf,
    pub every: u64,
    pub dt: f64,
    /// Steps the whole run takes.
    pub steps: u64,
    /// Write a checkpoint every this many steps (0: never).
    pub checkpoint_every: u64,
    /// Frames and bytes of the recording when the checkpoint was written.
    pub frames: u64,
    pub recording_bytes: u64,
    pub drift: Drift,
    /// Wall time spent before the checkpoint, s (the summary reports the total).
    pub wall_seconds: f64,
}

#[derive(serde::Serialize, serde::Deserialize)]
pub struct Checkpoint {
    pub run: RunState,
    /// `World::snapshot()` bytes.
    pub world: Vec<u8>,
}

/// Writes a checkpoint of `run` and `world` to `path`, atomically (module docs).
pub fn write(path: &Path, run: &RunState, world: &World) -> Result<(), String> {
    let checkpoint = Checkpoint { run: run.clone(), world: world.snapshot() };
    let payload =
        postcard::to_stdvec(&checkpoint).map_err(|e| format!("checkpoint {}: {e}", path.display()))?;
    write_atomically(path, &tumble::snapshot::seal(MAGIC, VERSION, &payload))
        .map_err(|e| format!("checkpoint {}: {e}", path.display()))
}

/// Replaces `path` with `bytes` so that it holds either its old contents or all of `bytes`, even
/// if the process or the machine stops at any point.
fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut name = path.file_name().map(|n| n.to_owned()).unwrap_or_else(|| "checkpoint".into());
    name.push(".tmp");
    let temporary = path.with_file_name(name);
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let mut file = File::create(&temporary)?;
    file.write_all(bytes)?;
    file.sync_all()?;
    drop(file);
    std::fs::rename(&temporary, path)?;
    // The rename itself is durable once the folder is flushed; a file system that cannot open a
    // folder for that (not Linux's) still has the checkpoint, just not guaranteed across a crash.
    if let Ok(folder) = File::open(dir) {
        let _ = folder.sync_all();
    }
    Ok(())
}

/// Reads a checkpoint; every failure is a message that names the file and says what is wrong.
pub fn read(path: &Path) -> Result<(RunState, World), String> {
    let fail = |why: String| format!("checkpoint {}: {why}", path.display());
    let bytes = std::fs::read(path).map_err(|e| fail(e.to_string()))?;
    let payload = tumble::snapshot::unseal(MAGIC, VERSION, &bytes).map_err(|e| {
        fail(match e {
            SnapshotError::NotASnapshot => {
                "not a tumble checkpoint (the file does not start with TUMBLECP)".to_string()
            }
            SnapshotError::Truncated { expected, got } => {
                format!("truncated: {got} bytes, expected {expected}")
            }
            SnapshotError::UnsupportedVersion { found, supported } => {
                format!("format version {found} is not supported (this build reads version {supported})")
            }
            SnapshotError::Corrupt => "damaged: its checksum does not match its contents".to_string(),
            SnapshotError::Decode(e) => format!("could not be decoded: {e}"),
        })
    })?;
    let checkpoint: Checkpoint =
        postcard::from_bytes(payload).map_err(|e| fail(format!("could not be decoded: {e}")))?;
    let world = World::restore(&checkpoint.world).map_err(|e| fail(format!("its world: {e}")))?;
    Ok((checkpoint.run, world))
}
