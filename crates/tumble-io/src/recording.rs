//! Recordings: the state of every body at chosen steps, as CSV, and a reader for them.
//!
//! One row per body per frame, header [`RECORDING_HEADER`]:
//! - `t`: simulated time, s; `body`: the body's name;
//! - `px,py,pz`: world position of the body frame's origin (what a scene's `position` sets);
//! - `qx,qy,qz,qw`: orientation of the body frame, unit quaternion (x, y, z, w);
//! - `vx,vy,vz`: velocity of the centre of mass; `wx,wy,wz`: angular velocity, world frame.
//!
//! Numbers are written with Rust's shortest round-trip formatting, so reading a recording back
//! gives the simulated values bit for bit (tests rely on it; so can anyone comparing runs). Every
//! frame is flushed when written: a run that is killed leaves a file of whole frames.

use std::fs::File;
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use tumble::{DQuat, DVec3, World};

use crate::error::IoError;

/// The exact first line of every recording.
pub const RECORDING_HEADER: &str = "t,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz";

const COLUMNS: usize = 15;

/// Writes a recording, one frame at a time.
pub struct RecordingWriter<W: Write = BufWriter<File>> {
    csv: csv::Writer<W>,
    path: PathBuf,
    every: u64,
    frames: u64,
}

impl RecordingWriter<BufWriter<File>> {
    /// Creates (or truncates) `path`, creating its folder if needed, and writes the header.
    /// `every`: [`RecordingWriter::record_step`] writes a frame every `every` steps (>= 1).
    pub fn create(path: impl AsRef<Path>, every: u64) -> Result<Self, IoError> {
        let path = path.as_ref();
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| IoError::file(dir, e))?;
        }
        let file = File::create(path).map_err(|e| IoError::file(path, e))?;
        RecordingWriter::new(BufWriter::new(file), every, path)
    }
}

impl<W: Write> RecordingWriter<W> {
    /// Writes the header to `writer`; `path` names it in messages.
    pub fn new(writer: W, every: u64, path: impl AsRef<Path>) -> Result<Self, IoError> {
        let path = path.as_ref().to_owned();
        if every == 0 {
            return Err(IoError::file(
                &path,
                std::io::Error::new(std::io::ErrorKind::InvalidInput, "`every` must be >= 1"),
            ));
        }
        // The csv writer's own buffer is flushed per frame, so it adds no loss on a kill.
        let mut csv = csv::WriterBuilder::new().has_headers(false).from_writer(writer);
        csv.write_record(RECORDING_HEADER.split(',')).map_err(|e| csv_error(&path, e))?;
        csv.flush().map_err(|e| IoError::file(&path, e))?;
        Ok(Self { csv, path, every, frames: 0 })
    }

    /// Writes the world's current state as one frame (every body, in the world's order) and
    /// flushes it.
    pub fn write_frame(&mut self, world: &World) -> Result<(), IoError> {
        let t = num(world.time());
        for (_, body) in world.bodies() {
            let p = body.position();
            let q = body.orientation();
            let v = body.linear_velocity();
            let w = body.angular_velocity();
            let row = [
                t.clone(),
                body.name().to_string(),
                num(p.x),
                num(p.y),
                num(p.z),
                num(q.x),
                num(q.y),
                num(q.z),
                num(q.w),
                num(v.x),
                num(v.y),
                num(v.z),
                num(w.x),
                num(w.y),
                num(w.z),
            ];
            self.csv.write_record(&row).map_err(|e| csv_error(&self.path, e))?;
        }
        self.csv.flush().map_err(|e| IoError::file(&self.path, e))?;
        self.frames += 1;
        Ok(())
    }

