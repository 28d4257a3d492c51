//! Recordings: the state of every body at chosen steps, as CSV, and a reader for them.
//!
//! One row per body per frame, header [`RECORDING_HEADER`]:
//! - `t`: simulated time, s; `body`: the body's name;
//! - `px,py,pz`: world position of the body frame's origin (what a scene's `position` sets);
//! - `qx,qy,qz,qw`: orientation of the body frame, unit quaternion (x, y, z, w);
//! - `vx,vy,vz`: velocity of the centre of mass; `wx,wy,wz`: angular velocity, world frame.
//!
//! Numbers are written with Rust's shortest round-trip formatting, so reading a recording back
//! gives the simulated values bit for bit (tests rely on it; so can anyone comparing runs).
//!
//! Every frame is built in memory and handed to the file in one `write` call, then flushed: a run
//! that is killed leaves a file of whole frames (a regular file's write is not cut short by a
//! signal). Only a crash of the machine itself can leave part of a frame; resuming from a
//! checkpoint ([`RecordingWriter::resume`]) cuts the file back to the frames the checkpoint covers
//! either way.

use std::fs::File;
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use tumble::{DQuat, DVec3, World};

use crate::error::IoError;

/// The exact first line of every recording.
pub const RECORDING_HEADER: &str = "t,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz";

const COLUMNS: usize = 15;

/// Writes a recording, one frame at a time.
pub struct RecordingWriter<W: Write = File> {
    /// One frame (or the header), formatted in memory before it goes to `out` in one piece.
    frame: Vec<u8>,
    out: W,
    path: PathBuf,
    every: u64,
    frames: u64,
    /// Bytes handed to `out` so far: the header and whole frames.
    bytes: u64,
}

fn invalid_every(path: &Path, every: u64) -> Result<(), IoError> {
    if every == 0 {
        return Err(IoError::file(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "`every` must be >= 1"),
        ));
    }
    Ok(())
}

impl RecordingWriter<File> {
    /// Creates (or truncates) `path`, creating its folder if needed, and writes the header.
    /// `every`: [`RecordingWriter::record_step`] writes a frame every `every` steps (>= 1).
    pub fn create(path: impl AsRef<Path>, every: u64) -> Result<Self, IoError> {
        let path = path.as_ref();
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| IoError::file(dir, e))?;
        }
        invalid_every(path, every)?;
        let file = File::create(path).map_err(|e| IoError::file(path, e))?;
        RecordingWriter::new(file, every, path)
    }

    /// Reopens a recording to continue it: cuts `path` back to its first `bytes` bytes (the
    /// header and `frames` whole frames, as [`RecordingWriter::bytes_written`] and
    /// [`RecordingWriter::frames_written`] reported them) and appends from there. An error if the
    /// file is shorter than that.
    pub fn resume(path: impl AsRef<Path>, every: u64, frames: u64, bytes: u64) -> Result<Self, IoError> {
        let path = path.as_ref();
        invalid_every(path, every)?;
        let mut file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .open(path)
            .map_err(|e| IoError::file(path, e))?;
        let len = file.metadata().map_err(|e| IoError::file(path, e))?.len();
        if len < bytes {
            return Err(IoError::file(
                path,
                std::io::Error::new(
                    std::io::ErrorKind::UnexpectedEof,
                    format!("the recording holds {len} bytes, fewer than the {bytes} it had when the checkpoint was written"),
                ),
            ));
        }
        file.set_len(bytes).map_err(|e| IoError::file(path, e))?;
        file.seek(SeekFrom::End(0)).map_err(|e| IoError::file(path, e))?;
        Ok(Self { frame: Vec::new(), out: file, path: path.to_owned(), every, frames, bytes })
    }

    /// Makes what was written so far durable (`fsync`), so a checkpoint that counts on it can be
    /// written after.
    pub fn sync(&self) -> Result<(), IoError> {
        self.out.sync_data().map_err(|e| IoError::file(&self.path, e))
    }
}

impl<W: Write> RecordingWriter<W> {
    /// Writes the header to `writer`; `path` names it in messages.
    pub fn new(writer: W, every: u64, path: impl AsRef<Path>) -> Result<Self, IoError> {
        let path = path.as_ref().to_owned();
        invalid_every(&path, every)?;
        let mut recording = Self { frame: Vec::new(), out: writer, path, every, frames: 0, bytes: 0 };
        recording.emit(|csv| csv.write_record(RECORDING_HEADER.split(',')))?;
        Ok(recording)
    }

    /// Formats rows with `rows` into the frame buffer, then hands them to the output in one piece
    /// and flushes it.
    fn emit(
        &mut self,
        rows: impl FnOnce(&mut csv::Writer<&mut Vec<u8>>) -> Result<(), csv::Error>,
    ) -> Result<(), IoError> {
        self.frame.clear();
        let mut csv = csv::WriterBuilder::new().has_headers(false).from_writer(&mut self.frame);
        rows(&mut csv).map_err(|e| csv_error(&self.path, e))?;
        csv.flush().map_err(|e| IoError::file(&self.path, e))?;
        drop(csv);
        self.out.write_all(&self.frame).map_err(|e| IoError::file(&self.path, e))?;
        self.out.flush().map_err(|e| IoError::file(&self.path, e))?;
        self.bytes += self.frame.len() as u64;
        Ok(())
    }

    /// Writes the world's current state as one frame (every body, in the world's order) and
    /// flushes it.
    pub fn write_frame(&mut self, world: &World) -> Result<(), IoError> {
        self.emit(|csv| {
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
                csv.write_record(&row)?;
            }
            Ok(())
        })?;
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

    /// Bytes written so far: the header and every whole frame.
    pub fn bytes_written(&self) -> u64 {
        self.bytes
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Flushes and hands back the underlying writer.
    pub fn finish(mut self) -> Result<W, IoError> {
        self.out.flush().map_err(|e| IoError::file(&self.path, e))?;
        Ok(self.out)
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
