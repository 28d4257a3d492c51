//! Soft constraints: a constraint treated as a damped spring of frequency `hertz` and damping
//! ratio `ζ`, integrated implicitly over the substep `h`.
//!
//! For a position error `C` and velocity error `Ċ`, the soft velocity update is
//! `λ = −m_eff · mass_scale · (Ċ + bias_rate · C) − impulse_scale · λ_accumulated`, with
//! `ω = 2π·hertz`, `a₁ = 2ζ + hω`, `a₂ = hω·a₁`, `a₃ = 1/(1 + a₂)`:
//! `bias_rate = ω / a₁`, `mass_scale = a₂ a₃`, `impulse_scale = a₃`.
//! This is implicit Euler applied to the spring–damper `m C̈ + c Ċ + k C = 0` solved for the
//! impulse (Catto, "Solver2D", 2024; Box2D v3 `b2MakeSoft`). A rigid constraint is the limit
//! `hertz → ∞`; `hertz = 0` gives no position correction at all.

use std::f64::consts::TAU;

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Softness {
    pub bias_rate: f64,
    pub mass_scale: f64,
    pub impulse_scale: f64,
}

impl Softness {
    /// No position correction, full mass: a plain velocity constraint (used in the relax pass).
    pub const RIGID_VELOCITY: Softness = Softness { bias_rate: 0.0, mass_scale: 1.0, impulse_scale: 0.0 };

    /// A spring of `hertz` and damping ratio `zeta`, for substep `h`.
    pub fn new(hertz: f64, zeta: f64, h: f64) -> Softness {
        if hertz <= 0.0 {
            return Softness::RIGID_VELOCITY;
        }
        let omega = TAU * hertz;
        let a1 = 2.0 * zeta + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Softness { bias_rate: omega / a1, mass_scale: a2 * a3, impulse_scale: a3 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A soft constraint on a unit mass with no other forces is a damped spring: check it rings at
    /// its frequency (implicit Euler lengthens the period by O((ωh)²)).
    #[test]
    fn soft_constraint_is_a_spring() {
        let (hertz, zeta, h) = (2.0, 0.0, 1.0 / 240.0);
        let s = Softness::new(hertz, zeta, h);
        let (mut x, mut v) = (1.0_f64, 0.0_f64);
        let mut crossings = Vec::new();
        for n in 0..2400 {
            // Velocity step from the soft constraint (no accumulated impulse: impulse_scale term 0).
            let impulse = -s.mass_scale * (v + s.bias_rate * x);
            v += impulse;
            let x_old = x;
            x += h * v;
            if x_old > 0.0 && x <= 0.0 {
                crossings.push(n as f64 * h);
            }
        }
        let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
        assert!((period * hertz - 1.0).abs() < 0.01, "period {period}");
    }
}
