//! Supporting features: the vertex, edge or face of a core that faces a given direction.
//!
//! GJK and EPA give one pair of closest (or deepest) points. A box standing on a cylinder's cap
//! needs more than one point to stand still, so after GJK/EPA the narrow phase asks each shape for
//! the whole feature facing the contact normal — a face polygon, an edge, or a vertex — and clips
//! the two features against each other, exactly as the separating-axis path does for polyhedra.
//! A feature counts as a face (or an edge) when it is within a small angle of facing the normal;
//! the clipped points then carry their own exact separations, so the tolerance only decides how
//! many points are produced, not where they are.

use super::polytope::Polytope;
use super::support::Core;
use smallvec::{smallvec, SmallVec};

use crate::math::DVec3;

/// A feature's points: on the stack up to 16 (a cylinder cap has 12, a box face 4), so finding
/// a feature allocates nothing in the usual cases.
pub type FeaturePoints = SmallVec<[DVec3; 16]>;

/// Faces count as facing `dir` when their normal is within ~2.6° of it.
pub const FACE_COS_TOLERANCE: f64 = 0.999;
/// Edges count as perpendicular to `dir` when within ~2.3° of it.
pub const EDGE_SIN_TOLERANCE: f64 = 0.04;
/// Sides of the polygon that stands in for a cylinder or cone cap.
const CAP_SIDES: usize = 12;

/// A vertex (1 point), edge (2 points) or face (≥ 3 points, counter-clockwise seen from outside)
/// of a core, in the core's local frame. `code` names it: kind in the top two bits (0 vertex,
/// 1 edge, 2 face), index below.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Feature {
    pub points: FeaturePoints,
    pub code: u16,
}

pub(crate) const VERTEX: u16 = 0;
pub(crate) const EDGE: u16 = 1 << 14;
pub(crate) const FACE: u16 = 2 << 14;

impl Feature {
    fn new(points: FeaturePoints, kind: u16, index: usize) -> Feature {
        Feature { points, code: kind | (index as u16 & 0x3FFF) }
    }

    pub fn is_face(&self) -> bool {
        self.points.len() >= 3
    }

    pub fn is_edge(&self) -> bool {
        self.points.len() == 2
    }
}

/// The feature of `core` facing `dir_local` (any length, non-zero).
pub fn supporting_feature(core: &Core, dir_local: DVec3) -> Feature {
    let d = dir_local.normalize_or_zero();
    match *core {
        Core::Point => Feature::new(smallvec![DVec3::ZERO], VERTEX, 0),
        Core::Segment { half_height } => {
            let (lo, hi) = (DVec3::new(0.0, 0.0, -half_height), DVec3::new(0.0, 0.0, half_height));
            if d.z.abs() <= EDGE_SIN_TOLERANCE {
                Feature::new(smallvec![lo, hi], EDGE, 0)
            } else if d.z > 0.0 {
                Feature::new(smallvec![hi], VERTEX, 1)
            } else {
                Feature::new(smallvec![lo], VERTEX, 0)
            }
        }
        Core::Cuboid { half_extents } => polytope_feature(&Polytope::Cuboid { half_extents }, d),
        Core::Hull(h) => polytope_feature(&Polytope::Hull(h), d),
        Core::Triangle(v) => super::triangle::triangle_feature(&v, d),
        Core::Cylinder { radius, half_height } => {
            if d.z.abs() >= FACE_COS_TOLERANCE {
                Feature::new(cap(radius, half_height, d.z > 0.0), FACE, usize::from(d.z > 0.0))
            } else if d.z.abs() <= EDGE_SIN_TOLERANCE {
                let u = DVec3::new(d.x, d.y, 0.0).normalize() * radius;
                Feature::new(smallvec![u - DVec3::Z * half_height, u + DVec3::Z * half_height], EDGE, 0)
            } else {
                Feature::new(smallvec![core.support_local(d)], VERTEX, 0)
            }
        }
        Core::Cone { radius, half_height } => {
            let horizontal = DVec3::new(d.x, d.y, 0.0);
            // Outward normal of the slanted side in the (radial, z) plane: (2h, r) normalised.
            let slant = DVec3::new(2.0 * half_height, 0.0, radius).normalize();
            let radial = horizontal.length();
            let slant_cos = slant.x * radial + slant.z * d.z;
            if -d.z >= FACE_COS_TOLERANCE {
                Feature::new(cap(radius, half_height, false), FACE, 0)
            } else if slant_cos >= 1.0 - 0.5 * EDGE_SIN_TOLERANCE * EDGE_SIN_TOLERANCE && radial > 0.0 {
                let rim = horizontal / radial * radius - DVec3::Z * half_height;
                Feature::new(smallvec![DVec3::Z * half_height, rim], EDGE, 0)
            } else {
                Feature::new(smallvec![core.support_local(d)], VERTEX, 0)
            }
        }
    }
}

