//! Scene queries (`query.rs`): ray casts against analytic answers, `ray_cast_all` order, overlap
//! and box queries against brute force over every body, filters, sensors and bad input.

use proptest::prelude::*;
use tumble::collision::shape_aabb;
use tumble::{
    Aabb, BodyDef, BodyId, BodyKind, Capsule, CollisionFilter, Cuboid, Cylinder, DQuat, DVec3, QueryError,
    QueryFilter, Shape, Sphere, Transform, World, WorldDef,
};

fn sphere(r: f64) -> Shape {
    Shape::Sphere(Sphere::new(r).unwrap())
}

fn cuboid(x: f64, y: f64, z: f64) -> Shape {
    Shape::Cuboid(Cuboid::new(DVec3::new(x, y, z)).unwrap())
}

fn add(world: &mut World, kind: BodyKind, shape: Shape, position: DVec3) -> BodyId {
    world.add_body(BodyDef { kind, shape: Some(shape), position, ..Default::default() }).unwrap()
}

fn zero_gravity() -> World {
    World::new(WorldDef { gravity: DVec3::ZERO, ..Default::default() }).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + b.abs())
}

/// Ground slab (top at z = 0), a ball of radius 0.5 at (0, 0, 2) and a unit cube at (3, 0, 1).
fn small_scene() -> (World, BodyId, BodyId, BodyId) {
    let mut w = zero_gravity();
    let ground = add(&mut w, BodyKind::Static, cuboid(5.0, 5.0, 0.5), DVec3::new(0.0, 0.0, -0.5));
    let ball = add(&mut w, BodyKind::Dynamic, sphere(0.5), DVec3::new(0.0, 0.0, 2.0));
    let cube = add(&mut w, BodyKind::Static, cuboid(0.5, 0.5, 0.5), DVec3::new(3.0, 0.0, 1.0));
    (w, ground, ball, cube)
}

#[test]
fn ray_hits_equal_analytic_answers() {
    let (w, ground, ball, cube) = small_scene();
    let down = -DVec3::Z;
    let cases = [
        (DVec3::new(0.0, 0.0, 10.0), down, ball, 7.5, DVec3::Z),
        (DVec3::new(3.0, 0.2, 10.0), down, cube, 8.5, DVec3::Z),
        (DVec3::new(-3.0, 1.0, 10.0), down, ground, 10.0, DVec3::Z),
        (DVec3::new(-10.0, 0.0, 2.0), DVec3::X, ball, 9.5, -DVec3::X),
        (DVec3::new(10.0, 0.0, 1.2), -DVec3::X, cube, 6.5, DVec3::X),
    ];
    for (origin, direction, body, distance, normal) in cases {
        let hit = w.ray_cast(origin, direction, 100.0, None).unwrap().expect("hit");
        assert_eq!(hit.body, body, "ray from {origin}");
        assert!(close(hit.distance, distance), "ray from {origin}: {} vs {distance}", hit.distance);
        assert!((hit.normal - normal).length() < 1e-12);
        assert!((hit.point - (origin + distance * direction)).length() < 1e-9);
    }
    // A direction of any length is normalised: distances stay metres.
    let hit = w.ray_cast(DVec3::new(0.0, 0.0, 10.0), DVec3::new(0.0, 0.0, -5.0), 100.0, None).unwrap();
    assert!(close(hit.unwrap().distance, 7.5));
    // Too short, pointing away, or past everything: no hit.
    assert_eq!(w.ray_cast(DVec3::new(0.0, 0.0, 10.0), down, 7.4, None).unwrap(), None);
    assert_eq!(w.ray_cast(DVec3::new(0.0, 0.0, 10.0), DVec3::Z, f64::INFINITY, None).unwrap(), None);
    assert_eq!(w.ray_cast(DVec3::new(20.0, 0.0, 10.0), down, f64::INFINITY, None).unwrap(), None);
    // An origin inside the ball hits it at distance 0.
    let inside = w.ray_cast(DVec3::new(0.1, 0.0, 2.0), DVec3::X, 10.0, None).unwrap().unwrap();
    assert_eq!((inside.body, inside.distance), (ball, 0.0));
}

