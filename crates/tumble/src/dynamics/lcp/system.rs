//! The velocity-level constraint system: bodies (inverse masses), their velocities, and rows
//! `J v`, independent of the rest of the engine.
//!
//! A row couples at most two bodies. Its Jacobian is four 3-vectors,
//! `[linear_a, angular_a, linear_b, angular_b]`, so that the row's velocity is
//!
//! ```text
//!     J v = linear_a·v_a + angular_a·ω_a + linear_b·v_b + angular_b·ω_b
//! ```
//!
//! and an impulse `λ` along the row changes the velocities by `M⁻¹ Jᵀ λ`:
//! `Δv_a = m_a⁻¹ linear_a λ`, `Δω_a = I_a⁻¹ angular_a λ`, and likewise for `b`. After all impulses,
//! the row's velocity is `J v⁺ + bias = (J v + bias) + (J M⁻¹ Jᵀ) λ = b + A λ`: `A` is the
//! Delassus (effective inverse mass) matrix and `b` the free velocity. For one row at a point `r`
//! of one body, `A` is `nᵀ K n` with the lecture's point inverse mass matrix `K = m⁻¹ 1 − r̂ I⁻¹ r̂`.

use super::dense::DenseMatrix;
use super::error::LcpError;
use crate::math::{is_finite_vec, mat3_max_abs, DMat3, DVec3};

/// The most rows [`ConstraintSystem::assemble`] and [`super::solve_exact`] accept. The friction
/// formulation turns `r` rows into an LCP of up to `3r` unknowns with a `3r × (6r + 2)` tableau, and
/// each pivot costs O(r²): at 126 random frictional contact rows a solve measured up to ~700 pivots
/// and ~0.1 s in an optimised build. Bigger systems are the iterative solver's job.
pub const MAX_ROWS: usize = 128;

/// A body as the solver sees it: inverse mass and world-frame inverse inertia about the centre of
/// mass. Static (and kinematic) bodies have both zero.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LcpBody {
    pub inverse_mass: f64,
    pub inverse_inertia_world: DMat3,
}

impl LcpBody {
    /// A body that impulses cannot move.
    pub const STATIC: Self = Self { inverse_mass: 0.0, inverse_inertia_world: DMat3::ZERO };

    pub fn new(inverse_mass: f64, inverse_inertia_world: DMat3) -> Self {
        Self { inverse_mass, inverse_inertia_world }
    }
}

/// The velocity of a body: centre of mass velocity and angular velocity, world frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BodyVelocity {
    pub linear: DVec3,
    pub angular: DVec3,
}

impl BodyVelocity {
    pub fn new(linear: DVec3, angular: DVec3) -> Self {
        Self { linear, angular }
    }
}

/// What a row asks of its impulse `λ` and velocity `w = J v⁺ + bias`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum RowKind {
    /// A joint row: `w = 0`, `λ` free.
    Equality,
    /// A contact normal: `λ ≥ 0`, `w ≥ 0`, `λ w = 0`.
    Normal,
    /// A friction (tangent) row bounded by its contact's normal impulse: `|λ| ≤ μ λ_n`, with
    /// `w = 0` while `|λ| < μ λ_n` (sticking), and `λ = −μ λ_n · sign(w)` when `w ≠ 0` (sliding).
    ///
    /// Each friction row is bounded on its own. Two tangent rows at a contact therefore make a
    /// four-sided friction pyramid whose faces are aligned with the two tangents (a square of side
    /// `2 μ λ_n` in the tangent plane), which is what per-row clamping in an iterative solver gives.
    Friction {
        /// Index of the contact's [`RowKind::Normal`] row.
        normal_row: usize,
        /// Friction coefficient, finite and `≥ 0`.
        mu: f64,
    },
}

/// One constraint row; see the module documentation for the meaning of the Jacobian.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Row {
    /// First body, or `None` for the fixed world.
    pub body_a: Option<usize>,
    /// Second body, or `None` for the fixed world.
    pub body_b: Option<usize>,
    /// `[linear_a, angular_a, linear_b, angular_b]`.
    pub jacobian: [DVec3; 4],
    /// Target: `J v⁺ + bias ≥ 0` (normal) or `= 0` (equality, friction while sticking).
    pub bias: f64,
    pub kind: RowKind,
}

impl Row {
    /// The row's velocity `J v` (without the bias).
    pub fn velocity(&self, velocities: &[BodyVelocity]) -> f64 {
        let [la, aa, lb, ab] = self.jacobian;
        let mut s = 0.0;
        if let Some(a) = self.body_a {
            s += la.dot(velocities[a].linear) + aa.dot(velocities[a].angular);
        }
        if let Some(b) = self.body_b {
            s += lb.dot(velocities[b].linear) + ab.dot(velocities[b].angular);
        }
        s
    }

