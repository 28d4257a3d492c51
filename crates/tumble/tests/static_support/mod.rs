//! Floors made of triangles for the static-geometry tests and benches.
#![allow(dead_code)]

use tumble::{DVec3, HeightField, Shape, TriMesh};

/// A flat, open grid of `n × n` square cells of side `cell` on z = `z`, centred on the origin,
/// each cell split into two triangles facing +Z: `2·n²` triangles.
pub fn grid_floor(n: usize, cell: f64, z: f64) -> TriMesh {
    let (vertices, triangles) = grid(n, cell, |_, _| z);
    TriMesh::new_static(vertices, triangles).expect("a valid grid")
}

/// Vertices and triangles of an `n × n` grid with heights from `height(x, y)`. Cells alternate
/// their diagonal, so both diagonal directions are exercised.
pub fn grid(n: usize, cell: f64, height: impl Fn(f64, f64) -> f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let half = 0.5 * n as f64 * cell;
    let mut vertices = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 * cell - half, j as f64 * cell - half);
            vertices.push(DVec3::new(x, y, height(x, y)));
        }
    }
    let idx = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            if (i + j) % 2 == 0 {
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            } else {
                triangles.push([a, b, d]);
                triangles.push([b, c, d]);
            }
        }
    }
    (vertices, triangles)
}

/// A flat height field of `n × n` samples spaced `cell` apart at height `z`.
pub fn flat_heightfield(n: usize, cell: f64, z: f64) -> HeightField {
    HeightField::new(vec![z; n * n], n, n, DVec3::new(cell, cell, 1.0)).expect("valid height field")
}

/// Shape wrapper.
pub fn mesh_shape(m: TriMesh) -> Shape {
    Shape::TriMesh(m)
}
