//! A half-space: the infinite solid below a plane. Static bodies only (it has no finite mass).

use super::ShapeError;
use crate::math::DVec3;

/// The half-space `normal · x ≤ offset` in the shape's frame: the solid lies on the side opposite
/// the normal, and its surface is the plane at signed distance `offset` from the origin along the
/// unit `normal`. `Plane::new(DVec3::Z, 0.0)` is a floor at z = 0 with the solid below.
///
/// A plane is static-only: a body with one must be static (`World::add_body` refuses anything
/// else). For the broad phase it is bounded to a box [`PLANE_EXTENT`] metres from the origin.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Plane {
    /// Outward unit normal (pointing out of the solid).
    pub normal: DVec3,
    /// Signed distance of the surface from the origin along `normal`, m.
    pub offset: f64,
}

/// Half size of the cube (about the world origin) to which a plane's bounding box is clipped.
pub const PLANE_EXTENT: f64 = 1.0e6;

impl Plane {
    /// A half-space with outward normal `normal` (normalised here; any finite non-zero length)
    /// whose surface lies `offset` metres from the origin along the unit normal.
    pub fn new(normal: DVec3, offset: f64) -> Result<Plane, ShapeError> {
        let bad = || ShapeError::BadPlaneNormal { x: normal.x, y: normal.y, z: normal.z };
        if !normal.is_finite() {
            return Err(bad());
        }
        let unit = normal.try_normalize().ok_or_else(bad)?;
        if !offset.is_finite() {
            return Err(ShapeError::BadPlaneOffset(offset));
        }
        Ok(Plane { normal: unit, offset })
    }

    /// Signed distance of a local point above the surface (negative inside the solid).
    #[inline]
    pub fn signed_distance(&self, p_local: DVec3) -> f64 {
        self.normal.dot(p_local) - self.offset
    }
}
