//! Continuous collision for bullets (`continuous.rs`, `collision/time_of_impact.rs`): cases that
//! speculative contacts alone let through, shown going through with `bullet = false` and stopped
//! with `bullet = true`; the time of impact against closed forms; bad input. Each test prints its
//! measurements.

use tumble::collision::support::{Core, Rounded};
use tumble::collision::time_of_impact::{separation, time_of_impact, Moving, Sweep, Target, ToiState};
use tumble::{
    BodyDef, BodyId, BodyKind, Cuboid, DQuat, DVec3, Plane, Shape, Sphere, Transform, World, WorldDef,
    WorldError,
};

/// Half thickness of the walls, m: 1 cm thick, near face at x = −0.005.
const WALL_HALF: f64 = 0.005;

fn zero_gravity_world() -> World {
    World::new(WorldDef { gravity: DVec3::ZERO, ..Default::default() }).unwrap()
}

/// A static 1 cm wall, 10 m × 10 m, centred on the origin, facing ±X.
fn wall(world: &mut World) -> BodyId {
    world
        .add_body(BodyDef {
            name: "wall".into(),
            kind: BodyKind::Static,
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(WALL_HALF, 5.0, 5.0)).unwrap())),
            ..Default::default()
        })
        .unwrap()
}

/// World corners of a box body with half extents `h`.
fn corners_world(world: &World, id: BodyId, h: DVec3) -> [DVec3; 8] {
    let pose = world.body(id).unwrap().transform();
    std::array::from_fn(|i| {
        let s = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
        pose.transform_point(h * DVec3::new(s(1), s(2), s(4)))
    })
}

/// The thrown stick: a 1 m × 2 cm × 2 cm box flying at 50 m/s towards the wall and spinning at
/// 90 rad/s about Z (its ends move at 22.5 m/s about its centre), stepped at 1/30 s: in one step it
/// turns by 3 rad and its ends sweep 1.5 m arcs, far more than anything the contacts made at the
/// start of the step foresee. `phase` shifts the start distance and angle.
struct StickRun {
    /// Largest x of any corner over the run (the wall's far face is at +0.005).
    max_corner_x: f64,
    /// Centre x at the end.
    end_x: f64,
    /// Steps in which some corner was past the far face.
    steps_past: usize,
}

const STICK_HALF: DVec3 = DVec3::new(0.5, 0.01, 0.01);

fn throw_stick(phase: f64, bullet: bool) -> StickRun {
    let mut world = zero_gravity_world();
    wall(&mut world);
    let stick = world
        .add_body(BodyDef {
            name: "stick".into(),
            shape: Some(Shape::Cuboid(Cuboid::new(STICK_HALF).unwrap())),
            position: DVec3::new(-20.0 - phase, 0.0, 0.0),
            orientation: DQuat::from_rotation_z(3.0 * phase),
            linear_velocity: DVec3::new(50.0, 0.0, 0.0),
            angular_velocity: DVec3::new(0.0, 0.0, 90.0),
            bullet,
            ..Default::default()
        })
        .unwrap();
    let mut run = StickRun { max_corner_x: f64::NEG_INFINITY, end_x: 0.0, steps_past: 0 };
    for _ in 0..60 {
        world.step(1.0 / 30.0).unwrap();
        let x = corners_world(&world, stick, STICK_HALF).iter().fold(f64::NEG_INFINITY, |m, c| m.max(c.x));
        run.max_corner_x = run.max_corner_x.max(x);
        if x > WALL_HALF {
            run.steps_past += 1;
        }
    }
    run.end_x = world.body(stick).unwrap().com_world().x;
    run
}

const PHASES: [f64; 10] = [0.0, 0.07, 0.13, 0.21, 0.29, 0.37, 0.41, 0.5, 0.57, 0.66];

