//! Mass properties of the primitive solids, and the operations that move and combine them.
//!
//! Every primitive is centred on the origin of its frame with its symmetry axis along Z, so its
//! inertia is diagonal in that frame; the cone is the one solid whose centre of mass is not at the
//! origin (it is a quarter of the height above the base).

use std::f64::consts::PI;

use super::{symmetric_eigen, MassError, MassProperties, PrincipalFrame};
use crate::math::{DMat3, DVec3, Transform};

/// Checks that a size, density or mass is finite and strictly positive.
pub(super) fn positive(what: &'static str, value: f64) -> Result<f64, MassError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MassError::NotPositive { what, value })
    }
}

/// `m ((d·d) 1 − d dᵀ)`: the inertia of a point mass `m` at offset `d`, i.e. what the
/// parallel-axis theorem adds when an inertia about the centre of mass is moved by `d`.
pub(super) fn point_mass_inertia(mass: f64, d: DVec3) -> DMat3 {
    let (x, y, z) = (d.x, d.y, d.z);
    mass * DMat3::from_cols(
        DVec3::new(y * y + z * z, -x * y, -x * z),
        DVec3::new(-x * y, x * x + z * z, -y * z),
        DVec3::new(-x * z, -y * z, x * x + y * y),
    )
}

/// The solid's properties with the inertia diagonal in its own axes.
fn diagonal(volume: f64, density: f64, center_of_mass: DVec3, moments: DVec3) -> MassProperties {
    MassProperties { volume, mass: density * volume, center_of_mass, inertia: DMat3::from_diagonal(moments) }
}

impl MassProperties {
    /// Solid ball of `radius` at uniform `density`.
    ///
    /// `V = 4/3 π r³`, `I = 2/5 m r²` about every axis.
    pub fn sphere(radius: f64, density: f64) -> Result<Self, MassError> {
        let r = positive("sphere radius", radius)?;
        let rho = positive("density", density)?;
        let volume = 4.0 / 3.0 * PI * r * r * r;
        let m = rho * volume;
        Ok(diagonal(volume, rho, DVec3::ZERO, DVec3::splat(0.4 * m * r * r)))
    }

    /// Solid box with `half_extents` at uniform `density`.
    ///
    /// With full edges `2a, 2b, 2c`: `V = 8abc`, `I_xx = m (b² + c²)/3` and cyclically.
    pub fn cuboid(half_extents: DVec3, density: f64) -> Result<Self, MassError> {
        let a = positive("box half extent x", half_extents.x)?;
        let b = positive("box half extent y", half_extents.y)?;
        let c = positive("box half extent z", half_extents.z)?;
        let rho = positive("density", density)?;
        let volume = 8.0 * a * b * c;
        let m = rho * volume;
        let moments = DVec3::new(b * b + c * c, a * a + c * c, a * a + b * b) * (m / 3.0);
        Ok(diagonal(volume, rho, DVec3::ZERO, moments))
    }

    /// Solid capsule along Z (cylinder of `half_height` plus two hemispherical caps).
    ///
    /// Cylinder part (mass `m_c`, length `2h`): `I_zz = m_c r²/2`, `I_xx = m_c (r²/4 + h²/3)`.
    /// Each cap (mass `m_h = 2/3 π r³ ρ`) has `I = 2/5 m_h r²` about its flat face's centre, and its
    /// own centre of mass is `3r/8` from that face. Exact parallel axis: remove `m_h (3r/8)²` to
    /// reach the cap's centre of mass, then add `m_h (h + 3r/8)²` to reach the capsule's centre:
    /// `I_xx(cap) = m_h (2/5 r² + h² + 3/4 h r)`.
    pub fn capsule(radius: f64, half_height: f64, density: f64) -> Result<Self, MassError> {
        let r = positive("capsule radius", radius)?;
        let h = positive("capsule half_height", half_height)?;
        let rho = positive("density", density)?;
        let v_cyl = PI * r * r * (2.0 * h);
        let v_cap = 2.0 / 3.0 * PI * r * r * r;
        let (m_cyl, m_cap) = (rho * v_cyl, rho * v_cap);
        let i_zz = 0.5 * m_cyl * r * r + 2.0 * (0.4 * m_cap * r * r);
        let i_xx = m_cyl * (0.25 * r * r + h * h / 3.0) + 2.0 * m_cap * (0.4 * r * r + h * h + 0.75 * h * r);
        Ok(MassProperties {
            volume: v_cyl + 2.0 * v_cap,
            mass: m_cyl + 2.0 * m_cap,
            center_of_mass: DVec3::ZERO,
            inertia: DMat3::from_diagonal(DVec3::new(i_xx, i_xx, i_zz)),
        })
    }

