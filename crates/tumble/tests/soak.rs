//! The short soak CI runs: the `soak` example's run (examples/soak/run.rs) for 30 s of wall time
//! on each of `rain` and `ragdolls`, at their full sizes. Energy must not rise, no body may leave
//! the scene or be isolated, and memory must stop growing once contacts reach their working set.
//! Hour-long runs: `cargo run --release -p tumble --example soak`.

#[path = "../examples/soak/run.rs"]
mod run;

use std::time::Duration;

#[test]
fn rain_and_ragdolls_soak_for_a_minute() {
    for scene in ["rain", "ragdolls"] {
        let report = run::soak(scene, None, Duration::from_secs(30));
        println!("{report}");
        assert!(report.steps > 0, "{report}");
        let problems = run::problems(&report);
        assert!(problems.is_empty(), "{scene}: {problems:?}\n{report}");
    }
}
