//! A borrowed view of a convex polyhedron — a box or a hull — with the topology the separating-axis
//! test walks (faces with planes, edges with their two faces).
//!
//! Boxes reuse one shared unit-cube hull (half extents 1) whose vertices are scaled on the fly:
//! scaling a box along its own axes leaves its face normals and topology unchanged, so no box ever
//! allocates a hull of its own.

use std::sync::OnceLock;

use super::support::Core;
use crate::math::DVec3;
use crate::shape::{ConvexHull, HullEdge};

/// A box or a convex hull, in its local frame.
#[derive(Clone, Copy, Debug)]
pub enum Polytope<'a> {
    Cuboid { half_extents: DVec3 },
    Hull(&'a ConvexHull),
}

/// The hull of (±1, ±1, ±1): the topology every box shares.
pub fn unit_cube() -> &'static ConvexHull {
    static CUBE: OnceLock<ConvexHull> = OnceLock::new();
    CUBE.get_or_init(|| {
        let corners: Vec<DVec3> = (0..8)
            .map(|i| {
                DVec3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 },
                    if i & 2 == 0 { -1.0 } else { 1.0 },
                    if i & 4 == 0 { -1.0 } else { 1.0 },
                )
            })
            .collect();
        ConvexHull::new(&corners).expect("the unit cube has a hull")
    })
}

impl Polytope<'_> {
    #[inline]
    fn hull(&self) -> &ConvexHull {
        match self {
            Polytope::Cuboid { .. } => unit_cube(),
            Polytope::Hull(h) => h,
        }
    }

    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.hull().vertices().len()
    }

    #[inline]
    pub fn vertex(&self, i: usize) -> DVec3 {
        match self {
            Polytope::Cuboid { half_extents } => unit_cube().vertices()[i] * *half_extents,
            Polytope::Hull(h) => h.vertices()[i],
        }
    }

    #[inline]
    pub fn face_count(&self) -> usize {
        self.hull().faces().len()
    }

    /// Outward unit normal of face `f`.
    #[inline]
    pub fn face_normal(&self, f: usize) -> DVec3 {
        self.hull().faces()[f].normal
    }

    /// Plane offset of face `f`: `normal · x = offset` on the face.
    #[inline]
    pub fn face_offset(&self, f: usize) -> f64 {
        match self {
            Polytope::Cuboid { half_extents } => {
                let n = unit_cube().faces()[f].normal;
                n.abs().dot(*half_extents)
            }
            Polytope::Hull(h) => h.faces()[f].offset,
        }
    }

    /// Area of face `f`.
    pub fn face_area(&self, f: usize) -> f64 {
        let vs = self.face_vertices(f);
        let o = self.vertex(vs[0] as usize);
        let mut twice = DVec3::ZERO;
        for k in 1..vs.len() - 1 {
            twice += (self.vertex(vs[k] as usize) - o).cross(self.vertex(vs[k + 1] as usize) - o);
        }
        0.5 * twice.length()
    }

    /// Vertex loop of face `f`, counter-clockwise seen from outside.
    #[inline]
    pub fn face_vertices(&self, f: usize) -> &[u32] {
        &self.hull().faces()[f].vertices
    }

    #[inline]
    pub fn edges(&self) -> &[HullEdge] {
        self.hull().edges()
    }

    /// Index of the vertex farthest along `dir` (lowest index on ties).
    pub fn support_index(&self, dir: DVec3) -> usize {
        match self {
            Polytope::Cuboid { half_extents } => self.hull().support_index(dir * *half_extents),
            Polytope::Hull(h) => h.support_index(dir),
        }
    }

    /// The face whose normal is most aligned with `dir`.
    pub fn best_face(&self, dir: DVec3) -> usize {
        let mut best = (0, f64::NEG_INFINITY);
        for f in 0..self.face_count() {
            let d = self.face_normal(f).dot(dir);
            if d > best.1 {
                best = (f, d);
            }
        }
        best.0
    }

    /// The same shape as a support-mapped core (for GJK).
    pub fn core(&self) -> Core<'_> {
        match *self {
            Polytope::Cuboid { half_extents } => Core::Cuboid { half_extents },
            Polytope::Hull(h) => Core::Hull(h),
        }
    }

    /// A point strictly inside.
    pub fn interior_point(&self) -> DVec3 {
        match self {
            Polytope::Cuboid { .. } => DVec3::ZERO,
            Polytope::Hull(h) => h.interior_point(),
        }
    }

    /// Radius of a ball about the origin containing the polytope.
    pub fn bounding_radius(&self) -> f64 {
        match self {
            Polytope::Cuboid { half_extents } => half_extents.length(),
            Polytope::Hull(h) => h.bounding_radius(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_cube_faces_are_exact() {
        let p = Polytope::Cuboid { half_extents: DVec3::new(1.0, 2.0, 3.0) };
        assert_eq!(p.face_count(), 6);
        assert_eq!(p.edges().len(), 12);
        for f in 0..6 {
            let n = p.face_normal(f);
            assert_eq!(n.abs().max_element(), 1.0, "axis-aligned normal");
            for &v in p.face_vertices(f) {
                assert_eq!(n.dot(p.vertex(v as usize)), p.face_offset(f));
            }
        }
        // Support of a scaled box along a skew direction picks the right corner.
        let i = p.support_index(DVec3::new(0.9, -0.1, 0.05));
        assert_eq!(p.vertex(i), DVec3::new(1.0, -2.0, 3.0));
    }
}