    /// Solid cylinder along Z.
    ///
    /// `V = π r² H` with `H = 2h`; `I_zz = m r²/2`, `I_xx = I_yy = m (r²/4 + H²/12)`.
    pub fn cylinder(radius: f64, half_height: f64, density: f64) -> Result<Self, MassError> {
        let r = positive("cylinder radius", radius)?;
        let h = positive("cylinder half_height", half_height)?;
        let rho = positive("density", density)?;
        let height = 2.0 * h;
        let volume = PI * r * r * height;
        let m = rho * volume;
        let i_xx = m * (0.25 * r * r + height * height / 12.0);
        Ok(diagonal(volume, rho, DVec3::ZERO, DVec3::new(i_xx, i_xx, 0.5 * m * r * r)))
    }

    /// Solid cone along Z, base at −half_height, apex at +half_height.
    ///
    /// `V = π r² H / 3` with `H = 2h`; the centre of mass is `H/4` above the base, at `z = −h/2`.
    /// About it: `I_zz = 3/10 m r²`, `I_xx = I_yy = m (3/20 r² + 3/80 H²)`.
    pub fn cone(radius: f64, half_height: f64, density: f64) -> Result<Self, MassError> {
        let r = positive("cone radius", radius)?;
        let h = positive("cone half_height", half_height)?;
        let rho = positive("density", density)?;
        let height = 2.0 * h;
        let volume = PI * r * r * height / 3.0;
        let m = rho * volume;
        let i_xx = m * (0.15 * r * r + 3.0 / 80.0 * height * height);
        let com = DVec3::new(0.0, 0.0, -0.5 * h);
        Ok(diagonal(volume, rho, com, DVec3::new(i_xx, i_xx, 0.3 * m * r * r)))
    }

    /// The same solid rescaled to total `mass` (the density is whatever gives that mass).
    pub fn with_mass(self, mass: f64) -> Result<Self, MassError> {
        let mass = positive("mass", mass)?;
        let scale = mass / self.mass;
        Ok(MassProperties { mass, inertia: self.inertia * scale, ..self })
    }

    /// The same solid placed at `pose`: the centre of mass is mapped by `pose` and the inertia
    /// rotated, `I' = R I Rᵀ`.
    ///
    /// The inertia stays about the centre of mass (which moved with the solid), so no
    /// parallel-axis term appears here; `combine` adds it when parts are joined.
    pub fn transformed(&self, pose: &Transform) -> Self {
        let r = DMat3::from_quat(pose.rotation);
        MassProperties {
            volume: self.volume,
            mass: self.mass,
            center_of_mass: pose.transform_point(self.center_of_mass),
            inertia: symmetrized(r * self.inertia * r.transpose()),
        }
    }

    /// The union of non-overlapping parts, all in one frame (parallel-axis theorem).
    ///
    /// Mass and volume add, the centre of mass is the mass-weighted mean, and each part's inertia
    /// is moved from its own centre of mass to the combined one by `I + m ((d·d) 1 − d dᵀ)`.
    pub fn combine(parts: &[MassProperties]) -> Result<Self, MassError> {
        let first = parts.first().ok_or(MassError::EmptyCompound)?;
        let mass: f64 = parts.iter().map(|p| p.mass).sum();
        let volume: f64 = parts.iter().map(|p| p.volume).sum();
        positive("compound mass", mass)?;
        // Offsets from the first part's centre keep the weighted mean accurate far from the origin.
        let origin = first.center_of_mass;
        let moment: DVec3 = parts.iter().map(|p| p.mass * (p.center_of_mass - origin)).sum();
        let center_of_mass = origin + moment / mass;
        let inertia = parts.iter().fold(DMat3::ZERO, |acc, p| {
            acc + p.inertia + point_mass_inertia(p.mass, p.center_of_mass - center_of_mass)
        });
        Ok(MassProperties { volume, mass, center_of_mass, inertia })
    }

