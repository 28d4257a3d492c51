//! Narrow-phase validation: known contacts with analytic answers, and properties over random
//! poses (separated shapes never penetrate, swapping shapes flips the normal, GJK matches brute
//! force, EPA and SAT agree with analytic depths, feature ids survive jitter).

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use tumble::collision::convex_contact::collide_convex;
use tumble::collision::gjk::{gjk, ConvexPair};
use tumble::collision::polytope::Polytope;
use tumble::collision::sat::sat_query;
use tumble::collision::support::Rounded;
use tumble::collision::{collide, Manifold, PairCache};
use tumble::shape::{ConvexHull, HullError};
use tumble::{Capsule, Cone, Cuboid, Cylinder, DQuat, DVec3, Shape, Sphere, Transform};

fn cuboid(x: f64, y: f64, z: f64) -> Shape {
    Shape::Cuboid(Cuboid::new(DVec3::new(x, y, z)).unwrap())
}

fn pose(t: DVec3, q: DQuat) -> Transform {
    Transform::new(t, q)
}

fn collide_fresh(a: &Shape, pa: &Transform, b: &Shape, pb: &Transform, margin: f64) -> Option<Manifold> {
    collide(a, pa, b, pb, margin, &mut PairCache::default())
}

/// A deterministic pseudo-random hull of `n` points on a squashed sphere.
fn random_hull(n: usize, seed: u64, scale: DVec3) -> ConvexHull {
    let mut s = seed | 1;
    let mut rnd = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let pts: Vec<DVec3> =
        (0..n).map(|_| DVec3::new(rnd(), rnd(), rnd()).normalize_or(DVec3::X) * scale).collect();
    ConvexHull::new(&pts).unwrap()
}

#[test]
fn resting_box_on_ground_gives_four_corner_points() {
    let ground = cuboid(10.0, 10.0, 1.0);
    let cube = cuboid(0.5, 0.4, 0.3);
    let q = DQuat::from_rotation_z(0.3);
    let pc = pose(DVec3::new(1.0, -2.0, 1.3 - 0.01), q);
    for swap in [false, true] {
        let m = if swap {
            collide_fresh(&cube, &pc, &ground, &Transform::IDENTITY, 0.02).unwrap().flipped()
        } else {
            collide_fresh(&ground, &Transform::IDENTITY, &cube, &pc, 0.02).unwrap()
        };
        assert!((m.normal_world - DVec3::Z).length() < 1e-12);
        assert_eq!(m.len(), 4);
        for p in m.points() {
            assert!((p.separation + 0.01).abs() < 1e-12, "separation {}", p.separation);
            assert!((p.point_world.z - 0.995).abs() < 1e-12);
            // Each point sits under a corner of the cube's bottom face.
            let local = q.inverse() * (p.point_world - pc.translation);
            assert!((local.x.abs() - 0.5).abs() < 1e-9 && (local.y.abs() - 0.4).abs() < 1e-9, "{local}");
        }
    }
    // Hovering within the margin: speculative points with positive separation.
    let hover = pose(DVec3::new(1.0, -2.0, 1.3 + 0.015), q);
    let m = collide_fresh(&ground, &Transform::IDENTITY, &cube, &hover, 0.02).unwrap();
    assert!(m.points().iter().all(|p| (p.separation - 0.015).abs() < 1e-12));
    assert!(collide_fresh(&ground, &Transform::IDENTITY, &cube, &hover, 0.01).is_none());
}

#[test]
fn sphere_sphere_known_contact() {
    let a = Shape::Sphere(Sphere::new(1.0).unwrap());
    let b = Shape::Sphere(Sphere::new(0.5).unwrap());
    let pb = pose(DVec3::new(1.2, 0.0, 0.0), DQuat::IDENTITY);
    let m = collide_fresh(&a, &Transform::IDENTITY, &b, &pb, 0.0).unwrap();
    assert_eq!(m.len(), 1);
    let p = m.points()[0];
    assert!((p.separation + 0.3).abs() < 1e-15);
    assert!((m.normal_world - DVec3::X).length() < 1e-15);
    assert!((p.point_world - DVec3::new(0.85, 0.0, 0.0)).length() < 1e-15);
    assert!((p.local_point_a - DVec3::X).length() < 1e-15);
    assert!((p.local_point_b - DVec3::new(-0.5, 0.0, 0.0)).length() < 1e-15);
}

