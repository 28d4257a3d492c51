//! Mass-properties validation: VALIDATION.md rows M1–M7.
//!
//! References are computed independently of the code under test: textbook formulas (M1),
//! Tonon's tetrahedron formulas over a decomposition into tetrahedra and exact box moments
//! (M2, M5), and explicit `R I Rᵀ` (M3, M4).

mod mass_support;

use mass_support::*;
use proptest::prelude::*;
use std::f64::consts::PI;
use tumble::math::mat3_max_abs;
use tumble::{
    Compound, CompoundChild, Cuboid, DMat3, DQuat, DVec3, MassError, MassProperties, Shape, Transform,
};

const RHO: f64 = 2700.0;

/// The principal moments of `p` against `expected` (any order), relative to the largest.
fn principal_error(p: &MassProperties, mut expected: [f64; 3]) -> f64 {
    expected.sort_by(f64::total_cmp);
    let got = p.principal().moments;
    let e = DVec3::from_array(expected);
    (got - e).abs().max_element() / e.max_element()
}

/// Errors as `[1.23e-4, …]` for the log.
fn show(e: &[f64]) -> String {
    let parts: Vec<String> = e.iter().map(|x| format!("{x:.2e}")).collect();
    format!("[{}]", parts.join(", "))
}

// ---------------------------------------------------------------------------------------------
// M1: primitives against textbook formulas, 1e-12 relative.

#[test]
fn m1_primitives_match_textbook_formulas() {
    let tol = 1e-12;
    let check = |what: &str, p: MassProperties, mass: f64, moments: [f64; 3], com: DVec3| {
        let volume = mass / RHO;
        assert!(((p.volume - volume) / volume).abs() <= tol, "{what} volume {} vs {volume}", p.volume);
        assert!(((p.mass - mass) / mass).abs() <= tol, "{what} mass {} vs {mass}", p.mass);
        assert!((p.center_of_mass - com).length() <= tol, "{what} com {}", p.center_of_mass);
        let diag = DMat3::from_diagonal(DVec3::from_array(moments));
        let e = mat3_max_abs(p.inertia - diag) / mat3_max_abs(diag);
        assert!(e <= tol, "{what} inertia {:?} vs {moments:?}: {e:e}", p.inertia);
        let e = principal_error(&p, moments);
        assert!(e <= tol, "{what} principal moments: {e:e}");
        eprintln!("M1 {what}: inertia error {:.2e}", mat3_max_abs(p.inertia - diag) / mat3_max_abs(diag));
    };

    // Box with edges a × b × c: m = ρabc, I_x = m (b² + c²)/12.
    let (a, b, c) = (0.3, 0.5, 1.2);
    let m = RHO * a * b * c;
    let p = MassProperties::cuboid(DVec3::new(a, b, c) / 2.0, RHO).unwrap();
    let moments = [m * (b * b + c * c) / 12.0, m * (a * a + c * c) / 12.0, m * (a * a + b * b) / 12.0];
    check("box", p, m, moments, DVec3::ZERO);

    // Sphere: m = 4/3 π r³ ρ, I = 2/5 m r².
    let r: f64 = 0.4;
    let m = RHO * 4.0 / 3.0 * PI * r.powi(3);
    check("sphere", MassProperties::sphere(r, RHO).unwrap(), m, [2.0 / 5.0 * m * r * r; 3], DVec3::ZERO);

    // Cylinder of height H: I_z = m r²/2, I_x = m (3r² + H²)/12.
    let (r, height) = (0.3, 0.8);
    let m = RHO * PI * r * r * height;
    let ix = m * (3.0 * r * r + height * height) / 12.0;
    let p = MassProperties::cylinder(r, height / 2.0, RHO).unwrap();
    check("cylinder", p, m, [ix, ix, m * r * r / 2.0], DVec3::ZERO);

    // Cone of height H: centre H/4 above the base, I_z = 3/10 m r², I_x = 3/80 m (4r² + H²).
    let (r, height) = (0.35, 0.9);
    let m = RHO * PI * r * r * height / 3.0;
    let ix = 3.0 / 80.0 * m * (4.0 * r * r + height * height);
    let p = MassProperties::cone(r, height / 2.0, RHO).unwrap();
    check("cone", p, m, [ix, ix, 0.3 * m * r * r], DVec3::new(0.0, 0.0, -height / 2.0 + height / 4.0));

    // Capsule with cylinder length H: cylinder m_c plus two hemispheres m_h; each hemisphere's
    // I_x about the capsule centre is m_h (2r²/5 + H²/4 + 3Hr/8).
    let (r, height): (f64, f64) = (0.25, 1.0);
    let m_c = RHO * PI * r * r * height;
    let m_h = RHO * 2.0 / 3.0 * PI * r.powi(3);
    let iz = m_c * r * r / 2.0 + 2.0 * m_h * 2.0 * r * r / 5.0;
    let ix = m_c * (height * height / 12.0 + r * r / 4.0)
        + 2.0 * m_h * (2.0 * r * r / 5.0 + height * height / 4.0 + 3.0 * height * r / 8.0);
    let p = MassProperties::capsule(r, height / 2.0, RHO).unwrap();
    check("capsule", p, m_c + 2.0 * m_h, [ix, ix, iz], DVec3::ZERO);
}

