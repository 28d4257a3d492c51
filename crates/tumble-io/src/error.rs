//! The one error type of `tumble-io`. Every variant says *which file* and, where a line is known,
//! *which line*, because a user reading the message has the file open and nothing else.

use std::path::PathBuf;

/// Errors from reading or writing Tumble's files.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// The file could not be opened, read or written.
    #[error("{}: {source}", path.display())]
    File {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A problem at a known line of a text file (scene or recording):
    /// `scenes/x.toml:14: body "arm": density must be > 0, got -2`.
    #[error("{}:{line}: {message}", path.display())]
    AtLine { path: PathBuf, line: usize, message: String },
    /// A mesh file that could not be turned into a closed triangle mesh.
    #[error("{}: {message}", path.display())]
    Mesh { path: PathBuf, message: String },
    /// A file whose format is not one Tumble reads (by extension).
    #[error("{}: unsupported file type (expected {expected})", path.display())]
    UnsupportedFormat { path: PathBuf, expected: &'static str },
    /// The world refused something while running (for example a non-finite state).
    #[error("{0}")]
    World(#[from] tumble::WorldError),
}

impl IoError {
    /// The line the error points at, when it has one.
    pub fn line(&self) -> Option<usize> {
        match self {
            IoError::AtLine { line, .. } => Some(*line),
            _ => None,
        }
    }

    pub(crate) fn file(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        IoError::File { path: path.into(), source }
    }
}

/// The 1-based line of byte offset `offset` in `text`.
pub(crate) fn line_of(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end].iter().filter(|&&b| b == b'\n').count() + 1
}

#[cfg(test)]
mod tests {
    use super::line_of;

    #[test]
    fn lines_count_from_one() {
        let text = "a\nbb\nccc";
        assert_eq!(line_of(text, 0), 1);
        assert_eq!(line_of(text, 2), 2);
        assert_eq!(line_of(text, 5), 3);
        assert_eq!(line_of(text, 100), 3);
    }
}