#[test]
fn capsule_capsule_crossing_and_parallel() {
    let cap = Shape::Capsule(Capsule::new(0.2, 1.0).unwrap());
    // A along X, B along Y, 0.3 above: depth 0.1 straight up through the crossing point.
    let pa = pose(DVec3::ZERO, DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2));
    let pb = pose(DVec3::new(0.0, 0.0, 0.3), DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2));
    let m = collide_fresh(&cap, &pa, &cap, &pb, 0.0).unwrap();
    assert_eq!(m.len(), 1);
    assert!((m.normal_world - DVec3::Z).length() < 1e-12);
    assert!((m.points()[0].separation + 0.1).abs() < 1e-12);
    assert!((m.points()[0].point_world - DVec3::new(0.0, 0.0, 0.15)).length() < 1e-12);
    // Parallel, offset by half a length: two points at the ends of the overlap.
    let pb = pose(DVec3::new(1.0, 0.0, 0.35), pa.rotation);
    let m = collide_fresh(&cap, &pa, &cap, &pb, 0.0).unwrap();
    assert_eq!(m.len(), 2);
    let mut xs: Vec<f64> = m.points().iter().map(|p| p.point_world.x).collect();
    xs.sort_by(f64::total_cmp);
    assert!((xs[0] - 0.0).abs() < 1e-12 && (xs[1] - 1.0).abs() < 1e-12, "{xs:?}");
    assert!(m.points().iter().all(|p| (p.separation + 0.05).abs() < 1e-12));
}

#[test]
fn edge_edge_box_contact() {
    // A's top edge runs along X at z = √½, B's bottom edge along Y: they cross at one point.
    let cube = cuboid(0.5, 0.5, 0.5);
    let h = 0.5 * std::f64::consts::SQRT_2;
    let pa = pose(DVec3::ZERO, DQuat::from_rotation_x(std::f64::consts::FRAC_PI_4));
    let pb =
        pose(DVec3::new(0.1, -0.05, 2.0 * h - 0.02), DQuat::from_rotation_y(std::f64::consts::FRAC_PI_4));
    let m = collide_fresh(&cube, &pa, &cube, &pb, 0.0).unwrap();
    assert_eq!(m.len(), 1);
    assert!((m.normal_world - DVec3::Z).length() < 1e-9, "{}", m.normal_world);
    let p = m.points()[0];
    assert!((p.separation + 0.02).abs() < 1e-9, "{}", p.separation);
    assert!((p.point_world - DVec3::new(0.1, 0.0, h - 0.01)).length() < 1e-9, "{}", p.point_world);
    assert!(p.feature_id & 0x8000_0000 != 0, "an edge–edge feature id");
}

#[test]
fn box_on_tilted_face() {
    let slab = cuboid(3.0, 3.0, 0.5);
    let cube = cuboid(0.25, 0.25, 0.25);
    let tilt = DQuat::from_rotation_x(0.4) * DQuat::from_rotation_z(0.2);
    let up = tilt * DVec3::Z;
    let pa = pose(DVec3::new(0.5, 0.5, -1.0), tilt);
    let q = tilt * DQuat::from_rotation_z(0.7);
    let pb = pose(pa.translation + up * (0.75 - 0.005) + tilt * DVec3::new(0.4, -0.3, 0.0), q);
    let m = collide_fresh(&slab, &pa, &cube, &pb, 0.01).unwrap();
    assert_eq!(m.len(), 4);
    assert!((m.normal_world - up).length() < 1e-12);
    assert!(m.points().iter().all(|p| (p.separation + 0.005).abs() < 1e-12));
}