    /// The (body, linear, angular) parts of the row, one per body it touches.
    fn parts(&self) -> impl Iterator<Item = (usize, DVec3, DVec3)> + '_ {
        let [la, aa, lb, ab] = self.jacobian;
        self.body_a.map(|a| (a, la, aa)).into_iter().chain(self.body_b.map(|b| (b, lb, ab)))
    }
}

/// The assembled system: `A = J M⁻¹ Jᵀ` (dense, symmetric, positive semidefinite) and the free row
/// velocities `b = J v + bias`, `v` being the velocities before any impulse.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ConstraintSystem {
    pub a: DenseMatrix,
    pub b: Vec<f64>,
}

impl ConstraintSystem {
    /// Validates the input (see [`validate`]) and assembles `A` and `b`.
    pub fn assemble(bodies: &[LcpBody], velocities: &[BodyVelocity], rows: &[Row]) -> Result<Self, LcpError> {
        validate(bodies, velocities, rows)?;
        let n = rows.len();
        // M⁻¹ Jᵀ per row and body, computed once.
        let scaled: Vec<Vec<(usize, DVec3, DVec3)>> = rows
            .iter()
            .map(|row| {
                row.parts()
                    .map(|(body, lin, ang)| {
                        let bd = &bodies[body];
                        (body, bd.inverse_mass * lin, bd.inverse_inertia_world * ang)
                    })
                    .collect()
            })
            .collect();
        let mut a = DenseMatrix::zeros(n, n);
        for (i, row) in rows.iter().enumerate() {
            for j in 0..=i {
                let mut s = 0.0;
                for (body, lin, ang) in row.parts() {
                    for &(other, m_lin, m_ang) in &scaled[j] {
                        if other == body {
                            s += lin.dot(m_lin) + ang.dot(m_ang);
                        }
                    }
                }
                a[(i, j)] = s;
                a[(j, i)] = s;
            }
        }
        let b = rows.iter().map(|row| row.velocity(velocities) + row.bias).collect();
        Ok(Self { a, b })
    }
}

/// The velocities after impulses `impulses[i]` along each row: `v⁺ = v + M⁻¹ Jᵀ λ`.
pub fn apply_impulses(
    bodies: &[LcpBody],
    velocities: &[BodyVelocity],
    rows: &[Row],
    impulses: &[f64],
) -> Vec<BodyVelocity> {
    let mut out = velocities.to_vec();
    for (row, &lambda) in rows.iter().zip(impulses) {
        for (body, lin, ang) in row.parts() {
            let bd = &bodies[body];
            out[body].linear += bd.inverse_mass * lambda * lin;
            out[body].angular += bd.inverse_inertia_world * (lambda * ang);
        }
    }
    out
}

/// Checks everything the solver relies on, with messages that name the body or row: counts,
/// finiteness, body indices, inverse masses `≥ 0` and symmetric inverse inertias with a
/// nonnegative diagonal, friction rows that name a normal row and have `μ ≥ 0`.
pub fn validate(bodies: &[LcpBody], velocities: &[BodyVelocity], rows: &[Row]) -> Result<(), LcpError> {
    if bodies.len() != velocities.len() {
        return Err(LcpError::VelocityCount { bodies: bodies.len(), velocities: velocities.len() });
    }
    if rows.len() > MAX_ROWS {
        return Err(LcpError::TooManyRows { rows: rows.len(), max: MAX_ROWS });
    }
    for (i, body) in bodies.iter().enumerate() {
        let inv_i = body.inverse_inertia_world;
        if !body.inverse_mass.is_finite() || !inv_i.is_finite() {
            return Err(LcpError::NonFinite { what: format!("body {i}: inverse mass or inverse inertia") });
        }
        if body.inverse_mass < 0.0 {
            let reason = format!("inverse mass must be >= 0, got {}", body.inverse_mass);
            return Err(LcpError::InvalidBody { body: i, reason });
        }
        let asym = mat3_max_abs(inv_i - inv_i.transpose());
        if asym > 1e-9 * mat3_max_abs(inv_i) {
            let reason = format!("inverse inertia is not symmetric (largest asymmetry {asym:e})");
            return Err(LcpError::InvalidBody { body: i, reason });
        }
        let diag = DVec3::new(inv_i.x_axis.x, inv_i.y_axis.y, inv_i.z_axis.z);
        if diag.min_element() < 0.0 {
            let reason = format!("inverse inertia has a negative diagonal entry: {diag}");
            return Err(LcpError::InvalidBody { body: i, reason });
        }
    }
    for (i, v) in velocities.iter().enumerate() {
        if !is_finite_vec(v.linear) || !is_finite_vec(v.angular) {
            return Err(LcpError::NonFinite { what: format!("velocity of body {i}") });
        }
    }
    for (i, row) in rows.iter().enumerate() {
        validate_row(i, row, rows, bodies.len())?;
    }
    Ok(())
}

