//! The lanes give each manifold the bits it gets alone: whole scenes end in the same state with
//! the still manifolds solved four at a time or one at a time, on one thread or two.

use crate::dynamics::solver_body::still_pair;
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
        .filter(|c| c.fits_lanes() && still_pair(&solver_bodies[c.body_a], &solver_bodies[c.body_b]))
        .count();
    assert!(
        still * 10 >= contact_constraints.len() * 9,
        "{still} of {} manifolds still",
        contact_constraints.len()
    );
}

/// A bouncy pyramid with a box dropped onto it, through `settings`, grouped or not, on
/// `threads` threads: its state hash after 120 steps.
fn bouncy_pyramid_hash(
    settings: impl Fn(&mut crate::dynamics::solver::SolverSettings),
    grouped: bool,
    threads: usize,
) -> u64 {
    use crate::body::{BodyDef, BodyKind};
    use crate::dynamics::material::Material;
    use crate::math::DVec3;
    use crate::scenes::box_centers;
    use crate::shape::{Cuboid, Plane, Shape};
    use crate::world::WorldDef;

    let mut def = WorldDef { gravity: DVec3::new(0.0, 0.0, -9.81), ..WorldDef::default() };
    def.sleep.enabled = false;
    let mut world = World::new(def).expect("valid settings");
    let material = Material { restitution: 0.5, ..Material::default() };
    let ground = Shape::Plane(Plane::new(DVec3::Z, 0.0).expect("unit normal"));
    world
        .add_body(BodyDef { kind: BodyKind::Static, shape: Some(ground), material, ..Default::default() })
        .expect("a valid ground");
    let cube = Shape::Cuboid(Cuboid::new(DVec3::splat(0.5)).expect("positive half extents"));
    let dropped = DVec3::new(0.3, 0.1, 9.0);
    for position in box_centers(6).into_iter().chain([dropped]) {
        let def = BodyDef { shape: Some(cube.clone()), position, material, ..Default::default() };
        world.add_body(def).expect("a valid box");
    }
    let mut solver = world.solver_settings().clone();
    solver.substeps = 4;
    settings(&mut solver);
    world.set_solver_settings(solver).expect("valid settings");
    world.set_threads(threads).expect("threads");
    world.contacts_in_groups = Some(grouped);
    for _ in 0..120 {
        world.step(1.0 / 60.0).expect("a valid step");
    }
    world.state_hash()
}

/// The stages that read the manifolds themselves between the groups' passes — restitution, and
/// the steady loads learned without a relax pass — see the state the groups hold.
#[test]
fn groups_hand_their_state_to_restitution_and_the_steady_loads() {
    // Every approach bounces, so resting manifolds (grouped) bounce too.
    let with_relax = |s: &mut crate::dynamics::solver::SolverSettings| s.restitution_threshold = 0.0;
    let without_relax = |s: &mut crate::dynamics::solver::SolverSettings| s.relax_iterations = 0;
    let alone = bouncy_pyramid_hash(with_relax, false, 1);
    assert_eq!(bouncy_pyramid_hash(with_relax, true, 1), alone, "restitution, one thread");
    assert_eq!(bouncy_pyramid_hash(with_relax, true, 2), alone, "restitution, two threads");
    let alone = bouncy_pyramid_hash(without_relax, false, 1);
    assert_eq!(bouncy_pyramid_hash(without_relax, true, 1), alone, "no relax pass, one thread");
    assert_eq!(bouncy_pyramid_hash(without_relax, true, 2), alone, "no relax pass, two threads");
}