#[test]
fn cylinder_standing_on_box_gets_a_patch() {
    let ground = cuboid(5.0, 5.0, 0.5);
    let cyl = Shape::Cylinder(Cylinder::new(0.3, 0.4).unwrap());
    let pb = pose(DVec3::new(0.2, 0.1, 0.9 - 0.002), DQuat::from_rotation_z(0.1));
    let m = collide_fresh(&ground, &Transform::IDENTITY, &cyl, &pb, 0.01).unwrap();
    assert_eq!(m.len(), 4);
    assert!((m.normal_world - DVec3::Z).length() < 1e-9);
    for p in m.points() {
        assert!((p.separation + 0.002).abs() < 1e-9);
        let r = (p.point_world - pb.translation).truncate().length();
        assert!((r - 0.3).abs() < 1e-9, "points on the rim, r = {r}");
    }
    // A cone on its base also stands on a patch; on its side it lies along a line.
    let cone = Shape::Cone(Cone::new(0.3, 0.4).unwrap());
    let m = collide_fresh(&ground, &Transform::IDENTITY, &cone, &pb, 0.01).unwrap();
    assert_eq!(m.len(), 4);
}

#[test]
fn hull_rejects_bad_input() {
    assert!(matches!(ConvexHull::new(&[DVec3::ZERO; 3]), Err(HullError::TooFewPoints { count: 3 })));
    let flat: Vec<DVec3> = (0..10).map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0)).collect();
    assert_eq!(ConvexHull::new(&flat), Err(HullError::Coplanar));
    let mut pts = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    pts.push(DVec3::new(f64::INFINITY, 0.0, 0.0));
    assert!(matches!(ConvexHull::new(&pts), Err(HullError::NonFinitePoint { index: 4, .. })));
}

// ---------------------------------------------------------------------------------------------
// Properties over random configurations.

fn config(cases: u32) -> Config {
    Config { cases, rng_seed: RngSeed::Fixed(0x7u64 << 40 | 0x5eed), ..Config::default() }
}

fn unit_quat() -> impl Strategy<Value = DQuat> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("non-zero", |(x, y, z, w)| x * x + y * y + z * z + w * w > 0.01)
        .prop_map(|(x, y, z, w)| DQuat::from_xyzw(x, y, z, w).normalize())
}

fn any_convex() -> impl Strategy<Value = Shape> {
    let size = 0.2..1.5f64;
    prop_oneof![
        size.clone().prop_map(|r| Shape::Sphere(Sphere::new(r).unwrap())),
        (size.clone(), size.clone()).prop_map(|(r, h)| Shape::Capsule(Capsule::new(0.5 * r, h).unwrap())),
        (size.clone(), size.clone(), size.clone()).prop_map(|(x, y, z)| cuboid(x, y, z)),
        (size.clone(), size.clone()).prop_map(|(r, h)| Shape::Cylinder(Cylinder::new(r, h).unwrap())),
        (size.clone(), size.clone()).prop_map(|(r, h)| Shape::Cone(Cone::new(r, h).unwrap())),
        (any::<u64>(), size).prop_map(|(seed, s)| Shape::ConvexHull(random_hull(
            20,
            seed,
            DVec3::new(s, 0.8 * s, 0.6 * s)
        ))),
    ]
}

/// Extent of `shape` along `dir` (world) when placed with rotation `q` at the origin.
fn extent(shape: &Shape, q: DQuat, dir: DVec3) -> f64 {
    Rounded::of(shape).unwrap().support_local(q.inverse() * dir).dot(q.inverse() * dir)
}