// ---------------------------------------------------------------------------------------------
// M2: the same solids as triangle meshes.

#[test]
fn m2_box_mesh_is_exact() {
    let half = DVec3::new(0.15, 0.25, 0.6);
    let mesh = box_mesh(-half, half);
    assert_eq!(mesh.triangles.len(), 12);
    let want = MassProperties::cuboid(half, RHO).unwrap();
    assert_close("M2 box", &mesh.mass(RHO), &want, 1.0, 1e-12);

    // Off-centre box: the centre of mass is the box centre.
    let (lo, hi) = (DVec3::new(1.0, -2.0, 0.5), DVec3::new(1.3, -1.5, 1.7));
    let want = want.transformed(&Transform::new((lo + hi) / 2.0, DQuat::IDENTITY));
    assert_close("M2 offset box", &box_mesh(lo, hi).mass(RHO), &want, 1.0, 1e-12);
}

/// A tessellated solid: equal to the polyhedron's exact values (1e-12) at every level, and
/// converging to the smooth solid as it refines.
fn check_tessellation(
    what: &str,
    levels: &[u32],
    make: impl Fn(u32) -> Mesh,
    smooth: MassProperties,
    size: f64,
) {
    let mut previous = f64::INFINITY;
    for &n in levels {
        let mesh = make(n);
        let got = mesh.mass(RHO);
        // The apex on the axis slightly above the origin: inside all three solids.
        let exact = tetra_reference(&mesh, DVec3::new(0.0, 0.0, 0.1 * size), RHO);
        assert_close(&format!("M2 {what} n={n} vs polyhedron"), &got, &exact, size, 1e-12);
        let e = errors(&got, &smooth, size);
        let worst = e.iter().fold(0.0_f64, |a, &b| a.max(b));
        eprintln!("M2 {what} n={n} ({} triangles) vs smooth solid: {}", mesh.triangles.len(), show(&e));
        assert!(worst < previous, "{what}: error {worst:e} at n={n} did not decrease from {previous:e}");
        previous = worst;
    }
    assert!(previous < 1e-3, "{what}: finest tessellation still {previous:e} from the smooth solid");
}

#[test]
fn m2_sphere_mesh() {
    let r: f64 = 0.4;
    let smooth = MassProperties::sphere(r, RHO).unwrap();
    check_tessellation("sphere", &[8, 16, 32, 64, 128], |n| uv_sphere(r, 2 * n, n), smooth, r);
}

