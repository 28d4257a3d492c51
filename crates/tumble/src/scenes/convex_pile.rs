//! `convex_pile`: random convex hulls (10 points each, about 0.25–0.45 m across each axis)
//! dropped in layers of 10 × 10 onto a static triangle-mesh terrain (a 40 × 40 m grid of 1 m
//! cells, gently rolling); 600 steps. Quality: the largest overlap among the touching contacts at
//! the end, and that largest overlap averaged over every step of the run (the end alone is one
//! sample of a pile still landing: in the first 120 steps it ranged 2-10 cm from one step to the
//! next).

use super::quality::{max_penetration, Metric, Quality};
use super::rng::SplitMix64;
use super::{world, Probe, Scene, G};
use crate::body::{BodyDef, BodyKind};
use crate::math::{DQuat, DVec3};
use crate::shape::{ConvexHull, Shape, TriMesh};
use crate::world::World;

/// Cells along each side of the terrain (1 m each, centred on the origin).
pub const TERRAIN_CELLS: usize = 40;
/// Hulls per row and rows per layer.
pub const PER_ROW: usize = 10;
/// Spacing of the hulls horizontally and between layers, m.
pub const SPACING: f64 = 1.5;
/// Height of the lowest layer, m.
pub const FIRST_LAYER: f64 = 2.5;
/// Seed of the hull shapes and orientations.
pub const SEED: u64 = 7;

/// The terrain's height at (x, y), m.
pub fn terrain_height(x: f64, y: f64) -> f64 {
    0.5 * (0.3 * x).sin() * (0.25 * y).cos()
}

/// The terrain: vertices row by row (y outer), two triangles per cell.
pub fn terrain() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let n = TERRAIN_CELLS;
    let half = 0.5 * n as f64;
    let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 - half, j as f64 - half);
            vertices.push(DVec3::new(x, y, terrain_height(x, y)));
        }
    }
    let idx = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    (vertices, triangles)
}

/// Hull `k`'s points (in its own frame), position and orientation.
pub fn hulls(count: usize) -> Vec<(Vec<DVec3>, DVec3, DQuat)> {
    let mut rng = SplitMix64::new(SEED);
    let per_layer = PER_ROW * PER_ROW;
    let offset = 0.5 * (PER_ROW as f64 - 1.0) * SPACING;
    (0..count)
        .map(|k| {
            let radii = DVec3::new(rng.range(0.25, 0.45), rng.range(0.25, 0.45), rng.range(0.25, 0.45));
            let points = (0..10)
                .map(|_| {
                    // A point on the unit sphere (by its height and azimuth), stretched to the radii.
                    let z: f64 = rng.range(-1.0, 1.0);
                    let phi = rng.range(0.0, std::f64::consts::TAU);
                    let r = (1.0 - z * z).sqrt();
                    DVec3::new(r * phi.cos(), r * phi.sin(), z) * radii
                })
                .collect();
            let yaw = rng.range(0.0, std::f64::consts::TAU);
            let (layer, rest) = (k / per_layer, k % per_layer);
            let (j, i) = (rest / PER_ROW, rest % PER_ROW);
            let position = DVec3::new(
                i as f64 * SPACING - offset,
                j as f64 * SPACING - offset,
                FIRST_LAYER + layer as f64 * SPACING,
            );
            (points, position, DQuat::from_rotation_z(yaw))
        })
        .collect()
}

/// `count` hulls (1,000 by default) onto the terrain.
pub fn convex_pile(count: usize) -> Scene {
    let mut w = world(G, false);
    let (vertices, triangles) = terrain();
    w.add_body(BodyDef {
        name: "terrain".into(),
        kind: BodyKind::Static,
        shape: Some(Shape::TriMesh(TriMesh::new_static(vertices, triangles).expect("a valid grid"))),
        ..Default::default()
    })
    .expect("a static mesh is a valid body");
    for (points, position, orientation) in hulls(count) {
        let hull = ConvexHull::new(&points).expect("ten points spread over an ellipsoid span a volume");
        w.add_body(BodyDef {
            shape: Some(Shape::ConvexHull(hull)),
            position,
            orientation,
            ..Default::default()
        })
        .expect("a hull is a valid body");
    }
    Scene::new("convex_pile", count, w, 600, Penetration::default())
}

/// The largest overlap of each step, summed over the steps observed.
#[derive(Default)]
struct Penetration {
    sum: f64,
    steps: u32,
}

impl Probe for Penetration {
    fn observe(&mut self, world: &World) {
        self.sum += max_penetration(world);
        self.steps += 1;
    }

    fn quality(&self, world: &World) -> Quality {
        let now = max_penetration(world);
        let mean = if self.steps == 0 { now } else { self.sum / f64::from(self.steps) };
        Quality {
            metrics: vec![
                Metric::Length("max penetration", now),
                Metric::Length("mean max penetration", mean),
            ],
        }
    }
}
