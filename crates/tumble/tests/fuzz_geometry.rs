//! The geometry fuzz targets (`fuzz/fuzz_targets/{convex_hull,narrow_phase}.rs`) as proptests, so
//! stable `cargo test` runs them: the same checks (`fuzz_support`), fed both from random bytes
//! through `arbitrary` (the fuzzers' input types) and from the shape strategies the collision
//! tests use. Crashes the fuzzers found are kept below as `fuzz_regression_*` tests.

mod fuzz_support;
mod shape_strategies;

use arbitrary::{Arbitrary, Unstructured};
use fuzz_support::{check_hull, check_pair, check_shapes, HullInput, PairInput};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use shape_strategies::{convex_shape, pose, scale, vec3};
use tumble::{ConvexHull, Shape};

fn from_bytes<'a, T: Arbitrary<'a>>(bytes: &'a [u8]) -> Option<T> {
    T::arbitrary_take_rest(Unstructured::new(bytes)).ok()
}

fn bytes(max: usize) -> impl Strategy<Value = Vec<u8>> {
    proptest::collection::vec(any::<u8>(), 0..max)
}

proptest! {
    // A fixed seed: the same cases on every run, so a rare find cannot make CI flaky; the fuzzers
    // are what explores.
    #![proptest_config(Config { cases: 2000, rng_seed: RngSeed::Fixed(0xf022_9e0e), ..Config::default() })]

    #[test]
    fn convex_hull_from_fuzz_bytes(data in bytes(800)) {
        if let Some(input) = from_bytes::<HullInput>(&data) {
            check_hull(&input);
        }
    }

    #[test]
    fn narrow_phase_from_fuzz_bytes(data in bytes(600)) {
        if let Some(input) = from_bytes::<PairInput>(&data) {
            check_pair(&input);
        }
    }

    /// Primitives and hulls of random points, from the collision tests' strategies.
    #[test]
    fn narrow_phase_pairs_are_symmetric(
        a in prop_oneof![convex_shape(), random_hull()],
        b in prop_oneof![convex_shape(), random_hull()],
        pa in pose(), pb in pose(),
    ) {
        // Pull B to within reach of A, so most cases touch.
        let pb = tumble::Transform::new(pa.translation + 0.4 * (pb.translation - pa.translation), pb.rotation);
        check_shapes(&a, &pa, &b, &pb, scale(&a) + scale(&b), 0.1 * scale(&a).min(scale(&b)));
    }
}

fn random_hull() -> impl Strategy<Value = Shape> {
    proptest::collection::vec(vec3(2.0), 4..40)
        .prop_filter_map("degenerate hull", |points| ConvexHull::new(&points).ok().map(Shape::ConvexHull))
}

/// Ten points within 1 cm, two of them 44 µm apart: the hull builds, but a merged face keeps a
/// vertex on one of its edges, and fanning that face gave a zero-area triangle that the mesh
/// checks of `MassProperties::from_mesh` rejected — a valid hull without mass properties. Fixed
/// by computing a hull's mass properties without the mesh checks it already passed when it was
/// built (`MassProperties::from_hull_triangles`).
#[test]
fn fuzz_regression_hull_sliver_triangle_in_face_fan() {
    let input: HullInput =
        from_bytes(include_bytes!("fuzz_regressions/hull_sliver_triangle_in_face_fan.bin")).unwrap();
    check_hull(&input);
}

/// Two cylinders of 100 m overlapping by 195 m: B–A's EPA picked a normal along which the overlap
/// is 0.014 m (7e-5 of the size) deeper than along A–B's, and reported that depth. Left as EPA's
/// accuracy on deep overlap of round shapes (contacts in a running world are millimetres deep):
/// depths and normals are compared for shallow contacts only (`fuzz_support::check_pair`).
#[test]
fn fuzz_regression_narrow_phase_deep_cylinders_epa_depth() {
    let input: PairInput =
        from_bytes(include_bytes!("fuzz_regressions/narrow_phase_deep_cylinders_epa_depth.bin")).unwrap();
    check_pair(&input);
}

/// Ten points up to 100 m out: a point 2e-6 m in front of a merged face, within the hull's merge
/// tolerance (1e-7 of the extent). The check's tolerance was tighter than the hull's; it now uses
/// the hull's (`fuzz_support::check_hull`).
#[test]
fn fuzz_regression_hull_point_outside_merged_face() {
    let input: HullInput =
        from_bytes(include_bytes!("fuzz_regressions/hull_point_outside_merged_face.bin")).unwrap();
    check_hull(&input);
}

/// A 0.2 m cylinder at the centre of a 100 m one: EPA stops with normals whose overlap is 0.27 m
/// and 0.17 m deeper than the 100.2 m the small one needs to leave — 1e-3 of the size. Left as
/// EPA's accuracy on deep overlap (see above).
#[test]
fn fuzz_regression_narrow_phase_small_cylinder_deep_in_large() {
    let input: PairInput =
        from_bytes(include_bytes!("fuzz_regressions/narrow_phase_small_cylinder_deep_in_large.bin")).unwrap();
    check_pair(&input);
}

/// A cone 2 cm wide and 200 m tall inside a 14 m wide cone of the same height, both at one spot
/// and turned alike: B–A reports 5.774 m of overlap along its normal, as the supports confirm;
/// A–B's normal is the same to 1e-3, but its clipped manifold points said only 1.129 m — the
/// deepest part of the needle lay beyond the reference face and was clipped away. Fixed in
/// `collide_convex`: a clipped manifold far shallower than the measured overlap is replaced by
/// the one exact point.
#[test]
fn fuzz_regression_narrow_phase_needle_cone_inside_cone() {
    let input: PairInput =
        from_bytes(include_bytes!("fuzz_regressions/narrow_phase_needle_cone_inside_cone.bin")).unwrap();
    check_pair(&input);
}

/// Two capsules 200 m long crossing at their centres at a shallow angle: the closest points of
/// the axes were a round-off apart, yet above the 1e-12 × radius under which the axes count as
/// crossing, so the normal followed round-off; B–A reported 1.265 m of overlap for the true
/// 0.055 m. Fixed in `capsule_capsule`: the crossing threshold scales with the segments' lengths.
#[test]
fn fuzz_regression_narrow_phase_long_capsules_crossing_shallow() {
    let input: PairInput =
        from_bytes(include_bytes!("fuzz_regressions/narrow_phase_long_capsules_crossing_shallow.bin"))
            .unwrap();
    check_pair(&input);
}

/// Two 0.2 m-radius cylinders, rims crossing: A–B reports 0.3258 m of overlap, exactly what its
/// normal gives; B–A's normal is the same to 1e-3, but its clipped points report 0.3173 m, 2.6%
/// less. Open: the clipped manifold of cylinder rims loses a little depth.
#[test]
#[ignore = "open: a cylinder-rim manifold reports 2.6% less overlap than its normal shows (0.3173 m of 0.3258 m)"]
fn fuzz_regression_narrow_phase_cylinder_rim_manifold_shallow() {
    let input: PairInput =
        from_bytes(include_bytes!("fuzz_regressions/narrow_phase_cylinder_rim_manifold_shallow.bin"))
            .unwrap();
    check_pair(&input);
}