#[test]
fn m2_cylinder_mesh() {
    let (r, h) = (0.3, 0.4);
    let smooth = MassProperties::cylinder(r, h, RHO).unwrap();
    check_tessellation("cylinder", &[8, 16, 32, 64, 128, 256], |n| cylinder_mesh(r, h, n), smooth, r);
}

#[test]
fn m2_cone_mesh() {
    let (r, h) = (0.35, 0.45);
    let smooth = MassProperties::cone(r, h, RHO).unwrap();
    check_tessellation("cone", &[8, 16, 32, 64, 128, 256], |n| cone_mesh(r, h, n), smooth, r);
}

// ---------------------------------------------------------------------------------------------
// M3, M4: moving a mesh moves its mass properties.

/// An L-shaped prism: `[0, 3] × [0, 1] ∪ [0, 1] × [1, 2.5]`, extruded over z ∈ [−0.4, 0.8].
fn l_prism() -> Mesh {
    let points = [(0.0, 0.0), (3.0, 0.0), (3.0, 1.0), (1.0, 1.0), (1.0, 2.5), (0.0, 2.5)];
    let fan = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
    extrude(&points, &[vec![0, 1, 2, 3, 4, 5]], &fan, -0.4, 0.8)
}

fn l_prism_exact() -> MassProperties {
    let (z0, z1) = (-0.4, 0.8);
    let a = RawMoments::cuboid(DVec3::new(0.0, 0.0, z0), DVec3::new(3.0, 1.0, z1));
    let b = RawMoments::cuboid(DVec3::new(0.0, 1.0, z0), DVec3::new(1.0, 2.5, z1));
    a.plus(b).mass_properties(RHO)
}

fn check_moved(mesh: &Mesh, q: DQuat, t: DVec3) -> Result<(), TestCaseError> {
    let base = mesh.mass(RHO);
    let moved = mesh.moved(q, t).mass(RHO);
    let r = DMat3::from_quat(q);
    let scale = 5.0 + t.length();
    let com_err = (moved.center_of_mass - (r * base.center_of_mass + t)).length() / scale;
    let rirt = r * base.inertia * r.transpose();
    let inertia_err = mat3_max_abs(moved.inertia - rirt) / mat3_max_abs(rirt);
    let mass_err = (moved.mass - base.mass).abs() / base.mass;
    prop_assert!(com_err <= 1e-12, "com error {com_err:e}");
    prop_assert!(inertia_err <= 1e-12, "inertia error {inertia_err:e}");
    prop_assert!(mass_err <= 1e-12, "mass error {mass_err:e}");
    // The library's own placement agrees.
    let placed = base.transformed(&Transform::new(t, q));
    prop_assert!(mat3_max_abs(placed.inertia - moved.inertia) <= 1e-12 * mat3_max_abs(rirt));
    Ok(())
}