#[test]
fn queries_see_the_bodies_where_they_are_after_steps_and_set_pose() {
    let mut w = World::new(WorldDef::default()).unwrap(); // gravity on
    let ball = add(&mut w, BodyKind::Dynamic, sphere(0.5), DVec3::new(0.0, 0.0, 50.0));
    w.set_linear_velocity(ball, DVec3::new(3.0, 0.0, 0.0)).unwrap();
    for _ in 0..30 {
        w.step(1.0 / 60.0).unwrap();
        let c = w.body(ball).unwrap().position();
        let hit = w.ray_cast(c + DVec3::new(0.0, 0.0, 10.0), -DVec3::Z, 100.0, None).unwrap().unwrap();
        assert!(close(hit.distance, 9.5), "distance {} with the ball at {c}", hit.distance);
        assert_eq!(
            w.query_aabb(&Aabb::from_center_half_extents(c, DVec3::splat(0.01)), None).unwrap(),
            [ball]
        );
    }
    w.set_pose(ball, DVec3::new(-40.0, 7.0, 3.0), DQuat::IDENTITY).unwrap();
    let hit = w.ray_cast(DVec3::new(-40.0, 7.0, 10.0), -DVec3::Z, 100.0, None).unwrap().unwrap();
    assert!(close(hit.distance, 6.5));
    let probe = Transform::new(DVec3::new(-40.0, 7.0, 3.0), DQuat::IDENTITY);
    assert_eq!(w.overlap_shape(&sphere(0.1), &probe, None).unwrap(), [ball]);
}

#[test]
fn ray_cast_all_is_sorted_by_distance_then_body_id() {
    let mut w = zero_gravity();
    // Added far to near, so slot order is not distance order; the last two tie.
    let far = add(&mut w, BodyKind::Static, sphere(0.5), DVec3::new(8.0, 0.0, 0.0));
    let tie_b = add(&mut w, BodyKind::Dynamic, sphere(0.5), DVec3::new(4.0, -0.3, 0.0));
    let near = add(&mut w, BodyKind::Dynamic, cuboid(0.5, 0.5, 0.5), DVec3::new(1.0, 0.0, 0.0));
    let tie_a = add(&mut w, BodyKind::Static, sphere(0.5), DVec3::new(4.0, 0.3, 0.0));
    let _off_ray = add(&mut w, BodyKind::Dynamic, sphere(0.5), DVec3::new(4.0, 3.0, 0.0));
    let hits = w.ray_cast_all(DVec3::new(-2.0, 0.0, 0.0), DVec3::X, 100.0, None).unwrap();
    let order: Vec<BodyId> = hits.iter().map(|h| h.body).collect();
    let (lo, hi) = (tie_a.min(tie_b), tie_a.max(tie_b));
    assert_eq!(order, [near, lo, hi, far]);
    assert!(close(hits[0].distance, 2.5) && close(hits[3].distance, 9.5));
    assert_eq!(hits[1].distance, hits[2].distance, "the two balls are mirror images");
    assert!(close(hits[1].distance, 6.0 - 0.4));
    // The closest hit agrees with the first of all hits; a short ray keeps only the near ones.
    assert_eq!(w.ray_cast(DVec3::new(-2.0, 0.0, 0.0), DVec3::X, 100.0, None).unwrap(), Some(hits[0]));
    let short = w.ray_cast_all(DVec3::new(-2.0, 0.0, 0.0), DVec3::X, 6.0, None).unwrap();
    assert_eq!(short.len(), 3);
}

