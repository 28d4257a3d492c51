//! f64 linear algebra used throughout Tumble: glam's `DVec3`, `DQuat`, `DMat3`, plus the few
//! helpers rigid-body dynamics needs (the cross-product matrix, poses).
//!
//! Conventions: right-handed, Z up, SI units. Quaternions at every interface are (x, y, z, w).

pub use glam::{DMat3, DQuat, DVec3};

/// The cross-product ("hat") matrix of `v`: `hat(v) * u == v.cross(u)` for every `u`.
#[inline]
pub fn hat(v: DVec3) -> DMat3 {
    DMat3::from_cols(DVec3::new(0.0, v.z, -v.y), DVec3::new(-v.z, 0.0, v.x), DVec3::new(v.y, -v.x, 0.0))
}

/// A rigid transform: first rotate, then translate. Maps a frame's local coordinates to its parent's.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Transform {
    pub translation: DVec3,
    pub rotation: DQuat,
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    pub const IDENTITY: Self = Self { translation: DVec3::ZERO, rotation: DQuat::IDENTITY };

    pub fn new(translation: DVec3, rotation: DQuat) -> Self {
        Self { translation, rotation }
    }

    /// Maps a point given in this frame to the parent frame.
    #[inline]
    pub fn transform_point(&self, p_local: DVec3) -> DVec3 {
        self.translation + self.rotation * p_local
    }

    /// Maps a direction given in this frame to the parent frame (no translation).
    #[inline]
    pub fn transform_vector(&self, v_local: DVec3) -> DVec3 {
        self.rotation * v_local
    }

    /// Maps a point given in the parent frame into this frame.
    #[inline]
    pub fn inverse_transform_point(&self, p_parent: DVec3) -> DVec3 {
        self.rotation.inverse() * (p_parent - self.translation)
    }

    /// `self * other`: first `other`, then `self`.
    #[inline]
    pub fn mul_transform(&self, other: &Transform) -> Transform {
        Transform {
            translation: self.transform_point(other.translation),
            rotation: (self.rotation * other.rotation).normalize(),
        }
    }

    pub fn inverse(&self) -> Transform {
        let rotation = self.rotation.inverse();
        Transform { translation: -(rotation * self.translation), rotation }
    }
}

/// A quaternion from the interface order (x, y, z, w).
#[inline]
pub fn quat_from_xyzw(q: [f64; 4]) -> DQuat {
    DQuat::from_xyzw(q[0], q[1], q[2], q[3])
}

/// A quaternion to the interface order (x, y, z, w).
#[inline]
pub fn quat_to_xyzw(q: DQuat) -> [f64; 4] {
    [q.x, q.y, q.z, q.w]
}

/// True when every component is finite.
#[inline]
pub fn is_finite_vec(v: DVec3) -> bool {
    v.x.is_finite() && v.y.is_finite() && v.z.is_finite()
}

/// The largest absolute entry of a matrix (a simple norm for tolerances).
pub fn mat3_max_abs(m: DMat3) -> f64 {
    m.to_cols_array().iter().fold(0.0_f64, |a, &b| a.max(b.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hat_is_cross_product() {
        let v = DVec3::new(1.0, -2.0, 3.5);
        let u = DVec3::new(-0.3, 0.7, 2.0);
        assert!((hat(v) * u - v.cross(u)).length() < 1e-15);
    }

    #[test]
    fn transform_roundtrip() {
        let t = Transform::new(DVec3::new(1.0, 2.0, 3.0), DQuat::from_rotation_z(0.7));
        let p = DVec3::new(-1.0, 0.5, 4.0);
        assert!((t.inverse_transform_point(t.transform_point(p)) - p).length() < 1e-14);
        assert!((t.inverse().transform_point(t.transform_point(p)) - p).length() < 1e-14);
    }
}