#[test]
fn thrown_stick_goes_through_a_thin_wall_unless_it_is_a_bullet() {
    let mut tunnelled = 0;
    let mut worst_bullet_penetration = f64::NEG_INFINITY;
    for phase in PHASES {
        let plain = throw_stick(phase, false);
        let bullet = throw_stick(phase, true);
        let through = plain.end_x > 0.0;
        tunnelled += usize::from(through);
        // Depth of the deepest corner past the near face (negative: never reached it).
        let penetration = bullet.max_corner_x + WALL_HALF;
        worst_bullet_penetration = worst_bullet_penetration.max(penetration);
        println!(
            "stick phase {phase:.2}: plain: max corner x {:+.4} m, {} steps past the far face, end x {:+.3} m{} | \
             bullet: max corner x {:+.4} m (penetration {:+.4} m), end x {:+.3} m",
            plain.max_corner_x,
            plain.steps_past,
            plain.end_x,
            if through { " (THROUGH)" } else { "" },
            bullet.max_corner_x,
            penetration,
            bullet.end_x,
        );
        assert_eq!(bullet.steps_past, 0, "phase {phase}: a bullet corner passed the wall");
        assert!(
            bullet.end_x < -WALL_HALF,
            "phase {phase}: the bullet's centre ended at x = {}",
            bullet.end_x
        );
    }
    println!(
        "sticks through the wall without bullet: {tunnelled} of {}; deepest bullet corner past the near face: {:+.4} m",
        PHASES.len(),
        worst_bullet_penetration
    );
    assert!(tunnelled > 0, "the case no longer shows tunnelling without bullet");
}

/// A 10 cm ball at 300 m/s, stepped at 1/30 s (10 m per step), made 4–8 m in front of a 1 cm
/// wall: it reaches the wall within its first step. The broad phase stretches the new proxy's
/// box by the step's motion before it looks for pairs, so the speculative contact stops the ball
/// at the wall, bullet or not. (It once did not: a new proxy's box was stretched only once the
/// body had left it, and the plain ball went through.)
#[test]
fn ball_fired_at_a_wall_from_close_range_is_stopped_bullet_or_not() {
    let mut through = 0;
    for start in [4.0, 5.3, 6.1, 7.9] {
        let mut ends = [0.0; 2];
        for (k, bullet) in [false, true].into_iter().enumerate() {
            let mut world = zero_gravity_world();
            wall(&mut world);
            let ball = world
                .add_body(BodyDef {
                    name: "ball".into(),
                    shape: Some(Shape::Sphere(Sphere::new(0.05).unwrap())),
                    position: DVec3::new(-start, 0.0, 0.0),
                    linear_velocity: DVec3::new(300.0, 0.0, 0.0),
                    bullet,
                    ..Default::default()
                })
                .unwrap();
            let mut furthest = f64::NEG_INFINITY;
            for _ in 0..30 {
                world.step(1.0 / 30.0).unwrap();
                furthest = furthest.max(world.body(ball).unwrap().com_world().x);
            }
            ends[k] = furthest;
            let what = if bullet { "bullet" } else { "plain ball" };
            assert!(furthest + 0.05 < WALL_HALF, "start {start}: the {what} reached x = {furthest}");
        }
        through += usize::from(ends[0] > 0.0);
        println!(
            "ball from x = {:+.1} m: furthest centre x plain {:+.3} m, bullet {:+.4} m (surface {:+.4}, near face {:+.3})",
            -start,
            ends[0],
            ends[1],
            ends[1] + 0.05,
            -WALL_HALF
        );
    }
    assert_eq!(through, 0, "a plain ball went through");
}

fn ground_plane(world: &mut World) {
    world
        .add_body(BodyDef {
            name: "ground".into(),
            kind: BodyKind::Static,
            shape: Some(Shape::Plane(Plane::new(DVec3::Z, 0.0).unwrap())),
            ..Default::default()
        })
        .unwrap();
}

