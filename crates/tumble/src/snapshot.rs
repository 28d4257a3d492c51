//! Exact snapshots: `World::snapshot()` writes everything that decides the world's future —
//! bodies and their shapes, joints and their accumulated impulses, the broad-phase trees, contacts
//! with their manifolds, narrow-phase caches and warm-start impulses, sleep timers and islands,
//! id generations, settings, time — and `World::restore()` reads it back, so that stepping a
//! restored world is bit-identical to stepping the original on.
//!
//! Format: an 8-byte magic `TUMBLESN`, a little-endian `u32` format version, a `u64` payload
//! length and a `u64` FNV-1a checksum of the payload, then the payload (the world encoded with
//! `postcard`, a compact serde format: f64 as its 8 bytes, so values round-trip exactly). A
//! truncated, foreign, newer or damaged file is an error that says which. [`seal`] and [`unseal`]
//! are that envelope on its own, for files that carry other payloads (the CLI's checkpoints).

use crate::state_hash::Fnv64;
use crate::world::World;

const MAGIC: &[u8; 8] = b"TUMBLESN";
/// Bumped whenever the encoded state changes shape. (postcard is not self-describing: a field
/// added to a saved struct shifts everything after it, so serde defaults cannot make an older
/// payload readable; the version says so instead.) 3: bodies carry the `bullet` flag. 4: contacts
/// carry the poses their manifold was made at, the world whether its proxies are in place, and a
/// body's fields are in a new order. 5: contact points carry how long they have been learning
/// their steady load. 6: contacts are a list in the order they were made (was a map keyed by
/// their proxy pair). 7: the broad phase's trees keep no scratch stack. 8: triangle meshes keep
/// each triangle's edge bends. 9: a contact's fields are in a new order (head first).
pub const SNAPSHOT_VERSION: u32 = 9;
const HEADER_LEN: usize = 8 + 4 + 8 + 8;

/// Why a snapshot could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SnapshotError {
    #[error("not a Tumble snapshot (the file does not start with TUMBLESN)")]
    NotASnapshot,
    #[error("snapshot is truncated: {got} bytes, expected {expected}")]
    Truncated { expected: u64, got: u64 },
    #[error("snapshot format version {found} is not supported (this build reads version {supported})")]
    UnsupportedVersion { found: u32, supported: u32 },
    #[error("snapshot is damaged: its checksum does not match its contents")]
    Corrupt,
    #[error("snapshot could not be decoded: {0}")]
    Decode(String),
}

fn checksum(payload: &[u8]) -> u64 {
    let mut h = Fnv64(Fnv64::OFFSET);
    h.bytes(payload);
    h.0
}

/// `payload` in the envelope of the module docs, with `magic` and `version` in the header.
pub fn seal(magic: &[u8; 8], version: u32, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER_LEN + payload.len());
    out.extend_from_slice(magic);
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&checksum(payload).to_le_bytes());
    out.extend_from_slice(payload);
    out
}

/// The payload of [`seal`]ed bytes, once their magic, version, length and checksum are checked.
/// A magic other than `magic` is [`SnapshotError::NotASnapshot`].
pub fn unseal<'a>(magic: &[u8; 8], version: u32, bytes: &'a [u8]) -> Result<&'a [u8], SnapshotError> {
    if bytes.len() < magic.len() || &bytes[..magic.len()] != magic {
        return Err(SnapshotError::NotASnapshot);
    }
    if bytes.len() < HEADER_LEN {
        return Err(SnapshotError::Truncated { expected: HEADER_LEN as u64, got: bytes.len() as u64 });
    }
    let word = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes"));
    let found = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if found != version {
        return Err(SnapshotError::UnsupportedVersion { found, supported: version });
    }
    let (length, sum) = (word(12), word(20));
    let expected = (HEADER_LEN as u64).saturating_add(length);
    if (bytes.len() as u64) < expected {
        return Err(SnapshotError::Truncated { expected, got: bytes.len() as u64 });
    }
    let payload = &bytes[HEADER_LEN..expected as usize];
    if checksum(payload) != sum {
        return Err(SnapshotError::Corrupt);
    }
    Ok(payload)
}

impl World {
    /// The world's complete state as bytes (see the module docs for the format).
    pub fn snapshot(&self) -> Vec<u8> {
        let payload = postcard::to_stdvec(self).expect("a world always encodes: it holds only plain data");
        seal(MAGIC, SNAPSHOT_VERSION, &payload)
    }

    /// A world rebuilt from `snapshot()` bytes; stepping it is bit-identical to stepping the world
    /// the snapshot was taken from.
    pub fn restore(bytes: &[u8]) -> Result<World, SnapshotError> {
        let payload = unseal(MAGIC, SNAPSHOT_VERSION, bytes)?;
        postcard::from_bytes(payload).map_err(|e| SnapshotError::Decode(e.to_string()))
    }
}