#[test]
fn filters_and_sensors_are_respected() {
    let mut w = zero_gravity();
    let debris = w
        .add_body(BodyDef {
            shape: Some(sphere(0.5)),
            position: DVec3::new(2.0, 0.0, 0.0),
            filter: CollisionFilter { group: 0b10, mask: u32::MAX },
            ..Default::default()
        })
        .unwrap();
    let trigger = w
        .add_body(BodyDef {
            kind: BodyKind::Static,
            shape: Some(cuboid(0.5, 0.5, 0.5)),
            position: DVec3::new(5.0, 0.0, 0.0),
            is_sensor: true,
            ..Default::default()
        })
        .unwrap();
    let wall = add(&mut w, BodyKind::Static, cuboid(0.5, 2.0, 2.0), DVec3::new(8.0, 0.0, 0.0));
    let cast = |f: Option<&QueryFilter>| -> Vec<BodyId> {
        w.ray_cast_all(DVec3::ZERO, DVec3::X, 100.0, f).unwrap().iter().map(|h| h.body).collect()
    };
    assert_eq!(cast(None), [debris, wall], "sensors are left out by default");
    assert_eq!(cast(Some(&QueryFilter::everything())), [debris, trigger, wall]);
    let not_debris = QueryFilter::from(CollisionFilter { group: 1, mask: !0b10 });
    assert_eq!(cast(Some(&not_debris)), [wall]);
    assert_eq!(w.ray_cast(DVec3::ZERO, DVec3::X, 100.0, Some(&not_debris)).unwrap().unwrap().body, wall);
    // A body whose mask refuses the query's group is not found either (both sides must accept).
    let shy = w
        .add_body(BodyDef {
            shape: Some(sphere(0.2)),
            position: DVec3::new(0.0, 5.0, 0.0),
            filter: CollisionFilter { group: 1, mask: 0b100 },
            ..Default::default()
        })
        .unwrap();
    let everywhere = Aabb::new(DVec3::splat(-100.0), DVec3::splat(100.0));
    let as_group_1 = QueryFilter::from(CollisionFilter { group: 1, mask: u32::MAX });
    assert!(!w.query_aabb(&everywhere, Some(&as_group_1)).unwrap().contains(&shy));
    assert!(w.query_aabb(&everywhere, None).unwrap().contains(&shy));
    let probe = Transform::new(DVec3::new(5.0, 0.0, 0.0), DQuat::IDENTITY);
    assert!(w.overlap_shape(&sphere(0.1), &probe, None).unwrap().is_empty());
    assert_eq!(w.overlap_shape(&sphere(0.1), &probe, Some(&QueryFilter::everything())).unwrap(), [trigger]);
}

#[test]
fn bad_input_is_an_error() {
    let (w, ..) = small_scene();
    let bad_ray = |o: DVec3, d: DVec3, m: f64| w.ray_cast(o, d, m, None).unwrap_err();
    assert!(matches!(bad_ray(DVec3::new(f64::NAN, 0.0, 0.0), DVec3::X, 1.0), QueryError::NotFinite { .. }));
    assert_eq!(bad_ray(DVec3::ZERO, DVec3::ZERO, 1.0), QueryError::ZeroDirection(DVec3::ZERO));
    assert!(matches!(bad_ray(DVec3::ZERO, DVec3::splat(1e-300), 1.0), QueryError::ZeroDirection(_)));
    assert!(matches!(
        bad_ray(DVec3::ZERO, DVec3::new(f64::INFINITY, 0.0, 0.0), 1.0),
        QueryError::ZeroDirection(_)
    ));
    assert_eq!(bad_ray(DVec3::ZERO, DVec3::X, -1.0), QueryError::InvalidMaxDistance(-1.0));
    assert!(matches!(bad_ray(DVec3::ZERO, DVec3::X, f64::NAN), QueryError::InvalidMaxDistance(_)));
    let message = bad_ray(DVec3::ZERO, DVec3::X, -1.0).to_string();
    assert!(message.contains("max_distance") && message.contains("-1"), "{message}");
    assert!(w.ray_cast_all(DVec3::ZERO, DVec3::ZERO, 1.0, None).is_err());

    let inverted = Aabb { min: DVec3::ONE, max: DVec3::ZERO };
    assert!(matches!(w.query_aabb(&inverted, None), Err(QueryError::InvalidAabb { .. })));
    let nan_box = Aabb { min: DVec3::splat(f64::NAN), max: DVec3::ZERO };
    assert!(matches!(w.query_aabb(&nan_box, None), Err(QueryError::NotFinite { .. })));

    let skewed = Transform { translation: DVec3::ZERO, rotation: DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0) };
    assert!(matches!(w.overlap_shape(&sphere(1.0), &skewed, None), Err(QueryError::InvalidOrientation(_))));
    let far = Transform::new(DVec3::new(f64::INFINITY, 0.0, 0.0), DQuat::IDENTITY);
    assert!(matches!(w.overlap_shape(&sphere(1.0), &far, None), Err(QueryError::NotFinite { .. })));
    let cube_mesh = tumble::TriMesh::new(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap();
    let err = w.overlap_shape(&Shape::TriMesh(cube_mesh), &Transform::IDENTITY, None).unwrap_err();
    assert_eq!(err, QueryError::UnsupportedShape("mesh"));
}

