//! Profiles of the round shapes for [`super::lathe::lathe`]. All lie along local Z, centred as
//! the core defines them: a cone's base disc at z = −half_height and its apex at +half_height.

use std::f64::consts::FRAC_PI_2;

use super::lathe::ProfilePoint;

fn point(r: f64, z: f64, n_r: f64, n_z: f64) -> ProfilePoint {
    ProfilePoint { r, z, n_r, n_z }
}

/// A quarter or half circle of `radius` centred at height `z0`, from latitude `from` to `to`
/// (radians, −π/2 at the south pole), in `steps` steps; normals point away from the centre.
fn arc(radius: f64, z0: f64, from: f64, to: f64, steps: usize) -> Vec<ProfilePoint> {
    (0..=steps)
        .map(|i| {
            let lat = from + (to - from) * i as f64 / steps as f64;
            let (s, c) = lat.sin_cos();
            // Exactly 0 at the poles, so the lathe knows the ring collapses.
            let c = if i == 0 && from == -FRAC_PI_2 || i == steps && to == FRAC_PI_2 { 0.0 } else { c };
            point(radius * c, z0 + radius * s, c, s)
        })
        .collect()
}

pub fn sphere_profile(radius: f64, rings: usize) -> Vec<Vec<ProfilePoint>> {
    vec![arc(radius, 0.0, -FRAC_PI_2, FRAC_PI_2, rings)]
}

/// One smooth strip: the lower cap, the side, the upper cap (`cap_rings` each).
pub fn capsule_profile(radius: f64, half_height: f64, cap_rings: usize) -> Vec<Vec<ProfilePoint>> {
    let mut strip = arc(radius, -half_height, -FRAC_PI_2, 0.0, cap_rings);
    strip.extend(arc(radius, half_height, 0.0, FRAC_PI_2, cap_rings));
    vec![strip]
}

/// Three strips with sharp rims: bottom disc, side, top disc.
pub fn cylinder_profile(radius: f64, half_height: f64) -> Vec<Vec<ProfilePoint>> {
    let (r, h) = (radius, half_height);
    vec![
        vec![point(0.0, -h, 0.0, -1.0), point(r, -h, 0.0, -1.0)],
        vec![point(r, -h, 1.0, 0.0), point(r, h, 1.0, 0.0)],
        vec![point(r, h, 0.0, 1.0), point(0.0, h, 0.0, 1.0)],
    ]
}

/// The base disc, then the slanted side up to the apex (smooth, with the side's normal).
pub fn cone_profile(radius: f64, half_height: f64) -> Vec<Vec<ProfilePoint>> {
    let (r, h) = (radius, half_height);
    // The side runs from (r, −h) to (0, h): direction (−r, 2h), outward normal (2h, r).
    let len = (4.0 * h * h + r * r).sqrt();
    let (n_r, n_z) = (2.0 * h / len, r / len);
    vec![
        vec![point(0.0, -h, 0.0, -1.0), point(r, -h, 0.0, -1.0)],
        vec![point(r, -h, n_r, n_z), point(0.0, h, n_r, n_z)],
    ]
}
