//! Meshes given as vertices and triangles (convex hulls, triangle meshes), flat-shaded: every
//! triangle gets its own three vertices with the face normal, so facets and creases read as such.

use tumble::DVec3;

use super::RenderMesh;

pub fn flat_shaded(vertices: &[DVec3], triangles: &[[u32; 3]]) -> RenderMesh {
    let mut mesh = RenderMesh::default();
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        let normal = (b - a).cross(c - a);
        if normal.length_squared() == 0.0 {
            continue; // a sliver has no face to draw
        }
        let i = mesh.push_vertex(a, normal);
        mesh.push_vertex(b, normal);
        mesh.push_vertex(c, normal);
        mesh.push_triangle(i, i + 1, i + 2);
    }
    mesh
}
