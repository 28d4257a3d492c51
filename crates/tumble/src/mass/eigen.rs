//! Eigen-decomposition of symmetric 3×3 matrices (for principal axes of inertia).

use crate::math::{DMat3, DVec3};

/// Eigenvalues (ascending) and eigenvectors (columns of a rotation, det +1) of a symmetric matrix.
/// Repeated eigenvalues give some orthonormal right-handed frame, never NaN.
pub fn symmetric_eigen(m: DMat3) -> (DVec3, DMat3) {
    todo!()
}
