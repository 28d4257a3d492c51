//! The rotation update of free motion, used by the solver's position stage
//! (`dynamics/solver_body.rs`, which also does translation: semi-implicit Euler).
//!
//! Rotation is the splitting method of Dullweber, Leimkuhler and McLachlan (1997). The free rigid
//! body's kinetic energy `H = Σ Lᵢ² / (2 Iᵢ)` (body-frame angular momentum `L`, principal moments
//! `Iᵢ`) is split into three parts `Hᵢ = Lᵢ² / (2 Iᵢ)`. Each part's flow is an *exact* rotation
//! about principal axis `i` by the angle `Lᵢ h / Iᵢ`: the body turns by that angle and its
//! body-frame momentum turns back by the same angle, so the world-frame momentum `R L` is unchanged.
//! Composing the flows symmetrically (Strang: ½·1, ½·2, 3, ½·2, ½·1) gives a second-order,
//! time-reversible, symplectic map: world angular momentum is kept to round-off, energy error stays
//! bounded with no drift, and the intermediate-axis flip happens at the right period. The lecture's
//! explicit update (ω = I⁻¹L, rotate by |ω| h about ω, I⁻¹ from the old orientation) is first order
//! and lets energy drift; `docs/free-rotation.md` derives both and compares them.
//!
//! Torque enters as two half kicks on the world momentum around the free flow: `L += τ h/2`, flow,
//! `L += τ h/2`.

use wide::f64x4;

use crate::lanes::Lane;
use crate::math::{DQuat, DVec3};
use crate::sin_cos::sin_cos;

/// Rotates `rotation` (principal frame → world) and the body-frame momentum `l_principal` by the
/// exact flow of `Lᵢ²/(2Iᵢ)` about principal axis `AXIS` (0, 1, 2), given the sine and cosine of
/// half the angle `Lᵢ h / Iᵢ` ([`half_angle`]).
#[inline]
fn rotate_about_principal_axis<const AXIS: usize>(
    rotation: &mut DQuat,
    l_principal: &mut DVec3,
    (hs, hc): (f64, f64),
) {
    // The whole angle's sine and cosine from the half angle's (the quaternion's): double angles.
    let (s, c) = (2.0 * hs * hc, (hc - hs) * (hc + hs));
    // Body turns by +angle about its own axis; its momentum, seen from the body, turns by −angle.
    let (i, j) = [(1, 2), (2, 0), (0, 1)][AXIS];
    let (li, lj) = (l_principal[i], l_principal[j]);
    l_principal[i] = c * li + s * lj;
    l_principal[j] = -s * li + c * lj;
    // `rotation * (hs eₐ, hc)`, written out: half the products of a full quaternion product vanish.
    let (x, y, z, w) = (rotation.x, rotation.y, rotation.z, rotation.w);
    *rotation = match AXIS {
        0 => DQuat::from_xyzw(w * hs + x * hc, y * hc + z * hs, z * hc - y * hs, w * hc - x * hs),
        1 => DQuat::from_xyzw(x * hc - z * hs, w * hs + y * hc, z * hc + x * hs, w * hc - y * hs),
        _ => DQuat::from_xyzw(x * hc + y * hs, y * hc - x * hs, w * hs + z * hc, w * hc - z * hs),
    };
}

/// Half the angle of the flow about principal axis `axis` for time `h`, given `1/Iᵢ` (a
/// multiplication where a division would lengthen the chain of dependent operations).
#[inline]
fn half_angle(l_principal: DVec3, inverse_inertia_principal: DVec3, axis: usize, h: f64) -> f64 {
    0.5 * (l_principal[axis] * inverse_inertia_principal[axis] * h)
}

/// The sines and cosines of `N` angles, four at a time in SIMD lanes and the rest one by one
/// (`sin_cos.rs`: the same bits either way).
#[inline]
fn sin_cos_each<const N: usize>(angles: [f64; N]) -> [(f64, f64); N] {
    let mut out = [(0.0, 1.0); N];
    let mut fours = angles.chunks_exact(4);
    for (k, four) in fours.by_ref().enumerate() {
        let (s, c) = sin_cos(f64x4::new([four[0], four[1], four[2], four[3]]));
        for lane in 0..4 {
            out[4 * k + lane] = (s.lane(lane), c.lane(lane));
        }
    }
    let done = N - fours.remainder().len();
    for (place, &angle) in out[done..].iter_mut().zip(fours.remainder()) {
        *place = sin_cos(angle);
    }
    out
}