proptest! {
    #![proptest_config(config(400))]

    /// Shapes on either side of a plane are reported (within a generous margin) with
    /// non-negative separations only.
    #[test]
    fn separated_shapes_never_penetrate(
        a in any_convex(), b in any_convex(), qa in unit_quat(), qb in unit_quat(),
        n in unit_quat(), gap in 0.0..0.2f64, slide in (-1.0..1.0f64, -1.0..1.0f64),
    ) {
        let normal = n * DVec3::Z;
        let (u, v) = (n * DVec3::X, n * DVec3::Y);
        let ta = -normal * (extent(&a, qa, normal) + 0.5 * gap);
        let tb = normal * (extent(&b, qb, -normal) + 0.5 * gap) + u * slide.0 + v * slide.1;
        let m = collide_fresh(&a, &pose(ta, qa), &b, &pose(tb, qb), 1.0);
        if let Some(m) = m {
            for p in m.points() {
                prop_assert!(p.separation >= -1e-7, "separation {} for gap {gap}", p.separation);
            }
        }
    }

    /// Swapping A and B flips the normal and keeps the points and separations.
    #[test]
    fn swapping_flips_the_normal_and_keeps_points(
        a in any_convex(), b in any_convex(), qa in unit_quat(), qb in unit_quat(),
        offset in (-1.5..1.5f64, -1.5..1.5f64, -1.5..1.5f64),
    ) {
        let pa = pose(DVec3::ZERO, qa);
        let pb = pose(DVec3::new(offset.0, offset.1, offset.2), qb);
        let m1 = collide_fresh(&a, &pa, &b, &pb, 0.05);
        let m2 = collide_fresh(&b, &pb, &a, &pa, 0.05);
        prop_assert_eq!(m1.is_some(), m2.is_some());
        if let (Some(m1), Some(m2)) = (m1, m2) {
            prop_assert!((m1.normal_world + m2.normal_world).length() < 1e-6, "{} vs {}", m1.normal_world, m2.normal_world);
            prop_assert_eq!(m1.len(), m2.len());
            for p in m1.points() {
                let found = m2.points().iter().any(|q| {
                    (p.point_world - q.point_world).length() < 1e-6 && (p.separation - q.separation).abs() < 1e-6
                });
                prop_assert!(found, "point {:?} missing from the swapped manifold {:?}", p, m2.points());
            }
        }
    }

    /// EPA depth equals the analytic depth: a sphere overlapping a box, and a box pressed
    /// face-down into a larger box.
    #[test]
    fn epa_depth_matches_analytic(
        he in (0.3..2.0f64, 0.3..2.0f64, 0.3..2.0f64), r in 0.1..0.5f64,
        c in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), depth in 0.001..0.1f64, yaw in -3.0..3.0f64,
    ) {
        let he = DVec3::new(he.0, he.1, he.2);
        let boxed = Cuboid::new(he).unwrap();
        let ball = Sphere::new(r).unwrap();
        let (box_shape, ball_shape) = (Shape::Cuboid(boxed), Shape::Sphere(ball));
        let centre = DVec3::new(c.0, c.1, c.2) * he;
        let gap = he - centre.abs();
        let analytic = gap.min_element() + r;
        let pa = pose(DVec3::new(0.3, 0.2, -0.1), DQuat::from_rotation_z(yaw));
        let pb = pose(pa.transform_point(centre), DQuat::IDENTITY);
        let m = collide_convex(&Rounded::of(&box_shape).unwrap(), &pa, &Rounded::of(&ball_shape).unwrap(), &pb, 0.0, &mut { DVec3::ZERO }).unwrap();
        prop_assert!((m.min_separation() + analytic).abs() < 1e-7, "epa {} analytic {}", -m.min_separation(), analytic);
        let closed = collide_fresh(&box_shape, &pa, &ball_shape, &pb, 0.0).unwrap();
        prop_assert!((closed.min_separation() + analytic).abs() < 1e-12);

        let small = cuboid(0.2, 0.15, 0.1);
        let pc = pose(pa.transform_point(DVec3::new(0.5 * c.0 * (he.x - 0.3).max(0.0), 0.5 * c.1 * (he.y - 0.3).max(0.0), he.z + 0.1 - depth)), pa.rotation * DQuat::from_rotation_z(c.2));
        let m = collide_convex(&Rounded::of(&box_shape).unwrap(), &pa, &Rounded::of(&small).unwrap(), &pc, 0.0, &mut { DVec3::ZERO }).unwrap();
        prop_assert!((m.min_separation() + depth).abs() < 1e-7, "epa {} analytic {}", -m.min_separation(), depth);
        prop_assert!((m.normal_world - pa.rotation * DVec3::Z).length() < 1e-6);
    }

    /// For overlapping polyhedra the separating-axis penetration equals EPA's depth — which
    /// checks the Gauss-map edge pruning never drops the axis that matters.
    #[test]
    fn sat_depth_equals_epa_depth(
        ea in (0.2..1.0f64, 0.2..1.0f64, 0.2..1.0f64), eb in (0.2..1.0f64, 0.2..1.0f64, 0.2..1.0f64),
        qa in unit_quat(), qb in unit_quat(), t in (-0.8..0.8f64, -0.8..0.8f64, -0.8..0.8f64), hull in any::<bool>(),
    ) {
        let hull_a = random_hull(20, 99, DVec3::new(ea.0, ea.1, ea.2) * 1.3);
        let a = if hull { Shape::ConvexHull(hull_a) } else { cuboid(ea.0, ea.1, ea.2) };
        let b = cuboid(eb.0, eb.1, eb.2);
        let pa = pose(DVec3::ZERO, qa);
        let pb = pose(DVec3::new(t.0, t.1, t.2), qb);
        let pair = ConvexPair::new(Rounded::of(&a).unwrap().core, &pa, Rounded::of(&b).unwrap().core, &pb);
        let g = gjk(&pair, pair.b_in_a.translation);
        prop_assume!(g.overlapping);
        let e = tumble::collision::epa::epa(&pair, &g.simplex).unwrap();
        let poly_a = match &a { Shape::ConvexHull(h) => Polytope::Hull(h), _ => Polytope::Cuboid { half_extents: DVec3::new(ea.0, ea.1, ea.2) } };
        let poly_b = Polytope::Cuboid { half_extents: DVec3::new(eb.0, eb.1, eb.2) };
        let q = sat_query(&poly_a, &pa, &poly_b, &pb);
        prop_assert!((q.max_separation() + e.depth).abs() < 1e-6, "sat {} epa {}", -q.max_separation(), e.depth);
    }

    /// Feature ids of a resting box survive small jitter of its pose.
    #[test]
    fn feature_ids_stable_under_jitter(
        jitter in proptest::collection::vec((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), 5),
        yaw in -3.0..3.0f64,
    ) {
        let ground = cuboid(10.0, 10.0, 1.0);
        let cube = cuboid(0.5, 0.5, 0.5);
        let mut cache = PairCache::default();
        let base = pose(DVec3::new(0.2, 0.3, 1.5 - 0.005), DQuat::from_rotation_z(yaw));
        let ids = |m: &Manifold| { let mut v: Vec<u32> = m.points().iter().map(|p| p.feature_id).collect(); v.sort(); v };
        let first = ids(&collide(&ground, &Transform::IDENTITY, &cube, &base, 0.02, &mut cache).unwrap());
        prop_assert_eq!(first.len(), 4);
        for j in jitter {
            let q = DQuat::from_axis_angle(DVec3::new(j.0, j.1, 1.0).normalize(), 1e-3 * j.3) * base.rotation;
            let p = pose(base.translation + DVec3::new(j.0, j.1, j.2) * 1e-3, q);
            let m = collide(&ground, &Transform::IDENTITY, &cube, &p, 0.02, &mut cache).unwrap();
            prop_assert_eq!(ids(&m), first.clone());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// GJK against brute force.

/// Points spread over the surface of a convex shape (local frame), roughly `spacing` apart.
fn surface_samples(shape: &Shape, spacing: f64) -> Vec<DVec3> {
    let fib = |n: usize| -> Vec<DVec3> {
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        (0..n)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let r = (1.0 - z * z).sqrt();
                DVec3::new(r * (golden * i as f64).cos(), r * (golden * i as f64).sin(), z)
            })
            .collect()
    };
    let steps = |len: f64| ((len / spacing).ceil() as usize).max(1);
    let grid = |o: DVec3, u: DVec3, v: DVec3, out: &mut Vec<DVec3>| {
        let (nu, nv) = (steps(u.length()), steps(v.length()));
        for i in 0..=nu {
            for j in 0..=nv {
                out.push(o + u * (i as f64 / nu as f64) + v * (j as f64 / nv as f64));
            }
        }
    };
    let mut out = Vec::new();
    match shape {
        Shape::Sphere(s) => {
            let n = (4.0 * std::f64::consts::PI * s.radius * s.radius / (spacing * spacing)) as usize + 10;
            out.extend(fib(n).into_iter().map(|p| p * s.radius));
        }
        Shape::Capsule(c) => {
            let n = (4.0 * std::f64::consts::PI * c.radius * c.radius / (spacing * spacing)) as usize + 10;
            out.extend(fib(n).into_iter().map(|p| p * c.radius + DVec3::Z * c.half_height * p.z.signum()));
            let m = steps(std::f64::consts::TAU * c.radius);
            for k in 0..m {
                let a = k as f64 / m as f64 * std::f64::consts::TAU;
                let rim = DVec3::new(a.cos(), a.sin(), 0.0) * c.radius;
                grid(rim - DVec3::Z * c.half_height, DVec3::Z * 2.0 * c.half_height, DVec3::ZERO, &mut out);
            }
        }
        Shape::Cuboid(b) => {
            let h = b.half_extents;
            for axis in 0..3 {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                for s in [-1.0, 1.0] {
                    let mut o = -h;
                    o[axis] = s * h[axis];
                    let mut du = DVec3::ZERO;
                    du[u] = 2.0 * h[u];
                    let mut dv = DVec3::ZERO;
                    dv[v] = 2.0 * h[v];
                    grid(o, du, dv, &mut out);
                }
            }
        }
        Shape::Cylinder(Cylinder { radius, half_height }) | Shape::Cone(Cone { radius, half_height }) => {
            let cone = matches!(shape, Shape::Cone(_));
            let m = steps(std::f64::consts::TAU * radius);
            for k in 0..m {
                let a = k as f64 / m as f64 * std::f64::consts::TAU;
                let rim = DVec3::new(a.cos(), a.sin(), 0.0) * *radius;
                let base = rim - DVec3::Z * *half_height;
                let top = if cone { DVec3::Z * *half_height } else { rim + DVec3::Z * *half_height };
                grid(base, top - base, DVec3::ZERO, &mut out);
                grid(-DVec3::Z * *half_height, rim, DVec3::ZERO, &mut out);
                if !cone {
                    grid(DVec3::Z * *half_height, rim, DVec3::ZERO, &mut out);
                }
            }
        }
        Shape::ConvexHull(h) => {
            for t in h.triangles() {
                let [a, b, c] = t.map(|i| h.vertices()[i as usize]);
                let n = steps((b - a).length().max((c - a).length()));
                for i in 0..=n {
                    for j in 0..=n - i {
                        out.push(a + (b - a) * (i as f64 / n as f64) + (c - a) * (j as f64 / n as f64));
                    }
                }
            }
        }
        _ => unreachable!(),
    }
    out
}

