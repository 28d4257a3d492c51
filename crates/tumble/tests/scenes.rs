//! The shared benchmark scenes build, run and report their quality results (small sizes here;
//! the full sizes are for `tumble bench` and the criterion benches).

use tumble::scenes::{self, Metric};

fn run(name: &str, size: usize, steps: u32) -> scenes::Quality {
    let mut scene = scenes::by_name(name, Some(size)).expect("a known scene");
    for _ in 0..steps {
        scene.step();
    }
    scene.quality()
}

fn value(q: &scenes::Quality, name: &str) -> f64 {
    q.metrics.iter().find(|m| m.name() == name).unwrap_or_else(|| panic!("no {name} in {q}")).value()
}

#[test]
fn every_scene_builds_by_name_with_its_default_step_count() {
    for name in scenes::NAMES {
        let scene = scenes::by_name(name, Some(2)).expect("a known scene");
        assert_eq!(scene.name, name);
        assert!(scene.steps >= 500 && scene.world.body_count() > 0, "{name}");
    }
    assert!(scenes::by_name("no such scene", None).is_none());
}

#[test]
fn small_pyramid_stands() {
    let q = run("pyramid", 5, 120);
    assert!(value(&q, "max displacement") < 0.01, "{q}");
}

#[test]
fn rain_stays_in_the_bin() {
    let q = run("rain", 300, 240);
    assert_eq!(value(&q, "escaped"), 0.0, "{q}");
    assert!(value(&q, "max penetration") < 0.05, "{q}");
}

#[test]
fn chain_holds_together() {
    let q = run("chain", 10, 120);
    assert!(value(&q, "max joint separation") < 0.05, "{q}");
}

#[test]
fn ragdolls_hold_together() {
    let scene = scenes::by_name("ragdolls", Some(2)).unwrap();
    assert_eq!(scene.world.body_count(), 1 + 2 * 11);
    assert_eq!(scene.world.joint_count(), 2 * 10);
    let q = run("ragdolls", 2, 120);
    assert!(value(&q, "max joint separation") < 0.05, "{q}");
    assert!(matches!(q.metrics[1], Metric::Flag("all asleep", _)));
}

#[test]
fn convex_pile_lands_on_the_terrain() {
    let q = run("convex_pile", 20, 120);
    assert!(value(&q, "max penetration") < 0.05, "{q}");
}

#[test]
fn tumbling_conserves_energy_and_momentum() {
    let q = run("tumbling", 27, 120);
    assert!(value(&q, "energy error") < 1e-6, "{q}");
    assert!(value(&q, "angular momentum error") < 1e-6, "{q}");
}
