//! The world fuzz target (`fuzz/fuzz_targets/world_step.rs`) as a proptest: random bodies, joints,
//! and pushes (forces, torques, impulses and velocities, including NaN, infinities and 1e308)
//! stepped 100 times; no panic, no non-finite state (`fuzz_support::check_world`).

mod fuzz_support;

use arbitrary::{Arbitrary, Unstructured};
use fuzz_support::{check_world, WorldInput};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

proptest! {
    // A fixed seed: the same cases on every run (see fuzz_geometry.rs).
    #![proptest_config(Config { cases: 1000, rng_seed: RngSeed::Fixed(0x3071_d5eb), ..Config::default() })]

    #[test]
    fn random_worlds_step_without_panic_or_nan(data in proptest::collection::vec(any::<u8>(), 0..3000)) {
        if let Ok(input) = WorldInput::arbitrary_take_rest(Unstructured::new(&data)) {
            check_world(&input);
        }
    }
}

fn replay(bytes: &[u8]) {
    let input = WorldInput::arbitrary_take_rest(Unstructured::new(bytes)).expect("a stored input decodes");
    check_world(&input);
}

/// Three bodies tied by conflicting joints (two welds, a slider and a distance joint, anchors
/// metres away) diverge to 1e80 m/s and then NaN; the bodies are isolated, but the ground they
/// touched took the NaN impulse times its zero inverse mass into its velocity. Fixed by writing
/// back only the velocities of dynamic bodies (`SolverBody::write_back`).
#[test]
fn fuzz_regression_static_body_nan_from_diverging_joints() {
    replay(include_bytes!("fuzz_regressions/world_static_body_nan_from_diverging_joints.bin"));
}