/// Bullets that the contacts handle are left where the contacts put them: a box sliding to a stop
/// on the ground and a ball rolling on it end bit-identical with and without the flag.
#[test]
fn bullets_the_contacts_stop_are_left_alone() {
    let run = |bullet: bool| {
        let mut world = World::default();
        ground_plane(&mut world);
        let sliding = world
            .add_body(BodyDef {
                name: "box".into(),
                shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.2, 0.1, 0.05)).unwrap())),
                position: DVec3::new(0.0, 0.0, 0.05),
                linear_velocity: DVec3::new(3.0, 1.0, 0.0),
                bullet,
                ..Default::default()
            })
            .unwrap();
        let rolling = world
            .add_body(BodyDef {
                name: "ball".into(),
                shape: Some(Shape::Sphere(Sphere::new(0.1).unwrap())),
                position: DVec3::new(3.0, 3.0, 0.1),
                linear_velocity: DVec3::new(2.0, 0.0, 0.0),
                bullet,
                ..Default::default()
            })
            .unwrap();
        for _ in 0..180 {
            world.step(1.0 / 60.0).unwrap();
        }
        let pose = |id| {
            let b = world.body(id).unwrap();
            (b.com_world(), b.orientation())
        };
        (pose(sliding), pose(rolling))
    };
    let (plain, bullet) = (run(false), run(true));
    println!("sliding box: plain {:?}, bullet {:?}", plain.0, bullet.0);
    println!("rolling ball: plain {:?}, bullet {:?}", plain.1, bullet.1);
    assert_eq!(plain, bullet);
}

/// A box dropped tilted lands on one edge and slaps down onto its face, turning fast: the far
/// edge comes down on an arc the contacts made at the start of the step do not foresee, and ends
/// the step centimetres into the ground. As a bullet it is held to the target separation.
#[test]
fn tumbling_box_landing_is_held_at_the_surface() {
    let half = DVec3::new(0.2, 0.1, 0.05);
    let mut depths = [0.0_f64; 2];
    for (k, bullet) in [false, true].into_iter().enumerate() {
        let mut world = World::default();
        ground_plane(&mut world);
        let id = world
            .add_body(BodyDef {
                name: "box".into(),
                shape: Some(Shape::Cuboid(Cuboid::new(half).unwrap())),
                position: DVec3::new(0.0, 0.0, 1.0),
                orientation: DQuat::from_rotation_x(0.3),
                bullet,
                ..Default::default()
            })
            .unwrap();
        for _ in 0..180 {
            world.step(1.0 / 60.0).unwrap();
            let lowest = corners_world(&world, id, half).iter().fold(f64::INFINITY, |m, c| m.min(c.z));
            depths[k] = depths[k].max(-lowest);
        }
    }
    println!(
        "tilted box dropped from 1 m: deepest corner below the ground plain {:.4} m, bullet {:.4} m",
        depths[0], depths[1]
    );
    assert!(depths[1] <= 0.005 + 1e-9, "bullet corner {} m deep", depths[1]);
}

// ---- time of impact against closed forms ---------------------------------------------------------

fn ball(radius: f64) -> Moving<'static> {
    Moving { shape: Rounded { core: Core::Point, radius }, pose_local: Transform::IDENTITY }
}

fn straight(from: DVec3, to: DVec3) -> Sweep {
    Sweep::new(DVec3::ZERO, (from, DQuat::IDENTITY), (to, DQuat::IDENTITY))
}

