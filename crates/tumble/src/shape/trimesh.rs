//! A triangle mesh, closed (a solid with mass) or open (static collision geometry).
//!
//! - [`TriMesh::new`] checks a closed mesh (finite, closed, consistently wound, outward,
//!   non-degenerate), so it has well-defined mass properties. A *dynamic* body with a closed mesh
//!   collides through the **convex hull of its vertices** (built once here); static and kinematic
//!   bodies collide with its triangles.
//! - [`TriMesh::new_static`] accepts any surface (a floor, terrain, a room): finite, indices in
//!   range, no degenerate triangles; it need not be closed. It has no mass properties, so only a
//!   static body can use it.
//!
//! Both build the collision data once: a static BVH over the triangles, the triangle normals
//! (from the counter-clockwise winding: a triangle's front is the side it winds
//! counter-clockwise around), and each triangle edge's neighbour across it, which the narrow phase
//! uses to ignore internal edges (see `collision::mesh_contact`). Collision against triangles is
//! one-sided: a body whose centre is behind a triangle's plane does not collide with it.

use std::sync::Arc;

use super::{ConvexHull, Shape};
use crate::collision::aabb::Aabb;
use crate::collision::mesh_bvh::MeshBvh;
use crate::collision::triangle::{ray_triangle, TriangleEdges};
use crate::mass::{validate_closed_mesh, validate_mesh_surface, MassError};
use crate::math::DVec3;

/// Marks an edge with no neighbour (a boundary, or an edge shared by more than two triangles or by
/// two inconsistently wound ones).
pub const NO_NEIGHBOR: u32 = u32::MAX;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TriMesh {
    vertices: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    closed: bool,
    /// Derived collision data, shared between clones.
    data: Arc<MeshData>,
}

#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
struct MeshData {
    bvh: MeshBvh,
    normals: Vec<DVec3>,
    /// `neighbors[t][k]`: the triangle across edge `k` (from vertex `k` to vertex `k + 1`) of `t`.
    neighbors: Vec<[u32; 3]>,
    /// `Shape::ConvexHull` of the vertices, for closed meshes on dynamic bodies.
    hull: Option<Shape>,
    /// Each triangle's edges as the internal-edge rule sees them (they depend on the mesh
    /// alone: worked out once here, not for every shape that touches the triangle).
    edges: Vec<TriangleEdges>,
}

impl TriMesh {
    /// A closed, outward-wound mesh; anything else is an error naming the problem.
    pub fn new(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MassError> {
        validate_closed_mesh(&vertices, &triangles)?;
        Ok(Self::build(vertices, triangles, true))
    }

    /// A static collision mesh, possibly open (a floor, terrain). Checks that it is not empty,
    /// that indices are in range, vertices finite and triangles not degenerate. Triangles face the
    /// side they wind counter-clockwise around; bodies collide with that side.
    pub fn new_static(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MassError> {
        validate_mesh_surface(&vertices, &triangles)?;
        Ok(Self::build(vertices, triangles, false))
    }

    fn build(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>, closed: bool) -> Self {
        let points = |t: &[u32; 3]| t.map(|i| vertices[i as usize]);
        let boxes: Vec<Aabb> = triangles.iter().map(|t| Aabb::from_points(points(t))).collect();
        let normals = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = points(t);
                (b - a).cross(c - a).normalize_or_zero()
            })
            .collect();
        let hull = if closed { ConvexHull::new(&vertices).ok().map(Shape::ConvexHull) } else { None };
        let data = MeshData {
            bvh: MeshBvh::build(&boxes),
            normals,
            neighbors: adjacency(&triangles),
            hull,
            edges: Vec::new(),
        };
        let mut mesh = Self { vertices, triangles, closed, data: Arc::new(data) };
        let edges = (0..mesh.triangles.len() as u32)
            .map(|t| TriangleEdges::of(&mesh, t, &mesh.triangle_points(t), mesh.normal(t)))
            .collect();
        if let Some(data) = Arc::get_mut(&mut mesh.data) {
            data.edges = edges;
        }
        mesh
    }

    /// Triangle `t`'s edges as the internal-edge rule sees them (kept from the build).
    #[inline]
    pub fn triangle_edges(&self, t: u32) -> TriangleEdges {
        self.data.edges[t as usize]
    }

    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// True for a mesh built by [`TriMesh::new`] (closed, with mass properties).
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The three corners of triangle `t`, local frame.
    #[inline]
    pub fn triangle_points(&self, t: u32) -> [DVec3; 3] {
        self.triangles[t as usize].map(|i| self.vertices[i as usize])
    }

    /// Unit normal of triangle `t` (its front side), local frame.
    #[inline]
    pub fn normal(&self, t: u32) -> DVec3 {
        self.data.normals[t as usize]
    }

    /// The triangle across edge `k` (vertex `k` to vertex `k + 1`) of triangle `t`, if any.
    #[inline]
    pub fn neighbor(&self, t: u32, k: usize) -> Option<u32> {
        let n = self.data.neighbors[t as usize][k];
        (n != NO_NEIGHBOR).then_some(n)
    }

    /// The static BVH over the triangles (local frame).
    pub fn bvh(&self) -> &MeshBvh {
        &self.data.bvh
    }

    /// The convex hull of a closed mesh's vertices (what a dynamic body with this mesh collides
    /// as); `None` for a static mesh.
    pub fn convex_hull(&self) -> Option<&ConvexHull> {
        match &self.data.hull {
            Some(Shape::ConvexHull(h)) => Some(h),
            _ => None,
        }
    }

    /// The hull as a `Shape::ConvexHull`, for the narrow phase.
    pub fn hull_shape(&self) -> Option<&Shape> {
        self.data.hull.as_ref()
    }

    /// First crossing of a ray (local frame, unit direction) with any triangle, either side:
    /// distance, the triangle's normal and its index.
    pub fn ray_cast_local(&self, origin: DVec3, direction: DVec3, max_t: f64) -> Option<(f64, DVec3, u32)> {
        let (t, d) = self.data.bvh.ray_cast(origin, direction, max_t, |t, t_max| {
            ray_triangle(origin, direction, self.triangle_points(t), t_max)
        })?;
        Some((d, self.normal(t), t))
    }

    /// The same mesh with every vertex moved by `-offset` (used to put the centre of mass at the
    /// origin, so the body frame is the principal-centred frame of the mesh).
    pub fn translated(&self, offset: DVec3) -> TriMesh {
        let vertices = self.vertices.iter().map(|&v| v - offset).collect();
        Self::build(vertices, self.triangles.clone(), self.closed)
    }
}

/// Each triangle edge's neighbour: the other triangle of an edge used by exactly two triangles in
/// opposite directions, else [`NO_NEIGHBOR`]. Sorting (not hashing) keeps it deterministic.
fn adjacency(triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let mut edges: Vec<(u32, u32, u32, u8)> = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b), t as u32, k as u8));
        }
    }
    edges.sort_unstable();
    let mut out = vec![[NO_NEIGHBOR; 3]; triangles.len()];
    for run in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        if let [(_, _, t0, k0), (_, _, t1, k1)] = *run {
            let dir = |t: u32, k: u8| triangles[t as usize][k as usize];
            // Consistent winding: the two triangles walk the edge in opposite directions.
            if dir(t0, k0) != dir(t1, k1) {
                out[t0 as usize][k0 as usize] = t1;
                out[t1 as usize][k1 as usize] = t0;
            }
        }
    }
    out
}