fn quaternion() -> impl Strategy<Value = DQuat> {
    prop::array::uniform4(-1.0..1.0f64).prop_filter_map("too short", quat_from)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn m3_moved_mesh(q in quaternion(), t in prop::array::uniform3(-10.0..10.0f64)) {
        let t = DVec3::from_array(t);
        check_moved(&l_prism(), q, t)?;
        check_moved(&cone_mesh(0.5, 0.8, 24), q, t)?;
    }

    #[test]
    fn m4_rotated_box_principal_frame(q in quaternion(), t in prop::array::uniform3(-10.0..10.0f64)) {
        let half = DVec3::new(0.5, 1.0, 1.5);
        let r = DMat3::from_quat(q);
        let cuboid = MassProperties::cuboid(half, RHO).unwrap();
        let body = cuboid.inertia; // diagonal
        let moments = [body.x_axis.x, body.y_axis.y, body.z_axis.z];
        // Ascending moments of this box are about z, y, x.
        let order = [2, 1, 0];
        let from_mesh = box_mesh(-half, half).moved(q, DVec3::from_array(t)).mass(RHO);
        let from_primitive = cuboid.transformed(&Transform::new(DVec3::ZERO, q));
        for p in [from_mesh, from_primitive] {
            let frame = p.principal();
            for (k, &axis) in order.iter().enumerate() {
                let m_err = (frame.moments[k] - moments[axis]).abs() / moments[axis];
                prop_assert!(m_err <= 1e-12, "moment {k}: {m_err:e}");
                let (got, want) = (frame.axes.col(k), r.col(axis));
                let a_err = (got - want).length().min((got + want).length());
                prop_assert!(a_err <= 1e-12, "axis {k}: {got} vs ±{want}: {a_err:e}");
            }
            prop_assert!((frame.axes.determinant() - 1.0).abs() <= 1e-14);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// M5: non-convex closed meshes against exact values, 1e-10.

#[test]
fn m5_l_prism() {
    assert_close("M5 L prism", &l_prism().mass(RHO), &l_prism_exact(), 3.0, 1e-10);
}

#[test]
fn m5_square_ring_with_offset_hole() {
    // Outer box [−2, 2.5] × [−1.5, 2] minus the hole [−1, 0.5] × [−0.5, 1], z ∈ [−0.3, 0.5]:
    // a genus-1 polyhedron whose hole is off-centre, so the centre of mass is not on an axis.
    let points = [
        (-2.0, -1.5),
        (2.5, -1.5),
        (2.5, 2.0),
        (-2.0, 2.0),
        (-1.0, -0.5),
        (0.5, -0.5),
        (0.5, 1.0),
        (-1.0, 1.0),
    ];
    let loops = [vec![0, 1, 2, 3], vec![4, 7, 6, 5]];
    let caps: Vec<[u32; 3]> = (0..4u32)
        .flat_map(|k| {
            let k1 = (k + 1) % 4;
            [[k, k1, 4 + k1], [k, 4 + k1, 4 + k]]
        })
        .collect();
    let (z0, z1) = (-0.3, 0.5);
    let mesh = extrude(&points, &loops, &caps, z0, z1);
    let outer = RawMoments::cuboid(DVec3::new(-2.0, -1.5, z0), DVec3::new(2.5, 2.0, z1));
    let hole = RawMoments::cuboid(DVec3::new(-1.0, -0.5, z0), DVec3::new(0.5, 1.0, z1));
    let want = outer.minus(hole).mass_properties(RHO);
    assert!(want.center_of_mass.x.abs() > 0.05 && want.center_of_mass.y.abs() > 0.05);
    assert_close("M5 square ring", &mesh.mass(RHO), &want, 4.5, 1e-10);
}

#[test]
fn m5_torus() {
    let (big_r, r) = (1.0, 0.3);
    // Smooth torus: V = 2π² R r², I_z = m (R² + 3r²/4), I_x = m (R²/2 + 5r²/8).
    let volume = 2.0 * PI * PI * big_r * r * r;
    let m = RHO * volume;
    let ix = m * (big_r * big_r / 2.0 + 5.0 * r * r / 8.0);
    let smooth = MassProperties {
        volume,
        mass: m,
        center_of_mass: DVec3::ZERO,
        inertia: DMat3::from_diagonal(DVec3::new(ix, ix, m * (big_r * big_r + 0.75 * r * r))),
    };
    let mut previous = f64::INFINITY;
    for n in [16, 64, 256] {
        let mesh = torus_mesh(big_r, r, n, n / 2);
        let got = mesh.mass(RHO);
        // The apex in the hole, outside the solid: the signed tetrahedra still sum exactly.
        let exact = tetra_reference(&mesh, DVec3::new(0.1, -0.2, 0.05), RHO);
        assert_close(&format!("M5 torus n={n} vs polyhedron"), &got, &exact, big_r, 1e-10);
        let e = errors(&got, &smooth, big_r);
        eprintln!("M5 torus n={n} vs smooth torus: {}", show(&e));
        let worst = e.iter().fold(0.0_f64, |a, &b| a.max(b));
        assert!(worst < previous, "torus: error {worst:e} at n={n} did not decrease");
        previous = worst;
    }
    assert!(previous < 1e-3, "finest torus still {previous:e} from the smooth one");
}

// ---------------------------------------------------------------------------------------------
// M6: bad meshes give a clear error naming the problem.

#[track_caller]
fn expect_error(mesh: &Mesh, matches: impl Fn(&MassError) -> bool, words: &[&str]) -> MassError {
    let err = MassProperties::from_mesh(&mesh.vertices, &mesh.triangles, RHO).unwrap_err();
    assert!(matches(&err), "unexpected error variant: {err:?}");
    let message = err.to_string();
    for w in words {
        assert!(message.contains(w), "message {message:?} does not mention {w:?}");
    }
    // (Compared through Debug: a NaN in the error is not equal to itself.)
    let again = tumble::mass::validate_closed_mesh(&mesh.vertices, &mesh.triangles).unwrap_err();
    assert_eq!(format!("{again:?}"), format!("{err:?}"));
    err
}

#[test]
fn m6_open_mesh() {
    let mut mesh = box_mesh(DVec3::ZERO, DVec3::ONE);
    mesh.triangles.pop();
    let err = expect_error(&mesh, |e| matches!(e, MassError::OpenMesh { count: 1, .. }), &["open", "edge"]);
    // The named edge is one of the removed triangle's (4, 7, 6).
    let MassError::OpenMesh { a, b, .. } = err else { unreachable!() };
    assert!([4, 6, 7].contains(&a) && [4, 6, 7].contains(&b), "edge ({a}, {b})");
}

#[test]
fn m6_inconsistent_winding() {
    let mut mesh = box_mesh(DVec3::ZERO, DVec3::ONE);
    mesh.triangles[5].swap(1, 2);
    let err = expect_error(
        &mesh,
        |e| matches!(e, MassError::InconsistentWinding { .. }),
        &["inconsistent", "same direction", "triangles"],
    );
    let MassError::InconsistentWinding { t1, t2, .. } = err else { unreachable!() };
    assert!(t1 == 5 || t2 == 5, "triangles {t1}, {t2} do not include the flipped one");
}

#[test]
fn m6_inward_normals() {
    let mesh = box_mesh(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)).flipped();
    let err =
        expect_error(&mesh, |e| matches!(e, MassError::InvertedMesh { .. }), &["inside out", "reverse"]);
    let MassError::InvertedMesh { volume } = err else { unreachable!() };
    assert!((volume + 6.0).abs() < 1e-12, "volume {volume}");
}

#[test]
fn m6_zero_volume() {
    // A flat, two-sided square (the sides split along different diagonals, so every edge is in
    // exactly two triangles): closed and consistently wound, but it encloses nothing.
    let vertices = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    let triangles = vec![[0, 1, 2], [0, 2, 3], [1, 0, 3], [1, 3, 2]];
    let mesh = Mesh { vertices, triangles };
    expect_error(&mesh, |e| matches!(e, MassError::ZeroVolume { .. }), &["no volume"]);
    // The same square tilted out of the coordinate planes.
    let tilted = mesh.moved(DQuat::from_euler(glam::EulerRot::XYZ, 0.3, 0.7, -1.1), DVec3::splat(5.0));
    expect_error(&tilted, |e| matches!(e, MassError::ZeroVolume { .. }), &["no volume"]);
}

#[test]
fn m6_nan_vertex() {
    let mut mesh = box_mesh(DVec3::ZERO, DVec3::ONE);
    mesh.vertices[3].y = f64::NAN;
    let err = expect_error(
        &mesh,
        |e| matches!(e, MassError::NonFiniteVertex { index: 3, .. }),
        &["vertex 3", "not finite"],
    );
    assert!(err.to_string().contains("NaN"));
}

#[test]
fn m6_index_out_of_range_empty_degenerate_density() {
    let mut mesh = box_mesh(DVec3::ZERO, DVec3::ONE);
    mesh.triangles[2][1] = 99;
    expect_error(
        &mesh,
        |e| *e == MassError::IndexOutOfRange { triangle: 2, vertex: 99, count: 8 },
        &["triangle 2", "vertex 99", "only 8 vertices"],
    );

    let empty = Mesh { vertices: vec![DVec3::ZERO], triangles: vec![] };
    expect_error(&empty, |e| *e == MassError::EmptyMesh, &["no triangles"]);

    let mut mesh = box_mesh(DVec3::ZERO, DVec3::ONE);
    mesh.triangles[7] = [2, 2, 3];
    expect_error(
        &mesh,
        |e| *e == MassError::DegenerateTriangle { triangle: 7 },
        &["triangle 7", "degenerate"],
    );

    let mesh = box_mesh(DVec3::ZERO, DVec3::ONE);
    let err = MassProperties::from_mesh(&mesh.vertices, &mesh.triangles, -1.0).unwrap_err();
    assert_eq!(err, MassError::NotPositive { what: "density", value: -1.0 });
    assert!(err.to_string().contains("density must be finite and > 0, got -1"));
}

// ---------------------------------------------------------------------------------------------
// M7: compounds by the parallel-axis theorem equal the mesh of the union.

#[test]
fn m7_two_halves_make_a_long_box() {
    let half = MassProperties::cuboid(DVec3::new(1.0, 0.5, 0.75), RHO).unwrap();
    let at = |x: f64| half.transformed(&Transform::new(DVec3::new(x, 0.2, -0.1), DQuat::IDENTITY));
    let combined = MassProperties::combine(&[at(-1.0), at(1.0)]).unwrap();
    let mesh = box_mesh(DVec3::new(-2.0, -0.3, -0.85), DVec3::new(2.0, 0.7, 0.65));
    assert_close("M7 long box", &combined, &mesh.mass(RHO), 2.0, 1e-12);
}

#[test]
fn m7_compound_shape_equals_l_prism_mesh() {
    // The L prism as a compound of two boxes (the second one placed with a quarter turn about z,
    // so the rotation path is exercised), through the public Shape API.
    let a = CompoundChild {
        pose: Transform::new(DVec3::new(1.5, 0.5, 0.2), DQuat::IDENTITY),
        shape: Shape::Cuboid(Cuboid::new(DVec3::new(1.5, 0.5, 0.6)).unwrap()),
    };
    let b = CompoundChild {
        pose: Transform::new(DVec3::new(0.5, 1.75, 0.2), DQuat::from_rotation_z(PI / 2.0)),
        shape: Shape::Cuboid(Cuboid::new(DVec3::new(0.75, 0.5, 0.6)).unwrap()),
    };
    let compound = Shape::Compound(Compound::new(vec![a, b]).unwrap());
    let combined = compound.mass_properties(RHO).unwrap();
    let mesh = l_prism().mass(RHO);
    assert_close("M7 L compound vs mesh", &combined, &mesh, 3.0, 1e-12);
    assert_close("M7 L compound vs exact", &combined, &l_prism_exact(), 3.0, 1e-12);

    // And the whole thing rotated and moved: still equal.
    let pose =
        Transform::new(DVec3::new(3.0, -1.0, 2.0), DQuat::from_euler(glam::EulerRot::ZXY, 0.4, 1.2, -0.6));
    let parts = [combined.transformed(&pose)];
    let mesh = l_prism().moved(pose.rotation, pose.translation).mass(RHO);
    assert_close("M7 moved", &MassProperties::combine(&parts).unwrap(), &mesh, 3.0, 1e-12);
    assert_eq!(MassProperties::combine(&[]), Err(MassError::EmptyCompound));
}
