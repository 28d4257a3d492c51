//! Surfaces of revolution about the local Z axis: a profile in the (r, z) half-plane swept around
//! the axis. Spheres, capsules, cylinders and cones are all made this way (their profiles are in
//! `round.rs`).
//!
//! A profile is a list of *strips*; each strip is a polyline drawn from the bottom of the solid
//! to its top, going round the outside, with a normal at each point. Within a strip the normals
//! are shared (smooth shading); a sharp rim (a cylinder's edge) is where one strip ends and the
//! next begins. Moving along a strip and counter-clockwise about Z makes outward triangles:
//! with `∂φ` the direction of increasing angle and `∂s` along the strip, `∂φ × ∂s` points out.

use tumble::DVec3;

use super::RenderMesh;

/// A point of a profile: radius, height and the outward normal `(n_r, n_z)` in the (r, z) plane.
#[derive(Clone, Copy, Debug)]
pub struct ProfilePoint {
    pub r: f64,
    pub z: f64,
    pub n_r: f64,
    pub n_z: f64,
}

/// Sweeps each strip of `profile` around Z in `segments` steps.
pub fn lathe(profile: &[Vec<ProfilePoint>], segments: usize) -> RenderMesh {
    let mut mesh = RenderMesh::default();
    let angles: Vec<(f64, f64)> = (0..=segments)
        .map(|j| {
            let phi = std::f64::consts::TAU * j as f64 / segments as f64;
            (phi.cos(), phi.sin())
        })
        .collect();
    for strip in profile {
        // One ring of vertices per profile point; the seam is duplicated (j = 0 and j = segments)
        // so that every ring is a plain run of indices.
        let rings: Vec<u32> = strip
            .iter()
            .map(|p| {
                let first = mesh.positions.len() as u32;
                for &(c, s) in &angles {
                    mesh.push_vertex(
                        DVec3::new(p.r * c, p.r * s, p.z),
                        DVec3::new(p.n_r * c, p.n_r * s, p.n_z),
                    );
                }
                first
            })
            .collect();
        for k in 0..strip.len().saturating_sub(1) {
            let (lower, upper) = (rings[k], rings[k + 1]);
            let lower_is_pole = strip[k].r == 0.0;
            let upper_is_pole = strip[k + 1].r == 0.0;
            for j in 0..segments as u32 {
                let (b0, b1, a0, a1) = (lower + j, lower + j + 1, upper + j, upper + j + 1);
                // At a pole a ring collapses to one point: one triangle of the quad vanishes.
                if !lower_is_pole {
                    mesh.push_triangle(b0, b1, a1);
                }
                if !upper_is_pole {
                    mesh.push_triangle(b0, a1, a0);
                }
            }
        }
    }
    mesh
}