// ---- brute force on random scenes ----------------------------------------------------------

/// Distance from the world point `p` to a shape placed at `pose` (0 inside), from the shape
/// definitions alone.
fn distance_to(shape: &Shape, pose: &Transform, p: DVec3) -> f64 {
    let q = pose.inverse_transform_point(p);
    match shape {
        Shape::Sphere(s) => (q.length() - s.radius).max(0.0),
        Shape::Cuboid(c) => (q - q.clamp(-c.half_extents, c.half_extents)).length(),
        Shape::Capsule(c) => {
            let axis = DVec3::new(0.0, 0.0, q.z.clamp(-c.half_height, c.half_height));
            ((q - axis).length() - c.radius).max(0.0)
        }
        Shape::Cylinder(c) => {
            let rho = (q.x * q.x + q.y * q.y).sqrt();
            let (dx, dz) = ((rho - c.radius).max(0.0), (q.z.abs() - c.half_height).max(0.0));
            (dx * dx + dz * dz).sqrt()
        }
        _ => unreachable!("the random scenes hold spheres, boxes, capsules and cylinders"),
    }
}

fn unit_quat() -> impl Strategy<Value = DQuat> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("non-zero", |(x, y, z, w)| x * x + y * y + z * z + w * w > 0.01)
        .prop_map(|(x, y, z, w)| DQuat::from_xyzw(x, y, z, w).normalize())
}

fn random_shape() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (0.1..1.0f64).prop_map(sphere),
        (0.1..1.0f64, 0.1..1.0f64, 0.1..1.0f64).prop_map(|(x, y, z)| cuboid(x, y, z)),
        (0.1..0.6f64, 0.1..1.0f64).prop_map(|(r, h)| Shape::Capsule(Capsule::new(r, h).unwrap())),
        (0.1..0.8f64, 0.1..0.8f64).prop_map(|(r, h)| Shape::Cylinder(Cylinder::new(r, h).unwrap())),
    ]
}

fn coord() -> impl Strategy<Value = f64> {
    -6.0..6.0f64
}

fn point() -> impl Strategy<Value = DVec3> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// (shape, position, orientation, static?, velocity) for each body, and how many steps to take.
type RandomScene = (Vec<(Shape, DVec3, DQuat, bool, DVec3)>, usize);

fn random_scene() -> impl Strategy<Value = RandomScene> {
    (prop::collection::vec((random_shape(), point(), unit_quat(), any::<bool>(), point()), 1..24), 0..4usize)
}