    /// Call after each step: writes a frame when the world's step count is a multiple of
    /// `every`. Returns whether it wrote.
    pub fn record_step(&mut self, world: &World) -> Result<bool, IoError> {
        if world.step_count().is_multiple_of(self.every) {
            self.write_frame(world)?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Frames written so far.
    pub fn frames_written(&self) -> u64 {
        self.frames
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Flushes and hands back the underlying writer.
    pub fn finish(self) -> Result<W, IoError> {
        let path = self.path;
        self.csv.into_inner().map_err(|e| IoError::file(&path, e.into_error()))
    }
}

/// Shortest text that parses back to exactly `x` (Rust's `Debug` for f64: round-trip, and it
/// switches to exponent notation for tiny and huge values instead of printing hundreds of zeros).
fn num(x: f64) -> String {
    format!("{x:?}")
}

fn csv_error(path: &Path, e: csv::Error) -> IoError {
    IoError::file(path, e.into())
}

/// One body in one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct BodySample {
    pub name: String,
    /// Body-frame origin, world frame.
    pub position: DVec3,
    pub orientation: DQuat,
    /// Velocity of the centre of mass.
    pub linear_velocity: DVec3,
    /// Angular velocity, world frame.
    pub angular_velocity: DVec3,
}

/// All bodies at one time.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    pub t: f64,
    pub bodies: Vec<BodySample>,
}

/// A recording read back: frames in file order. Consecutive rows with the same `t` form a frame.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Recording {
    pub frames: Vec<Frame>,
}

impl Recording {
    pub fn read(path: impl AsRef<Path>) -> Result<Recording, IoError> {
        let path = path.as_ref();
        let file = File::open(path).map_err(|e| IoError::file(path, e))?;
        Recording::from_reader(std::io::BufReader::new(file), path)
    }

    /// Parses a recording from `reader`; `path` names it in messages.
    pub fn from_reader(reader: impl Read, path: impl AsRef<Path>) -> Result<Recording, IoError> {
        let path = path.as_ref();
        let at = |line: u64, message: String| IoError::AtLine {
            path: path.to_owned(),
            line: line as usize,
            message,
        };
        let mut csv = csv::ReaderBuilder::new().has_headers(false).flexible(true).from_reader(reader);
        let mut records = csv.records();
        let header = match records.next() {
            Some(r) => r.map_err(|e| csv_error(path, e))?,
            None => return Err(at(1, format!("empty file; a recording starts with `{RECORDING_HEADER}`"))),
        };
        if header.iter().collect::<Vec<_>>().join(",") != RECORDING_HEADER {
            return Err(at(1, format!("not a recording: the header must be `{RECORDING_HEADER}`")));
        }
        let mut recording = Recording::default();
        for record in records {
            let record = record.map_err(|e| csv_error(path, e))?;
            let line = record.position().map_or(0, |p| p.line());
            if record.len() != COLUMNS {
                return Err(at(line, format!("expected {COLUMNS} columns, found {}", record.len())));
            }
            let mut values = [0.0; COLUMNS];
            for (i, field) in record.iter().enumerate() {
                if i == 1 {
                    continue;
                }
                values[i] = field.trim().parse().map_err(|_| {
                    let column = RECORDING_HEADER.split(',').nth(i).unwrap_or("?");
                    at(line, format!("column {column}: `{field}` is not a number"))
                })?;
            }
            let v = |i: usize| DVec3::new(values[i], values[i + 1], values[i + 2]);
            let sample = BodySample {
                name: record[1].to_string(),
                position: v(2),
                orientation: DQuat::from_xyzw(values[5], values[6], values[7], values[8]),
                linear_velocity: v(9),
                angular_velocity: v(12),
            };
            let t = values[0];
            match recording.frames.last_mut() {
                Some(frame) if frame.t.to_bits() == t.to_bits() => frame.bodies.push(sample),
                _ => recording.frames.push(Frame { t, bodies: vec![sample] }),
            }
        }
        Ok(recording)
    }

    /// The samples of the body called `name`, one per frame that has it, with their times.
    pub fn body_track<'a>(&'a self, name: &'a str) -> impl Iterator<Item = (f64, &'a BodySample)> + 'a {
        self.frames.iter().filter_map(move |f| f.bodies.iter().find(|b| b.name == name).map(|b| (f.t, b)))
    }
}
