//! The lanes give each manifold the bits it gets alone: whole scenes end in the same state with
//! the still manifolds solved four at a time or one at a time, on one thread or two.

use crate::scenes::{by_name, Scene};
use crate::world::World;

/// The state hash after `steps` steps of `scene` with `substeps`, solving contacts in lanes or
/// one by one, on `threads` threads.
fn final_hash(scene: &str, size: usize, steps: u32, substeps: u32, one_by_one: bool, threads: usize) -> u64 {
    let Scene { mut world, dt, .. } = by_name(scene, Some(size)).expect("a built-in scene");
    let mut settings = world.solver_settings().clone();
    settings.substeps = substeps;
    world.set_solver_settings(settings).expect("valid settings");
    world.set_threads(threads).expect("threads");
    world.contacts_in_groups = Some(!one_by_one);
    for _ in 0..steps {
        world.step(dt).expect("a valid step");
    }
    world.state_hash()
}

/// Resting boxes (four-point faces, with pivoting blocks) and a pile of hulls on a mesh (one to
/// four points, bodies that stop being still mid-step).
#[test]
fn groups_of_four_give_the_bits_of_one_at_a_time() {
    for (scene, size, steps, substeps) in
        [("pyramid", 12, 150, 4), ("convex_pile", 120, 90, 5), ("ragdolls", 6, 90, 3)]
    {
        let alone = final_hash(scene, size, steps, substeps, true, 1);
        assert_eq!(final_hash(scene, size, steps, substeps, false, 1), alone, "{scene}, one thread");
        assert_eq!(final_hash(scene, size, steps, substeps, false, 2), alone, "{scene}, two threads");
    }
}

/// The lanes take part at all: a resting pyramid's still manifolds are grouped (and the world
/// that does not group them, by the test above, ends the same).
#[test]
fn a_resting_pyramid_is_solved_in_groups() {
    let Scene { mut world, dt, .. } = by_name("pyramid", Some(8)).expect("a built-in scene");
    for _ in 0..60 {
        world.step(dt).expect("a valid step");
    }
    let World { contact_constraints, solver_bodies, .. } = &world;
    let still = contact_constraints
        .iter()
        .filter(|c| c.fits_lanes() && solver_bodies[c.body_a].still && solver_bodies[c.body_b].still)
        .count();
    assert!(
        still * 10 >= contact_constraints.len() * 9,
        "{still} of {} manifolds still",
        contact_constraints.len()
    );
}