/// Advances a free rigid rotation by `h` with the symmetric splitting. `rotation` maps the principal
/// frame to the world, `l_principal` is the angular momentum about the centre of mass in principal
/// axes. Returns both advanced; the world momentum `rotation * l_principal` is unchanged.
pub fn free_rotation_flow(
    rotation: DQuat,
    l_principal: DVec3,
    inertia_principal: DVec3,
    h: f64,
) -> (DQuat, DVec3) {
    free_rotation_flow_steps(rotation, l_principal, inertia_principal, h, 1)
}

/// `steps` steps of [`free_rotation_flow`] of `h` each, at once: a step's last half rotation about
/// the first axis and the next step's first are one rotation (the flows of one axis commute), so
/// `n` steps take `4n + 1` rotations instead of `5n`. The same map up to round-off, for a body on
/// which nothing acts between the steps.
pub fn free_rotation_flow_steps(
    rotation: DQuat,
    l_principal: DVec3,
    inertia_principal: DVec3,
    h: f64,
    steps: u32,
) -> (DQuat, DVec3) {
    let (mut q, mut l) = ([rotation], [l_principal]);
    free_rotation_flow_steps_lanes(&mut q, &mut l, &[inertia_principal], h, steps);
    (q[0], l[0])
}

/// [`free_rotation_flow_steps`] for `N` bodies side by side: each lane's numbers are exactly those
/// of the body alone, but the lanes' chains of dependent operations (each rotation needs the last
/// one's momentum) are independent, so the processor overlaps them.
pub fn free_rotation_flow_steps_lanes<const N: usize>(
    rotations: &mut [DQuat; N],
    l_principal: &mut [DVec3; N],
    inertia_principal: &[DVec3; N],
    h: f64,
    steps: u32,
) {
    if steps == 0 {
        return;
    }
    let inverse_inertia = inertia_principal.map(DVec3::recip);
    let rotate = |axis: usize, q: &mut [DQuat; N], l: &mut [DVec3; N], h: f64| {
        let half_angles: [f64; N] = std::array::from_fn(|k| half_angle(l[k], inverse_inertia[k], axis, h));
        let half_turns = sin_cos_each(half_angles);
        for (lane, half_turn) in half_turns.into_iter().enumerate() {
            let (q, l) = (&mut q[lane], &mut l[lane]);
            match axis {
                0 => rotate_about_principal_axis::<0>(q, l, half_turn),
                1 => rotate_about_principal_axis::<1>(q, l, half_turn),
                _ => rotate_about_principal_axis::<2>(q, l, half_turn),
            }
        }
    };
    let half = 0.5 * h;
    rotate(0, rotations, l_principal, half);
    for step in 1..=steps {
        rotate(1, rotations, l_principal, half);
        rotate(2, rotations, l_principal, h);
        rotate(1, rotations, l_principal, half);
        let last = if step == steps { half } else { h };
        rotate(0, rotations, l_principal, last);
    }
    for q in rotations.iter_mut() {
        *q = q.normalize();
    }
}

/// `free_rotation_flow` for a world-frame momentum `l_world`; returns the new rotation.
pub fn free_rotation_step(rotation: DQuat, l_world: DVec3, inertia_principal: DVec3, h: f64) -> DQuat {
    free_rotation_flow(rotation, rotation.inverse() * l_world, inertia_principal, h).0
}

/// The lecture's explicit update (`RigidBody::Update`), kept as a reference to compare against:
/// `ω = I⁻¹ L` with the world inertia of the *current* orientation, then one rotation by `|ω| h`
/// about `ω`. It is first order and not symplectic: energy drifts and the intermediate-axis flip
/// period comes out wrong. The engine does not use it.
pub fn explicit_rotation_step(rotation: DQuat, l_world: DVec3, inertia_principal: DVec3, h: f64) -> DQuat {
    let w_world = rotation * ((rotation.inverse() * l_world) / inertia_principal);
    rotate_by_angular_velocity(rotation, w_world, h)
}