proptest! {
    #![proptest_config(config(60))]

    /// GJK's distance lies between the best separating-direction bound and the closest sampled
    /// surface pair, and equals the latter within the sampling error.
    #[test]
    fn gjk_distance_matches_brute_force(
        a in any_convex(), b in any_convex(), qa in unit_quat(), qb in unit_quat(),
        n in unit_quat(), gap in 0.05..0.5f64,
    ) {
        let normal = n * DVec3::Z;
        let ta = -normal * (extent(&a, qa, normal) + 0.5 * gap);
        let tb = normal * (extent(&b, qb, -normal) + 0.5 * gap);
        let (pa, pb) = (pose(ta, qa), pose(tb, qb));
        let (ra, rb) = (Rounded::of(&a).unwrap(), Rounded::of(&b).unwrap());
        let pair = ConvexPair::new(ra.core, &pa, rb.core, &pb);
        let g = gjk(&pair, pair.b_in_a.translation);
        prop_assert!(!g.overlapping);
        let distance = g.distance - ra.radius - rb.radius;
        prop_assert!(distance >= gap - 1e-9, "gjk {distance} below the plane gap {gap}");

        // Only points within reach of the other shape can form the closest pair: keep the slab
        // of each surface nearest the separating plane (the plane passes through the origin).
        let spacing = 0.04;
        let reach = distance + 0.1;
        let sa: Vec<DVec3> = surface_samples(&a, spacing).into_iter().map(|p| pa.transform_point(p))
            .filter(|p| normal.dot(*p) >= -0.5 * gap - reach).collect();
        let sb: Vec<DVec3> = surface_samples(&b, spacing).into_iter().map(|p| pb.transform_point(p))
            .filter(|q| normal.dot(*q) <= 0.5 * gap + reach).collect();
        let mut brute = f64::INFINITY;
        for p in &sa {
            for q in &sb {
                brute = brute.min(p.distance_squared(*q));
            }
        }
        let brute = brute.sqrt();
        prop_assert!(distance <= brute + 1e-9, "gjk {distance} above sampled {brute}");
        prop_assert!(brute - distance <= 2.0 * spacing, "gjk {distance} vs sampled {brute}");
    }
}