/// How far (m) a cap polygon's corners may sit above the core's true support point before that
/// point joins the contact as well.
pub(crate) const CAP_MISS: f64 = 1e-6;

/// Whether `feature` (of `core`) is a polygon standing in for a round cap — a cylinder's or a
/// cone's. Its corners are points of the shape, so their separations are never too deep, but they
/// can be too shallow: the polygon's edges cut inside the circle, so a tipped cap's lowest corner
/// sits above the rim's true lowest point, by up to `r·sin(tilt)·(1 − cos 15°)` (1.6 mm for a 2.2 m
/// disc tipped 1.2°, still within [`FACE_COS_TOLERANCE`] of flat). Contacts built from such a
/// feature check the core's own support point and add it when it is lower (see [`CAP_MISS`]).
pub(crate) fn is_round_cap(core: &Core, feature: &Feature) -> bool {
    feature.is_face() && matches!(core, Core::Cylinder { .. } | Core::Cone { .. })
}

/// A regular polygon inscribed in a cap circle, wound counter-clockwise seen from outside. Its
/// corners are fixed in the shape's frame, so their ids stay put as the shape moves.
fn cap(radius: f64, half_height: f64, top: bool) -> FeaturePoints {
    let z = if top { half_height } else { -half_height };
    let mut pts: FeaturePoints = (0..CAP_SIDES)
        .map(|k| {
            let a = k as f64 / CAP_SIDES as f64 * std::f64::consts::TAU;
            DVec3::new(radius * a.cos(), radius * a.sin(), z)
        })
        .collect();
    if !top {
        pts.reverse();
    }
    pts
}

/// Face, edge or vertex of a polyhedron facing `d` (unit).
fn polytope_feature(p: &Polytope, d: DVec3) -> Feature {
    let f = p.best_face(d);
    if p.face_normal(f).dot(d) >= FACE_COS_TOLERANCE {
        let pts = p.face_vertices(f).iter().map(|&v| p.vertex(v as usize)).collect();
        return Feature::new(pts, FACE, f);
    }
    let i = p.support_index(d);
    let vi = p.vertex(i);
    let mut best: Option<(usize, DVec3, f64)> = None;
    for (e, edge) in p.edges().iter().enumerate() {
        let other = if edge.vertices[0] as usize == i {
            edge.vertices[1]
        } else if edge.vertices[1] as usize == i {
            edge.vertices[0]
        } else {
            continue;
        };
        let vo = p.vertex(other as usize);
        let sine = (vo - vi).normalize().dot(d).abs();
        let better = match best {
            Some(b) => sine < b.2,
            None => true,
        };
        if sine <= EDGE_SIN_TOLERANCE && better {
            best = Some((e, vo, sine));
        }
    }
    match best {
        Some((e, vo, _)) => Feature::new(smallvec![vi, vo], EDGE, e),
        None => Feature::new(smallvec![vi], VERTEX, i),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn features_by_direction() {
        let cyl = Core::Cylinder { radius: 1.0, half_height: 2.0 };
        let top = supporting_feature(&cyl, DVec3::new(0.01, 0.0, 1.0));
        assert!(top.is_face() && top.points.iter().all(|p| p.z == 2.0));
        let n = (top.points[1] - top.points[0]).cross(top.points[2] - top.points[1]);
        assert!(n.z > 0.0, "cap wound counter-clockwise from outside");
        let bottom = supporting_feature(&cyl, -DVec3::Z);
        let n = (bottom.points[1] - bottom.points[0]).cross(bottom.points[2] - bottom.points[1]);
        assert!(n.z < 0.0);
        assert!(supporting_feature(&cyl, DVec3::X).is_edge());
        assert_eq!(supporting_feature(&cyl, DVec3::new(1.0, 0.0, 1.0)).points.len(), 1);
        let boxc = Core::Cuboid { half_extents: DVec3::ONE };
        assert!(supporting_feature(&boxc, DVec3::new(1.0, 1.0, 0.01)).is_edge());
        assert!(supporting_feature(&boxc, DVec3::new(0.0, 0.01, 1.0)).is_face());
        let cone = Core::Cone { radius: 1.0, half_height: 1.0 };
        assert!(supporting_feature(&cone, DVec3::new(2.0, 0.0, 1.0)).is_edge());
    }
}
