//! What can go wrong when the exact solver is given a system, and why.

/// Errors from the exact (LCP) solver: bad input, found before any arithmetic, or a pivoting
/// algorithm that could not finish.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum LcpError {
    #[error(
        "too many rows: {rows}, the exact solver takes at most {max} (its cost grows like the cube of the \
         row count; use the iterative solver for large systems)"
    )]
    TooManyRows { rows: usize, max: usize },
    #[error("{bodies} bodies but {velocities} velocities: give exactly one velocity per body")]
    VelocityCount { bodies: usize, velocities: usize },
    #[error("non-finite input: {what}")]
    NonFinite { what: String },
    #[error("body {body}: {reason}")]
    InvalidBody { body: usize, reason: String },
    #[error("row {row}: refers to body {index}, but there are only {bodies} bodies")]
    BodyIndex { row: usize, index: usize, bodies: usize },
    #[error("row {row}: body_a and body_b are the same body {body}; a row couples two different bodies")]
    SameBody { row: usize, body: usize },
    #[error("row {row}: friction row names normal_row {normal_row}, {reason}")]
    NormalRow { row: usize, normal_row: usize, reason: String },
    #[error("row {row}: friction coefficient must be finite and >= 0, got {mu}")]
    FrictionCoefficient { row: usize, mu: f64 },
    #[error(
        "the equality rows are linearly dependent, or some act on no dynamic body: their effective-mass \
         block J M⁻¹ Jᵀ is singular (pivot {pivot:e} at equality row {row}); remove the redundant rows"
    )]
    SingularEquality { row: usize, pivot: f64 },
    #[error(
        "Lemke's algorithm ended on a secondary ray after {pivots} pivots: no column could leave the basis \
         when {entering} entered. The LCP has no solution (e.g. a normal row between static bodies asking \
         for a separating velocity), or it is degenerate beyond what the tie-breaking resolves"
    )]
    RayTermination { pivots: usize, entering: String },
    #[error("Lemke's algorithm did not finish within {max_pivots} pivots")]
    MaxPivots { max_pivots: usize },
    #[error(
        "dimension mismatch: the LCP matrix is {rows}x{cols} and q has {len} entries; the matrix must be \
         square and q must have one entry per row"
    )]
    Dimension { rows: usize, cols: usize, len: usize },
}