fn validate_row(i: usize, row: &Row, rows: &[Row], bodies: usize) -> Result<(), LcpError> {
    for index in [row.body_a, row.body_b].into_iter().flatten() {
        if index >= bodies {
            return Err(LcpError::BodyIndex { row: i, index, bodies });
        }
    }
    if let (Some(a), Some(b)) = (row.body_a, row.body_b) {
        if a == b {
            return Err(LcpError::SameBody { row: i, body: a });
        }
    }
    if !row.jacobian.iter().all(|&v| is_finite_vec(v)) || !row.bias.is_finite() {
        return Err(LcpError::NonFinite { what: format!("row {i}: jacobian or bias") });
    }
    if let RowKind::Friction { normal_row, mu } = row.kind {
        if !mu.is_finite() || mu < 0.0 {
            return Err(LcpError::FrictionCoefficient { row: i, mu });
        }
        let reason = match rows.get(normal_row).map(|r| r.kind) {
            None => Some(format!("but there are only {} rows", rows.len())),
            Some(RowKind::Normal) => None,
            Some(kind) => Some(format!("which is not a normal row but {kind:?}")),
        };
        if let Some(reason) = reason {
            return Err(LcpError::NormalRow { row: i, normal_row, reason });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::hat;

    #[test]
    fn one_row_is_the_lecture_point_inverse_mass() {
        // A row along n at offset r of one body: A = nᵀ K n with K = m⁻¹ 1 − r̂ I⁻¹ r̂.
        let inv_inertia = DMat3::from_cols(
            DVec3::new(0.5, 0.1, 0.0),
            DVec3::new(0.1, 0.8, 0.05),
            DVec3::new(0.0, 0.05, 0.3),
        );
        let body = LcpBody::new(0.25, inv_inertia);
        let r = DVec3::new(0.3, -0.2, 0.7);
        let n = DVec3::new(0.2, 0.9, -0.4).normalize();
        let row = Row {
            body_a: None,
            body_b: Some(0),
            jacobian: [DVec3::ZERO, DVec3::ZERO, n, r.cross(n)],
            bias: 0.0,
            kind: RowKind::Normal,
        };
        let sys = ConstraintSystem::assemble(&[body], &[BodyVelocity::default()], &[row]).unwrap();
        let k = DMat3::from_diagonal(DVec3::splat(0.25)) - hat(r) * inv_inertia * hat(r);
        assert!((sys.a[(0, 0)] - n.dot(k * n)).abs() < 1e-15);
    }

    #[test]
    fn impulses_move_the_row_velocity_by_a_lambda() {
        let inv_i = DMat3::from_diagonal(DVec3::new(2.0, 3.0, 4.0));
        let bodies = [LcpBody::new(0.5, inv_i), LcpBody::new(1.5, inv_i * 0.5)];
        let vel = [
            BodyVelocity::new(DVec3::new(1.0, 0.0, -1.0), DVec3::new(0.2, 0.1, 0.0)),
            BodyVelocity::new(DVec3::new(0.0, 2.0, 0.5), DVec3::new(0.0, -0.3, 0.4)),
        ];
        let row = |l: [f64; 3], s: f64| Row {
            body_a: Some(0),
            body_b: Some(1),
            jacobian: [DVec3::from(l), DVec3::new(0.1, s, 0.2), -DVec3::from(l), DVec3::new(s, 0.3, -0.1)],
            bias: s,
            kind: RowKind::Equality,
        };
        let rows = [row([1.0, 0.0, 0.0], 0.2), row([0.0, 0.6, 0.8], -0.4), row([0.0, 0.0, 1.0], 0.7)];
        let sys = ConstraintSystem::assemble(&bodies, &vel, &rows).unwrap();
        let lambda = [0.3, -1.2, 0.5];
        let after = apply_impulses(&bodies, &vel, &rows, &lambda);
        let predicted: Vec<f64> = sys.a.mul_vec(&lambda).iter().zip(&sys.b).map(|(x, y)| x + y).collect();
        for (row, p) in rows.iter().zip(predicted) {
            assert!((row.velocity(&after) + row.bias - p).abs() < 1e-14);
        }
    }
}
