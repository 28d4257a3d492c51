//! Shapes as triangles, for drawing: every shape a body can have becomes a [`RenderMesh`] in the
//! body's frame (f32 positions and normals, counter-clockwise outward triangles). The viewer page
//! and the glTF export both draw from these.
//!
//! One file per way of making triangles: [`lathe`] (surfaces of revolution about Z: sphere,
//! capsule, cylinder, cone, profiles in [`round`]), [`cuboid`], [`polyhedron`] (convex hulls and
//! triangle meshes, flat-shaded), [`ground`] (planes and height fields).

mod cuboid;
pub mod ground;
mod lathe;
mod polyhedron;
mod round;

use tumble::{DVec3, Shape, Transform};

/// Segments around the axis of a round shape (sphere, capsule, cylinder, cone).
pub const ROUND_SEGMENTS: usize = 32;
/// Rings from pole to pole of a sphere (a capsule's two caps share them).
pub const SPHERE_RINGS: usize = 16;

/// A triangle mesh ready to draw: one normal per vertex, triangles wound counter-clockwise seen
/// from outside.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderMesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
}

impl RenderMesh {
    /// Adds a vertex and returns its index.
    pub fn push_vertex(&mut self, position: DVec3, normal: DVec3) -> u32 {
        let index = self.positions.len() as u32;
        self.positions.push(position.as_vec3().to_array());
        self.normals.push(normal.normalize_or_zero().as_vec3().to_array());
        index
    }

    pub fn push_triangle(&mut self, a: u32, b: u32, c: u32) {
        self.indices.extend_from_slice(&[a, b, c]);
    }

    /// Appends `other` placed at `pose` (a compound's part in the compound's frame).
    pub fn append(&mut self, other: &RenderMesh, pose: &Transform) {
        let base = self.positions.len() as u32;
        for (p, n) in other.positions.iter().zip(&other.normals) {
            let p = pose.transform_point(DVec3::from(p.map(f64::from)));
            let n = pose.transform_vector(DVec3::from(n.map(f64::from)));
            self.push_vertex(p, n);
        }
        self.indices.extend(other.indices.iter().map(|i| i + base));
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Smallest and largest coordinates of the vertices (zeros for an empty mesh).
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        if self.positions.is_empty() {
            return ([0.0; 3], [0.0; 3]);
        }
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &self.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }
}

/// Half the side of the square a plane is drawn as, m.
const PLANE_HALF_SIZE: f64 = 50.0;

/// The triangles of `shape` in its own frame.
pub fn shape_mesh(shape: &Shape) -> RenderMesh {
    match shape {
        Shape::Sphere(s) => lathe::lathe(&round::sphere_profile(s.radius, SPHERE_RINGS), ROUND_SEGMENTS),
        Shape::Capsule(c) => {
            lathe::lathe(&round::capsule_profile(c.radius, c.half_height, SPHERE_RINGS / 2), ROUND_SEGMENTS)
        }
        Shape::Cylinder(c) => lathe::lathe(&round::cylinder_profile(c.radius, c.half_height), ROUND_SEGMENTS),
        Shape::Cone(c) => lathe::lathe(&round::cone_profile(c.radius, c.half_height), ROUND_SEGMENTS),
        Shape::Cuboid(b) => cuboid::cuboid(b.half_extents),
        Shape::ConvexHull(h) => polyhedron::flat_shaded(h.vertices(), &h.triangles()),
        Shape::TriMesh(m) => polyhedron::flat_shaded(m.vertices(), m.triangles()),
        // A plane is unbounded: it is drawn as a square large enough for everyday scenes.
        Shape::Plane(p) => ground::plane(p.normal, p.offset, PLANE_HALF_SIZE),
        Shape::HeightField(h) => ground::height_grid(h.heights(), h.rows(), h.cols(), h.scale()),
        Shape::Compound(c) => {
            let mut mesh = RenderMesh::default();
            for child in c.children() {
                mesh.append(&shape_mesh(&child.shape), &child.pose);
            }
            mesh
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tumble::{Capsule, Cone, Cuboid, Cylinder, Sphere};

    /// Signed volume by the divergence theorem: positive when every triangle faces outward.
    fn volume(mesh: &RenderMesh) -> f64 {
        let p = |i: u32| DVec3::from(mesh.positions[i as usize].map(f64::from));
        mesh.indices.chunks(3).map(|t| p(t[0]).dot(p(t[1]).cross(p(t[2]))) / 6.0).sum()
    }

    /// Every triangle's winding agrees with its vertices' normals (outward, counter-clockwise).
    fn assert_wound_outward(mesh: &RenderMesh) {
        let p = |i: u32| DVec3::from(mesh.positions[i as usize].map(f64::from));
        for t in mesh.indices.chunks(3) {
            let face = (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
            assert!(face.length() > 1e-12, "degenerate triangle {t:?}");
            let n: DVec3 = t.iter().map(|&i| DVec3::from(mesh.normals[i as usize].map(f64::from))).sum();
            assert!(face.dot(n) > 0.0, "triangle {t:?} faces against its normals");
        }
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn primitives_enclose_about_their_volume() {
        let pi = std::f64::consts::PI;
        let cases: Vec<(Shape, f64)> = vec![
            (Shape::Sphere(Sphere::new(0.5).unwrap()), 4.0 / 3.0 * pi * 0.125),
            (Shape::Cuboid(Cuboid::new(DVec3::new(0.5, 1.0, 1.5)).unwrap()), 6.0),
            (Shape::Cylinder(Cylinder::new(0.3, 0.6).unwrap()), pi * 0.09 * 1.2),
            (Shape::Cone(Cone::new(0.4, 0.5).unwrap()), pi * 0.16 * 1.0 / 3.0),
            (Shape::Capsule(Capsule::new(0.2, 0.5).unwrap()), pi * 0.04 * 1.0 + 4.0 / 3.0 * pi * 0.008),
        ];
        for (shape, exact) in cases {
            let mesh = shape_mesh(&shape);
            assert_wound_outward(&mesh);
            // 32 segments inscribe the circle: about 0.6 % less area.
            assert!(close(volume(&mesh), exact, 0.03), "{}: {} vs {exact}", shape.kind_name(), volume(&mesh));
        }
    }

    #[test]
    fn cone_apex_is_up_and_bounds_match() {
        let mesh = shape_mesh(&Shape::Cone(Cone::new(0.4, 0.5).unwrap()));
        let (lo, hi) = mesh.bounds();
        assert!((lo[2] + 0.5).abs() < 1e-6 && (hi[2] - 0.5).abs() < 1e-6);
        assert!((hi[0] - 0.4).abs() < 1e-6);
    }

    #[test]
    fn compound_parts_are_placed() {
        use tumble::{Compound, CompoundChild, DQuat};
        let part = |x: f64| CompoundChild {
            pose: Transform::new(DVec3::new(x, 0.0, 0.0), DQuat::IDENTITY),
            shape: Shape::Cuboid(Cuboid::new(DVec3::splat(0.5)).unwrap()),
        };
        let mesh = shape_mesh(&Shape::Compound(Compound::new(vec![part(-2.0), part(2.0)]).unwrap()));
        assert_eq!(mesh.triangle_count(), 24);
        let (lo, hi) = mesh.bounds();
        assert_eq!((lo[0], hi[0]), (-2.5, 2.5));
        assert!(close(volume(&mesh), 2.0, 1e-9));
    }
}