    /// Principal moments (ascending) and axes (a rotation whose columns are the axes).
    pub fn principal(&self) -> PrincipalFrame {
        let (moments, axes) = symmetric_eigen(self.inertia);
        PrincipalFrame { moments, axes }
    }
}

/// `(m + mᵀ)/2`: removes the round-off asymmetry of a product like `R I Rᵀ`.
pub(super) fn symmetrized(m: DMat3) -> DMat3 {
    (m + m.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{mat3_max_abs, DQuat};

    #[test]
    fn rejects_bad_sizes_and_density() {
        let err = MassProperties::sphere(-1.0, 1.0).unwrap_err();
        assert_eq!(err, MassError::NotPositive { what: "sphere radius", value: -1.0 });
        assert!(err.to_string().contains("sphere radius must be finite and > 0"));
        let err = MassProperties::cuboid(DVec3::new(1.0, f64::NAN, 1.0), 1.0).unwrap_err();
        assert!(matches!(err, MassError::NotPositive { what: "box half extent y", .. }));
        let err = MassProperties::cone(1.0, 1.0, 0.0).unwrap_err();
        assert!(matches!(err, MassError::NotPositive { what: "density", .. }));
        let err = MassProperties::capsule(1.0, f64::INFINITY, 1.0).unwrap_err();
        assert!(matches!(err, MassError::NotPositive { what: "capsule half_height", .. }));
        let err = MassProperties::cylinder(0.0, 1.0, 1.0).unwrap_err();
        assert!(matches!(err, MassError::NotPositive { what: "cylinder radius", .. }));
        let unit = MassProperties::sphere(1.0, 1.0).unwrap();
        assert!(matches!(unit.with_mass(-2.0), Err(MassError::NotPositive { what: "mass", .. })));
    }

    #[test]
    fn with_mass_scales_inertia() {
        let p = MassProperties::cuboid(DVec3::new(1.0, 2.0, 3.0), 2.0).unwrap();
        let q = p.with_mass(p.mass * 3.0).unwrap();
        assert_eq!(q.volume, p.volume);
        assert!(mat3_max_abs(q.inertia - p.inertia * 3.0) <= 1e-15 * mat3_max_abs(q.inertia));
    }

    #[test]
    fn capsule_with_tiny_cylinder_tends_to_sphere() {
        let c = MassProperties::capsule(0.7, 1e-9, 5.0).unwrap();
        let s = MassProperties::sphere(0.7, 5.0).unwrap();
        assert!((c.mass - s.mass).abs() < 1e-7 * s.mass);
        assert!(mat3_max_abs(c.inertia - s.inertia) < 1e-7 * mat3_max_abs(s.inertia));
    }

    #[test]
    fn transformed_rotates_about_the_center() {
        let cone = MassProperties::cone(1.0, 2.0, 3.0).unwrap();
        let pose = Transform::new(DVec3::new(1.0, 2.0, 3.0), DQuat::from_rotation_x(PI / 2.0));
        let t = cone.transformed(&pose);
        // The cone's axis Z maps to −Y; its centre (0, 0, −1) to (1, 3, 3).
        assert!((t.center_of_mass - DVec3::new(1.0, 3.0, 3.0)).length() < 1e-15);
        assert!((t.inertia.col(1).y - cone.inertia.col(2).z).abs() < 1e-14);
        assert!((t.inertia.col(2).z - cone.inertia.col(0).x).abs() < 1e-14);
    }

    #[test]
    fn combine_two_halves_is_the_whole() {
        let half = MassProperties::cuboid(DVec3::new(0.5, 1.0, 1.5), 2.0).unwrap();
        let left = half.transformed(&Transform::new(DVec3::new(-0.5, 0.0, 0.0), DQuat::IDENTITY));
        let right = half.transformed(&Transform::new(DVec3::new(0.5, 0.0, 0.0), DQuat::IDENTITY));
        let whole = MassProperties::combine(&[left, right]).unwrap();
        let expected = MassProperties::cuboid(DVec3::new(1.0, 1.0, 1.5), 2.0).unwrap();
        assert!((whole.mass - expected.mass).abs() < 1e-14 * expected.mass);
        assert!(whole.center_of_mass.length() < 1e-15);
        let err = mat3_max_abs(whole.inertia - expected.inertia);
        assert!(err < 1e-14 * mat3_max_abs(expected.inertia));
        assert_eq!(MassProperties::combine(&[]), Err(MassError::EmptyCompound));
    }
}