/// Rotates `rotation` by a constant world angular velocity for time `h` (exact: one rotation by
/// |ω|h about ω). Used for kinematic bodies, whose ω is prescribed.
pub fn rotate_by_angular_velocity(rotation: DQuat, angular_velocity: DVec3, h: f64) -> DQuat {
    let angle = angular_velocity.length() * h;
    if angle == 0.0 {
        return rotation;
    }
    // `DQuat::from_axis_angle`, with the sine and cosine of `sin_cos.rs`.
    let (hs, hc) = sin_cos(0.5 * angle);
    let axis = angular_velocity.normalize() * hs;
    (DQuat::from_xyzw(axis.x, axis.y, axis.z, hc) * rotation).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_axis_spin_is_exact() {
        // Spinning about a principal axis: the splitting reduces to the exact rotation.
        let inertia = DVec3::new(1.0, 2.0, 3.0);
        let w = 2.0;
        let l_world = DVec3::new(0.0, 0.0, 3.0 * w);
        let mut q = DQuat::IDENTITY;
        let h = 0.01;
        for _ in 0..100 {
            q = free_rotation_step(q, l_world, inertia, h);
        }
        let expected = DQuat::from_rotation_z(w * 1.0);
        assert!(q.dot(expected).abs() > 1.0 - 1e-13, "{q:?} vs {expected:?}");
    }

    #[test]
    fn steps_at_once_match_steps_one_by_one() {
        // An asymmetric body tumbling about no principal axis, 8 steps: the merged rotations give
        // the same map to round-off.
        let inertia = DVec3::new(0.3, 1.1, 1.7);
        let (q0, l0) = (DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.2, 2.0), DVec3::new(0.9, -0.4, 1.3));
        let h = 1.0 / 480.0;
        let (mut q, mut l) = (q0, l0);
        for _ in 0..8 {
            (q, l) = free_rotation_flow(q, l, inertia, h);
        }
        let (q8, l8) = free_rotation_flow_steps(q0, l0, inertia, h, 8);
        assert!(q.dot(q8).abs() > 1.0 - 1e-15, "{q:?} vs {q8:?}");
        assert!((l - l8).length() < 1e-14 * l0.length(), "{l:?} vs {l8:?}");
        // And it moved: not the identity map.
        assert!((l8 - l0).length() > 1e-3);
        assert_eq!(free_rotation_flow_steps(q0, l0, inertia, h, 0), (q0, l0));
        // Side by side with other bodies, a body's numbers are its own, bit for bit.
        let (mut qs, mut ls) = ([DQuat::IDENTITY, q0, DQuat::from_rotation_z(1.0)], [l0 * 3.0, l0, -l0]);
        let inertias = [DVec3::ONE, inertia, inertia * 2.0];
        free_rotation_flow_steps_lanes(&mut qs, &mut ls, &inertias, h, 8);
        assert_eq!((qs[1], ls[1]), (q8, l8));
    }

    #[test]
    fn world_momentum_is_unchanged_by_one_step() {
        let inertia = DVec3::new(1.0, 2.0, 3.0);
        let q0 = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7);
        let l_world = DVec3::new(0.4, -2.0, 1.3);
        let q1 = free_rotation_step(q0, l_world, inertia, 0.05);
        // The body-frame momentum after the step, mapped back, must be the same world vector:
        // reconstruct it from the flow and compare.
        let mut q = q0;
        let mut l = q0.inverse() * l_world;
        let inverse = inertia.recip();
        let half_turn = |l: DVec3, axis: usize, h: f64| sin_cos(half_angle(l, inverse, axis, h));
        let turn = half_turn(l, 0, 0.025);
        rotate_about_principal_axis::<0>(&mut q, &mut l, turn);
        let turn = half_turn(l, 1, 0.025);
        rotate_about_principal_axis::<1>(&mut q, &mut l, turn);
        let turn = half_turn(l, 2, 0.05);
        rotate_about_principal_axis::<2>(&mut q, &mut l, turn);
        let turn = half_turn(l, 1, 0.025);
        rotate_about_principal_axis::<1>(&mut q, &mut l, turn);
        let turn = half_turn(l, 0, 0.025);
        rotate_about_principal_axis::<0>(&mut q, &mut l, turn);
        assert!((q * l - l_world).length() < 1e-14);
        assert!(q1.dot(q.normalize()).abs() > 1.0 - 1e-15);
    }
}
