//! Building rows for the common cases: a point constraint along a direction, a contact point
//! (normal plus two friction rows), and a ball joint (three equality rows).
//!
//! Everything here is in the world frame. `r_a`, `r_b` are the constraint point relative to each
//! body's centre of mass; the row velocity is the relative velocity of the point on `b` with respect
//! to the point on `a`, along the direction:
//!
//! ```text
//!   J v = d · (v_b + ω_b × r_b − v_a − ω_a × r_a)
//!       = (−d)·v_a + (−r_a × d)·ω_a + d·v_b + (r_b × d)·ω_b
//! ```
//!
//! so a positive impulse pushes `b` along `d` and `a` against it.

use super::system::{Row, RowKind};
use crate::math::DVec3;

/// One body of a point row: index (or `None` for the world) and the point relative to its centre
/// of mass (ignored for the world).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Anchor {
    pub body: Option<usize>,
    pub r: DVec3,
}

impl Anchor {
    /// The fixed world: no body.
    pub const WORLD: Self = Self { body: None, r: DVec3::ZERO };

    pub fn new(body: usize, r: DVec3) -> Self {
        Self { body: Some(body), r }
    }
}

/// A row measuring the relative velocity of the anchors along `direction` (see the module
/// documentation), with bias 0.
pub fn point_row(a: Anchor, b: Anchor, direction: DVec3, kind: RowKind) -> Row {
    Row {
        body_a: a.body,
        body_b: b.body,
        jacobian: [-direction, -a.r.cross(direction), direction, b.r.cross(direction)],
        bias: 0.0,
        kind,
    }
}

/// A contact point between `a` and `b`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactPoint {
    pub a: Anchor,
    pub b: Anchor,
    /// Unit normal pointing from `a` to `b`: the normal row velocity is positive when separating.
    pub normal: DVec3,
    /// Unit tangent, perpendicular to `normal`; the second tangent is `normal × tangent`.
    pub tangent: DVec3,
    pub mu: f64,
    /// Bias of the normal row (e.g. a separation or restitution term); 0 for a plain contact.
    pub bias: f64,
}

/// The three rows of a contact point: `[normal, tangent, normal × tangent]`. `normal_row` is the
/// index the normal row will have in the final row list (the friction rows refer to it).
pub fn contact_rows(c: &ContactPoint, normal_row: usize) -> [Row; 3] {
    let friction = RowKind::Friction { normal_row, mu: c.mu };
    let mut normal = point_row(c.a, c.b, c.normal, RowKind::Normal);
    normal.bias = c.bias;
    [
        normal,
        point_row(c.a, c.b, c.tangent, friction),
        point_row(c.a, c.b, c.normal.cross(c.tangent), friction),
    ]
}

/// The three equality rows of a ball joint holding the anchors together: the relative anchor
/// velocity along world x, y and z is zero (set each row's bias for drift correction).
pub fn ball_joint_rows(a: Anchor, b: Anchor) -> [Row; 3] {
    [DVec3::X, DVec3::Y, DVec3::Z].map(|axis| point_row(a, b, axis, RowKind::Equality))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::lcp::BodyVelocity;

    #[test]
    fn point_row_is_the_relative_point_velocity() {
        let v = [
            BodyVelocity::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.1, -0.2, 0.3)),
            BodyVelocity::new(DVec3::new(-1.0, 0.5, 0.0), DVec3::new(0.4, 0.0, -0.1)),
        ];
        let (ra, rb) = (DVec3::new(0.2, 0.0, -0.5), DVec3::new(-0.3, 0.1, 0.4));
        let d = DVec3::new(1.0, 2.0, 2.0) / 3.0;
        let row = point_row(Anchor::new(0, ra), Anchor::new(1, rb), d, RowKind::Normal);
        let rel = (v[1].linear + v[1].angular.cross(rb)) - (v[0].linear + v[0].angular.cross(ra));
        assert!((row.velocity(&v) - rel.dot(d)).abs() < 1e-15);
    }

    #[test]
    fn contact_rows_refer_to_their_normal() {
        let c = ContactPoint {
            a: Anchor::WORLD,
            b: Anchor::new(0, DVec3::new(0.5, 0.5, -0.5)),
            normal: DVec3::Z,
            tangent: DVec3::X,
            mu: 0.3,
            bias: 0.0,
        };
        let rows = contact_rows(&c, 7);
        assert_eq!(rows[0].kind, RowKind::Normal);
        assert_eq!(rows[1].kind, RowKind::Friction { normal_row: 7, mu: 0.3 });
        assert_eq!(rows[2].jacobian[2], DVec3::Y);
    }
}