fn build(scene: &RandomScene) -> World {
    let mut w = zero_gravity();
    for (shape, position, orientation, fixed, velocity) in &scene.0 {
        w.add_body(BodyDef {
            kind: if *fixed { BodyKind::Static } else { BodyKind::Dynamic },
            shape: Some(shape.clone()),
            position: *position,
            orientation: *orientation,
            linear_velocity: *velocity,
            ..Default::default()
        })
        .unwrap();
    }
    // Moving bodies leave their step-start fat boxes behind: the queries must still be exact.
    for _ in 0..scene.1 {
        w.step(1.0 / 30.0).unwrap();
    }
    w
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn sphere_overlap_equals_brute_force(scene in random_scene(), center in point(), r in 0.05..3.0f64) {
        let w = build(&scene);
        let probe = Transform::new(center, DQuat::IDENTITY);
        let found = w.overlap_shape(&sphere(r), &probe, None).unwrap();
        for (id, body) in w.bodies() {
            let d = distance_to(body.shape().unwrap(), &body.transform(), center);
            if (d - r).abs() < 1e-6 {
                continue; // grazing: either answer is right to round-off
            }
            prop_assert_eq!(found.contains(&id), d < r, "body {} at distance {} from a ball of radius {}", id, d, r);
        }
        prop_assert!(found.windows(2).all(|p| p[0] < p[1]), "sorted and unique");
    }

    #[test]
    fn box_overlap_equals_brute_force_narrow_phase(
        scene in random_scene(), center in point(), half in (0.1..2.0f64, 0.1..2.0f64, 0.1..2.0f64), q in unit_quat()
    ) {
        let w = build(&scene);
        let shape = cuboid(half.0, half.1, half.2);
        let pose = Transform::new(center, q);
        let found = w.overlap_shape(&shape, &pose, None).unwrap();
        // Brute force: every body, no tree, the same exact test.
        let mut expected = Vec::new();
        for (id, body) in w.bodies() {
            let mut cache = tumble::collision::PairCache::default();
            let m = tumble::collision::collide(&shape, &pose, body.shape().unwrap(), &body.transform(), 0.0, &mut cache);
            if m.is_some_and(|m| !m.is_empty() && m.min_separation() <= 0.0) {
                expected.push(id);
            }
        }
        prop_assert_eq!(found, expected);
    }

    #[test]
    fn aabb_query_equals_brute_force(scene in random_scene(), a in point(), b in point()) {
        let w = build(&scene);
        let aabb = Aabb::new(a.min(b), a.max(b));
        let found = w.query_aabb(&aabb, None).unwrap();
        let expected: Vec<BodyId> = w
            .bodies()
            .filter(|(_, body)| shape_aabb(body.shape().unwrap(), &body.transform()).overlaps(&aabb))
            .map(|(id, _)| id)
            .collect();
        prop_assert_eq!(found, expected);
    }

    #[test]
    fn closest_ray_hit_is_the_first_of_all_hits(scene in random_scene(), origin in point(), target in point()) {
        let w = build(&scene);
        prop_assume!((target - origin).length() > 1e-3);
        let all = w.ray_cast_all(origin, target - origin, 20.0, None).unwrap();
        let closest = w.ray_cast(origin, target - origin, 20.0, None).unwrap();
        prop_assert_eq!(closest, all.first().copied());
        prop_assert!(all.windows(2).all(|p| (p[0].distance, p[0].body) < (p[1].distance, p[1].body)));
        // Brute force: each body's shape cast on its own.
        let ray = tumble::collision::Ray::new(origin, target - origin, 20.0);
        let mut expected: Vec<(BodyId, f64)> = w
            .bodies()
            .filter_map(|(id, b)| tumble::collision::ray_cast_shape(b.shape().unwrap(), &b.transform(), &ray).map(|h| (id, h.distance)))
            .collect();
        expected.sort_by(|x, y| x.1.total_cmp(&y.1).then(x.0.cmp(&y.0)));
        let got: Vec<(BodyId, f64)> = all.iter().map(|h| (h.body, h.distance)).collect();
        prop_assert_eq!(got, expected);
    }
}
