//! Errors from building the static-geometry shapes (plane, height field).

/// Why a plane or height field cannot be built. Every variant says what and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum ShapeError {
    #[error("plane normal must be finite and non-zero, got ({x}, {y}, {z})")]
    BadPlaneNormal { x: f64, y: f64, z: f64 },
    #[error("plane offset must be finite, got {0}")]
    BadPlaneOffset(f64),
    #[error("height field needs at least 2 x 2 samples, got {rows} rows x {cols} columns")]
    HeightFieldTooSmall { rows: usize, cols: usize },
    #[error("height field of {rows} rows x {cols} columns needs {} heights, got {len}", rows * cols)]
    HeightFieldSize { rows: usize, cols: usize, len: usize },
    #[error("height field sample (row {row}, column {col}) is not finite: {value}")]
    NonFiniteHeight { row: usize, col: usize, value: f64 },
    #[error("height field scale {what} must be finite and > 0, got {value}")]
    BadScale { what: &'static str, value: f64 },
}
