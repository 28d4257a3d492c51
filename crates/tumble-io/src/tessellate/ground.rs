//! Ground shapes: a plane (drawn as a large square) and a height field (a grid of heights). The
//! core's static shapes map onto these; they take plain numbers so they do not depend on how the
//! shapes store them.

use tumble::DVec3;

use super::RenderMesh;

/// The surface `normal · x = offset` drawn as a square of half size `half_size` centred on the
/// point of the plane nearest the origin, facing along `normal` (unit).
pub fn plane(normal: DVec3, offset: f64, half_size: f64) -> RenderMesh {
    let normal = normal.normalize();
    let (u, v) = normal.any_orthonormal_pair();
    let centre = normal * offset;
    let mut mesh = RenderMesh::default();
    let corners = [
        centre - u * half_size - v * half_size,
        centre + u * half_size - v * half_size,
        centre + u * half_size + v * half_size,
        centre - u * half_size + v * half_size,
    ];
    for c in corners {
        mesh.push_vertex(c, normal);
    }
    // any_orthonormal_pair gives u × v = normal, so this runs counter-clockwise seen from above.
    mesh.push_triangle(0, 1, 2);
    mesh.push_triangle(0, 2, 3);
    mesh
}

/// A height field of `rows × cols` samples (`heights[row * cols + col]`, times `scale.z`),
/// columns along X spaced `scale.x`, rows along Y spaced `scale.y`, centred on the origin in X
/// and Y; each cell split along its diagonal from (row, col) to (row + 1, col + 1). Smooth normals
/// from central differences.
pub fn height_grid(heights: &[f64], rows: usize, cols: usize, scale: DVec3) -> RenderMesh {
    let mut mesh = RenderMesh::default();
    if rows < 2 || cols < 2 || heights.len() != rows * cols {
        return mesh;
    }
    let x0 = -0.5 * (cols - 1) as f64 * scale.x;
    let y0 = -0.5 * (rows - 1) as f64 * scale.y;
    let h = |r: usize, c: usize| heights[r * cols + c] * scale.z;
    for r in 0..rows {
        for c in 0..cols {
            let dzdx = (h(r, (c + 1).min(cols - 1)) - h(r, c.saturating_sub(1)))
                / (((c + 1).min(cols - 1) - c.saturating_sub(1)) as f64 * scale.x);
            let dzdy = (h((r + 1).min(rows - 1), c) - h(r.saturating_sub(1), c))
                / (((r + 1).min(rows - 1) - r.saturating_sub(1)) as f64 * scale.y);
            let p = DVec3::new(x0 + c as f64 * scale.x, y0 + r as f64 * scale.y, h(r, c));
            mesh.push_vertex(p, DVec3::new(-dzdx, -dzdy, 1.0));
        }
    }
    for r in 0..rows - 1 {
        for c in 0..cols - 1 {
            let i = |r: usize, c: usize| (r * cols + c) as u32;
            mesh.push_triangle(i(r, c), i(r, c + 1), i(r + 1, c + 1));
            mesh.push_triangle(i(r, c), i(r + 1, c + 1), i(r + 1, c));
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_faces_its_normal() {
        let mesh = plane(DVec3::Z, 1.0, 10.0);
        let p = |i: usize| DVec3::from(mesh.positions[i].map(f64::from));
        let face = (p(1) - p(0)).cross(p(2) - p(0));
        assert!(face.z > 0.0 && p(0).z == 1.0);
    }

    #[test]
    fn flat_height_grid_faces_up() {
        let mesh = height_grid(&[0.0; 12], 3, 4, DVec3::new(1.0, 2.0, 1.0));
        assert_eq!(mesh.triangle_count(), 2 * 2 * 3);
        let p = |i: u32| DVec3::from(mesh.positions[i as usize].map(f64::from));
        for t in mesh.indices.chunks(3) {
            assert!((p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0])).z > 0.0);
        }
        assert_eq!(mesh.bounds(), ([-1.5, -2.0, 0.0], [1.5, 2.0, 0.0]));
    }
}