/// A ball of radius r moving at speed v along a line towards a face at distance d first comes
/// within s of it at `t = (d − r − s)/v` (as a fraction of the sweep: divided by the sweep
/// length). Conservative advancement stops with the separation in `[s, s + tolerance]`, so the
/// fraction is early by at most `tolerance / |Δx · n|`, and never late.
#[test]
fn time_of_impact_matches_closed_forms() {
    let (s, tolerance) = (0.005, 0.00125);
    let mut worst: f64 = 0.0;
    let cube = Cuboid::new(DVec3::splat(0.5)).unwrap();
    let cube_pose = Transform::new(DVec3::new(3.0, 0.2, -0.1), DQuat::from_rotation_z(0.0));
    let cases: [(&str, Target, f64); 3] = [
        // Face of the cube at x = 2.5.
        (
            "box",
            Target::Convex {
                shape: Rounded { core: Core::Cuboid { half_extents: cube.half_extents }, radius: 0.0 },
                pose: cube_pose,
            },
            2.5,
        ),
        // A half-space with its surface at x = 2.5 (outward normal −X).
        ("plane", Target::HalfSpace { normal_world: -DVec3::X, offset: -2.5 }, 2.5),
        // A sphere of radius 0.4 centred at x = 2.9 (the ball travels through its centre line).
        (
            "sphere",
            Target::Convex {
                shape: Rounded { core: Core::Point, radius: 0.4 },
                pose: Transform::new(DVec3::new(2.9, 0.0, 0.0), DQuat::IDENTITY),
            },
            2.5,
        ),
    ];
    for (name, target, face_x) in cases {
        for (x0, length, r) in [(-1.0, 10.0, 0.1), (0.0, 3.0, 0.25), (2.0, 0.45, 0.05), (-40.0, 300.0, 0.02)]
        {
            let sweep = straight(DVec3::new(x0, 0.0, 0.0), DVec3::new(x0 + length, 0.0, 0.0));
            let out = time_of_impact(&target, &ball(r), &sweep, 0.0, s, tolerance);
            let exact = (face_x - x0 - r - s) / length;
            assert_eq!(out.state, ToiState::Hit, "{name}: {out:?}");
            let error = exact - out.fraction;
            let bound = tolerance / length;
            println!(
                "TOI {name}: from x = {x0:+.1}, sweep {length} m, r = {r}: t = {:.9} exact {exact:.9}, early by {:.2e} ({:.2e} m; bound {bound:.2e}), {} iterations",
                out.fraction,
                error,
                error * length,
                out.iterations
            );
            assert!((-1e-12..=bound + 1e-12).contains(&error), "{name}: t = {} vs {exact}", out.fraction);
            worst = worst.max(error * length);
        }
    }
    println!("largest distance short of the target separation: {worst:.2e} m (tolerance {tolerance} m)");
}

/// A turning body: a 2 m rod (a capsule of half length 1 and radius 0.01) pivoting about its
/// centre at the origin through a quarter turn, from along Y to along X, towards a face at x = a.
/// Its tip is at x = sin(πt/2), so it first comes within s of the face at
/// `t = asin(a − s − 0.01) / (π/2)`. The turn is all the motion here: the bound is `θ r_max`.
#[test]
fn time_of_impact_of_a_turning_rod() {
    let (s, tolerance) = (0.005, 0.00125);
    let rod = Moving {
        shape: Rounded { core: Core::Segment { half_height: 1.0 }, radius: 0.01 },
        pose_local: Transform::IDENTITY,
    };
    // Start along Y (local Z → world Y), turn a quarter turn about Z, ending along X.
    let q0 = DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2);
    let q1 = DQuat::from_rotation_z(-std::f64::consts::FRAC_PI_2) * q0;
    let sweep = Sweep::new(DVec3::ZERO, (DVec3::ZERO, q0), (DVec3::ZERO, q1));
    let a = 0.7;
    let target = Target::HalfSpace { normal_world: -DVec3::X, offset: -a };
    let out = time_of_impact(&target, &rod, &sweep, 0.0, s, tolerance);
    // The tip at angle θ·t from Y towards X: x = sin(θ t) (plus the radius).
    let exact = ((a - s - 0.01) / 1.0).asin() / std::f64::consts::FRAC_PI_2;
    let pose = sweep.transform_at(out.fraction);
    let gap = separation(&target, &rod.shape, &pose).unwrap().distance;
    println!(
        "turning rod: t = {:.6}, exact {exact:.6}; gap there {gap:.6} m (target {s}, tolerance {tolerance}); {} iterations",
        out.fraction, out.iterations
    );
    assert_eq!(out.state, ToiState::Hit);
    assert!(out.fraction <= exact + 1e-12 && gap >= s - 1e-12 && gap <= s + tolerance);
}

// ---- bad input ----------------------------------------------------------------------------------

