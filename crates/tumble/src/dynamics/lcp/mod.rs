//! The exact solver: impulses for a few constraint rows, found by pivoting rather than iterating.
//!
//! It is the reference the iterative contact/joint solver is tested against, and it is public for
//! anyone who wants exact answers for a few bodies. The pieces, one per file:
//!
//! - [`system`]: the velocity-level description: [`LcpBody`] (inverse mass and world inverse
//!   inertia), [`BodyVelocity`], and [`Row`]s of kind [`RowKind::Equality`] (joints),
//!   [`RowKind::Normal`] (contacts) or [`RowKind::Friction`] (tangents bounded by `μ λ_n`, each row
//!   on its own: a four-sided pyramid per pair of tangent rows); [`ConstraintSystem`] assembles
//!   `A = J M⁻¹ Jᵀ` and `b = J v + bias`.
//! - [`rows`]: builders for point rows, contact points and ball joints.
//! - [`lemke`]: Lemke's complementary pivoting algorithm for a standard LCP, with lexicographic
//!   tie-breaking.
//! - `mixed`: equality rows eliminated by a Schur complement, friction by the Stewart–Trinkle
//!   construction, giving one standard LCP.
//! - [`dense`]: a small dense matrix and LU factorisation.
//!
//! [`solve_exact`] runs them in order. The derivation, with references, is in `docs/lcp.md`.
//!
//! ```
//! use tumble::dynamics::lcp::{solve_exact, contact_rows, Anchor, BodyVelocity, ContactPoint, LcpBody};
//! use tumble::{DMat3, DVec3};
//!
//! // A 2 kg particle falling at 0.1 m/s onto the ground: the normal impulse stops it.
//! let body = LcpBody::new(0.5, DMat3::ZERO);
//! let v = BodyVelocity::new(DVec3::new(0.0, 0.0, -0.1), DVec3::ZERO);
//! let contact = ContactPoint {
//!     a: Anchor::WORLD,
//!     b: Anchor::new(0, DVec3::ZERO),
//!     normal: DVec3::Z,
//!     tangent: DVec3::X,
//!     mu: 0.5,
//!     bias: 0.0,
//! };
//! let sol = solve_exact(&[body], &[v], &contact_rows(&contact, 0)).unwrap();
//! assert!((sol.impulses[0] - 0.2).abs() < 1e-15);
//! assert!(sol.velocities[0].linear.length() < 1e-15);
//! ```

pub mod dense;
mod error;
pub mod lemke;
mod mixed;
#[cfg(test)]
mod pgs;
pub mod rows;
pub mod system;

pub use dense::DenseMatrix;
pub use error::LcpError;
pub use lemke::{natural_residual, solve_lcp, LcpSolution};
pub use rows::{ball_joint_rows, contact_rows, point_row, Anchor, ContactPoint};
pub use system::{apply_impulses, BodyVelocity, ConstraintSystem, LcpBody, Row, RowKind, MAX_ROWS};

/// The exact impulses of a system and what they do.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ExactSolution {
    /// `λ` per row, in the order of the rows.
    pub impulses: Vec<f64>,
    /// Body velocities after the impulses, `v + M⁻¹ Jᵀ λ`.
    pub velocities: Vec<BodyVelocity>,
    /// Row velocities after the impulses, `J v⁺ + bias`.
    pub row_velocities: Vec<f64>,
    /// Pivots Lemke's algorithm took.
    pub pivots: usize,
    /// Unknowns of the standard LCP solved: normal rows + 3 × friction rows.
    pub lcp_size: usize,
}

impl ExactSolution {
    /// The natural residual of the row conditions for these impulses and row velocities:
    /// `max |λ − mid(lo, hi, λ − w)|` over the rows, with bounds `(−∞, ∞)` for equality rows,
    /// `[0, ∞)` for normal rows and `[−μλ_n, μλ_n]` for friction rows. Zero exactly at a solution;
    /// round-off level (a mix of impulse and velocity units) for what [`solve_exact`] returns.
    pub fn residual(&self, rows: &[Row]) -> f64 {
        residual(rows, &self.impulses, &self.row_velocities)
    }
}

/// The natural residual of the row conditions for any impulses `impulses` and row velocities
/// `row_velocities` (see [`ExactSolution::residual`]); useful to judge an iterative solver's answer.
pub fn residual(rows: &[Row], impulses: &[f64], row_velocities: &[f64]) -> f64 {
    let kinds: Vec<RowKind> = rows.iter().map(|r| r.kind).collect();
    mixed::mixed_residual(&kinds, impulses, row_velocities)
}

/// Solves the rows exactly: the impulses `λ` such that, with `w = J (v + M⁻¹Jᵀλ) + bias`,
/// equality rows have `w = 0`, normal rows `λ ≥ 0, w ≥ 0, λw = 0`, and friction rows stick
/// (`w = 0`, `|λ| ≤ μλ_n`) or slide at full friction (`λ = −μλ_n sign w`).
///
/// `velocities` are the velocities before any impulse (e.g. after the step's gravity). At most
/// [`MAX_ROWS`] rows. Errors: invalid input (counts, indices, non-finite numbers, a friction row
/// that does not name a normal row), dependent equality rows, or a problem with no solution
/// (reported as Lemke's ray termination).
///
/// Where the physics leaves the impulses undetermined (e.g. four coplanar contacts under a box),
/// this returns one valid answer; compare sums or velocities, which are unique, with other solvers.
pub fn solve_exact(
    bodies: &[LcpBody],
    velocities: &[BodyVelocity],
    rows: &[Row],
) -> Result<ExactSolution, LcpError> {
    let system = ConstraintSystem::assemble(bodies, velocities, rows)?;
    let kinds: Vec<RowKind> = rows.iter().map(|r| r.kind).collect();
    let mixed = mixed::solve_mixed(&system.a, &system.b, &kinds)?;
    let after = apply_impulses(bodies, velocities, rows, &mixed.lambda);
    let row_velocities = rows.iter().map(|r| r.velocity(&after) + r.bias).collect();
    Ok(ExactSolution {
        impulses: mixed.lambda,
        velocities: after,
        row_velocities,
        pivots: mixed.pivots,
        lcp_size: mixed.lcp_size,
    })
}
