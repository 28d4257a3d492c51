//! Surface materials and how two of them combine at a contact.
//!
//! Combine rules (documented, and the same in every pair order):
//! - friction: geometric mean `√(μ_a μ_b)` — a frictionless surface (0) makes the contact
//!   frictionless, and equal materials keep their value;
//! - restitution: the larger, `max(e_a, e_b)` — a bouncy ball bounces on any floor;
//! - rolling and torsional friction: the larger of the two.

use super::contact_solver::ContactMaterial;

/// A shape's surface.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Material {
    /// Coulomb friction coefficient μ (≥ 0). Default 0.6.
    pub friction: f64,
    /// Coefficient of restitution e in [0, 1]. Default 0.
    pub restitution: f64,
    /// Rolling resistance, m: the resisting torque is this times the normal force. Default 0.
    pub rolling_friction: f64,
    /// Torsional (spinning) resistance, m: the resisting torque about the normal is this times
    /// the normal force. Default 0.
    pub torsional_friction: f64,
}

impl Default for Material {
    fn default() -> Self {
        Material { friction: 0.6, restitution: 0.0, rolling_friction: 0.0, torsional_friction: 0.0 }
    }
}

impl Material {
    /// Checks every coefficient; the message names the bad one.
    pub fn validate(&self) -> Result<(), String> {
        for (what, v) in [
            ("friction", self.friction),
            ("rolling_friction", self.rolling_friction),
            ("torsional_friction", self.torsional_friction),
        ] {
            if !v.is_finite() || v < 0.0 {
                return Err(format!("{what} must be finite and >= 0, got {v}"));
            }
        }
        if !(0.0..=1.0).contains(&self.restitution) {
            return Err(format!("restitution must be in [0, 1], got {}", self.restitution));
        }
        Ok(())
    }

    /// The material of a contact between surfaces `a` and `b`.
    pub fn combine(a: &Material, b: &Material) -> ContactMaterial {
        ContactMaterial {
            friction: (a.friction * b.friction).sqrt(),
            restitution: a.restitution.max(b.restitution),
            rolling_friction: a.rolling_friction.max(b.rolling_friction),
            torsional_friction: a.torsional_friction.max(b.torsional_friction),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combine_is_symmetric_and_keeps_equal_materials() {
        let a = Material { friction: 0.4, restitution: 0.2, rolling_friction: 0.01, torsional_friction: 0.0 };
        let b = Material { friction: 0.9, restitution: 0.7, rolling_friction: 0.0, torsional_friction: 0.02 };
        assert_eq!(Material::combine(&a, &b), Material::combine(&b, &a));
        let same = Material::combine(&a, &a);
        assert!((same.friction - 0.4).abs() < 1e-15);
        assert_eq!(Material::combine(&a, &b).restitution, 0.7);
        assert!(Material { restitution: 1.5, ..a }.validate().unwrap_err().contains("restitution"));
    }
}