#[test]
fn set_bullet_reports_a_missing_body() {
    let mut world = zero_gravity_world();
    let id = world
        .add_body(BodyDef { shape: Some(Shape::Sphere(Sphere::new(0.1).unwrap())), ..Default::default() })
        .unwrap();
    world.set_bullet(id, true).unwrap();
    assert!(world.body(id).unwrap().is_bullet());
    world.remove_body(id).unwrap();
    let err = world.set_bullet(id, true).unwrap_err();
    println!("set_bullet on a removed body: {err}");
    assert_eq!(err, WorldError::StaleBody(id));
    assert!(err.to_string().contains("does not name a body"));
}

/// A bullet's velocity cannot be set to NaN (the setter refuses it), and one whose motion
/// overflows is isolated by the step before the sweep; neither panics. The sweep itself, handed a
/// NaN pose, reports no hit.
#[test]
fn non_finite_bullets_do_not_panic() {
    let mut world = zero_gravity_world();
    wall(&mut world);
    let id = world
        .add_body(BodyDef {
            shape: Some(Shape::Sphere(Sphere::new(0.1).unwrap())),
            position: DVec3::new(-1.0, 0.0, 0.0),
            bullet: true,
            ..Default::default()
        })
        .unwrap();
    let err = world.set_linear_velocity(id, DVec3::new(f64::NAN, 0.0, 0.0)).unwrap_err();
    println!("NaN velocity on a bullet: {err}");
    world.set_linear_velocity(id, DVec3::new(1e300, 0.0, 0.0)).unwrap();
    world.apply_force(id, DVec3::new(1e308, 0.0, 0.0)).unwrap();
    for _ in 0..3 {
        world.step(1.0 / 60.0).unwrap();
    }
    let body = world.body(id).unwrap();
    println!("overflowing bullet: isolated {}, at {:?}", body.is_isolated(), body.com_world());
    assert!(body.is_isolated());
    assert!(body.com_world().x < 0.0);

    let nan = DVec3::new(f64::NAN, 0.0, 0.0);
    let sweep = straight(DVec3::ZERO, nan);
    let target = Target::HalfSpace { normal_world: -DVec3::X, offset: -1.0 };
    let out = time_of_impact(&target, &ball(0.1), &sweep, 0.0, 0.005, 0.001);
    println!("NaN sweep: {out:?}");
    assert_ne!(out.state, ToiState::Hit);
}

// ---- state ---------------------------------------------------------------------------------------

/// The flag survives a snapshot, and a bullet scene steps to the same bits on 1 and 2 threads.
#[test]
fn bullet_flag_is_saved_and_deterministic() {
    let build = || {
        let mut world = zero_gravity_world();
        wall(&mut world);
        for k in 0..4 {
            world
                .add_body(BodyDef {
                    shape: Some(Shape::Cuboid(Cuboid::new(STICK_HALF).unwrap())),
                    position: DVec3::new(-20.0 - 0.1 * k as f64, 2.0 * k as f64 - 3.0, 0.0),
                    linear_velocity: DVec3::new(50.0, 0.0, 0.0),
                    angular_velocity: DVec3::new(0.0, 0.0, 90.0),
                    bullet: true,
                    ..Default::default()
                })
                .unwrap();
        }
        world
    };
    let mut one = build();
    let mut two = build();
    two.set_threads(2).unwrap();
    for _ in 0..30 {
        one.step(1.0 / 30.0).unwrap();
        two.step(1.0 / 30.0).unwrap();
    }
    assert_eq!(one.state_hash(), two.state_hash());
    let restored = World::restore(&one.snapshot()).unwrap();
    assert!(restored.bodies().filter(|(_, b)| b.kind() == BodyKind::Dynamic).all(|(_, b)| b.is_bullet()));
    let (mut a, mut b) = (one, restored);
    for _ in 0..30 {
        a.step(1.0 / 30.0).unwrap();
        b.step(1.0 / 30.0).unwrap();
    }
    assert_eq!(a.state_hash(), b.state_hash());
}
