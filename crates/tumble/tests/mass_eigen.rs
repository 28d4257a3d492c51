//! Symmetric 3×3 eigen-decomposition (principal axes): reconstruction, orthonormality, and
//! repeated eigenvalues.

use proptest::prelude::*;
use tumble::mass::symmetric_eigen;
use tumble::math::mat3_max_abs;
use tumble::{DMat3, DQuat, DVec3};

/// Checks the decomposition of `m`; returns (reconstruction error relative to ‖m‖, orthonormality
/// error).
fn check(m: DMat3) -> (f64, f64) {
    let (values, axes) = symmetric_eigen(m);
    assert!(values.is_finite() && axes.is_finite(), "non-finite result for {m:?}");
    assert!(values.x <= values.y && values.y <= values.z, "not ascending: {values}");
    let ortho = mat3_max_abs(axes.transpose() * axes - DMat3::IDENTITY);
    let det = axes.determinant();
    assert!(ortho <= 1e-14, "axes not orthonormal: {ortho:e}");
    assert!((det - 1.0).abs() <= 1e-14, "det {det}");
    let back = axes * DMat3::from_diagonal(values) * axes.transpose();
    let scale = mat3_max_abs(m);
    let err = if scale > 0.0 { mat3_max_abs(back - m) / scale } else { mat3_max_abs(back) };
    assert!(err <= 1e-13, "reconstruction error {err:e} for {m:?}");
    (err, ortho)
}

fn symmetric(e: [f64; 6], scale: f64) -> DMat3 {
    DMat3::from_cols(DVec3::new(e[0], e[3], e[4]), DVec3::new(e[3], e[1], e[5]), DVec3::new(e[4], e[5], e[2]))
        * scale
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_symmetric_matrices(e in prop::array::uniform6(-1.0..1.0f64), exp in -8i32..8) {
        check(symmetric(e, 10f64.powi(exp)));
    }

    #[test]
    fn random_inertia_like_matrices(q in prop::array::uniform4(-1.0..1.0f64),
                                    d in prop::array::uniform3(0.0..1.0f64),
                                    repeat in 0usize..4) {
        let v = glam::DVec4::from_array(q);
        prop_assume!(v.length() > 0.1);
        let r = DMat3::from_quat(DQuat::from_vec4(v.normalize()));
        // Possibly repeated moments: none, two equal (either pair), or all three equal.
        let d = match repeat {
            0 => DVec3::from_array(d),
            1 => DVec3::new(d[0], d[0], d[2]),
            2 => DVec3::new(d[0], d[2], d[2]),
            _ => DVec3::splat(d[0]),
        };
        let m = r * DMat3::from_diagonal(d) * r.transpose();
        let (values, _) = symmetric_eigen(m);
        let mut want = d.to_array();
        want.sort_by(f64::total_cmp);
        prop_assert!((values - DVec3::from_array(want)).abs().max_element() <= 1e-14);
        check(m);
    }
}

#[test]
fn repeated_eigenvalues_give_finite_frames() {
    for m in [
        DMat3::ZERO,
        DMat3::IDENTITY,
        DMat3::from_diagonal(DVec3::new(1.0, 1.0, 2.0)),
        DMat3::from_diagonal(DVec3::new(2.0, 1.0, 1.0)),
        DMat3::from_diagonal(DVec3::new(-3.0, 0.0, -3.0)),
    ] {
        check(m);
    }
    let (values, axes) = symmetric_eigen(DMat3::from_diagonal(DVec3::new(1.0, 1.0, 2.0)));
    assert_eq!(values, DVec3::new(1.0, 1.0, 2.0));
    assert_eq!(axes.col(2).abs(), DVec3::Z);
}

#[test]
fn rotated_symmetric_top() {
    let r = DMat3::from_quat(DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -0.2, 1.9));
    let m = r * DMat3::from_diagonal(DVec3::new(2.0, 2.0, 5.0)) * r.transpose();
    let (values, axes) = symmetric_eigen(m);
    assert!((values - DVec3::new(2.0, 2.0, 5.0)).abs().max_element() <= 1e-14);
    // The unique axis is the body's third axis; the other two span its orthogonal plane.
    assert!((axes.col(2).dot(r.col(2)).abs() - 1.0).abs() <= 1e-14);
    assert!(axes.col(0).dot(r.col(2)).abs() <= 1e-14 && axes.col(1).dot(r.col(2)).abs() <= 1e-14);
    check(m);
}

#[test]
fn nearly_repeated_eigenvalues() {
    let r = DMat3::from_quat(DQuat::from_euler(glam::EulerRot::ZYX, 1.3, 0.4, -2.2));
    for gap in [1e-4, 1e-8, 1e-12, 1e-15] {
        let m = r * DMat3::from_diagonal(DVec3::new(1.0, 1.0 + gap, 3.0)) * r.transpose();
        check(m);
    }
}
