//! A box: six faces of two triangles, each face with its own four vertices (sharp edges).

use tumble::DVec3;

use super::RenderMesh;

pub fn cuboid(half_extents: DVec3) -> RenderMesh {
    let mut mesh = RenderMesh::default();
    for axis in 0..3 {
        for sign in [-1.0, 1.0] {
            let mut normal = DVec3::ZERO;
            normal[axis] = sign;
            // Two directions in the face with u × v = normal, so (0, u, u+v, v) runs counter-clockwise.
            let mut u = DVec3::ZERO;
            u[(axis + 1) % 3] = 1.0;
            let v = normal.cross(u);
            let centre = normal * half_extents;
            let (hu, hv) = (u * half_extents, v * half_extents);
            let corners = [centre - hu - hv, centre + hu - hv, centre + hu + hv, centre - hu + hv];
            let first = mesh.positions.len() as u32;
            for c in corners {
                mesh.push_vertex(c, normal);
            }
            mesh.push_triangle(first, first + 1, first + 2);
            mesh.push_triangle(first, first + 2, first + 3);
        }
    }
    mesh
}
