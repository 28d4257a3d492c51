//! Tests of the separating-axis test (`sat.rs`).

use super::*;
use crate::math::DQuat;

/// The reference form of the test, with explicit cross products (the loop in `query` uses
/// edge directions in their place).
/// Do the Gauss-map arcs `a → b` and `c → d` (unit normals) cross? They do when c and d lie on
/// opposite sides of the plane through a and b, a and b on opposite sides of the plane through c
/// and d, and both arcs lie in the same hemisphere (the last sign test).
fn is_minkowski_face(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> bool {
    let b_x_a = b.cross(a);
    let d_x_c = d.cross(c);
    let cba = c.dot(b_x_a);
    let dba = d.dot(b_x_a);
    let adc = a.dot(d_x_c);
    let bdc = b.dot(d_x_c);
    cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0
}

#[test]
fn minkowski_face_arcs() {
    let s = 3f64.sqrt();
    // Arc from +X to +Z against an arc crossing y = 0 at (1, 0, 1)/√2: they cross.
    assert!(is_minkowski_face(
        DVec3::X,
        DVec3::Z,
        DVec3::new(1.0, -1.0, 1.0) / s,
        DVec3::new(1.0, 1.0, 1.0) / s
    ));
    // The antipodal arc does not.
    assert!(!is_minkowski_face(
        DVec3::X,
        DVec3::Z,
        DVec3::new(-1.0, -1.0, -1.0) / s,
        DVec3::new(-1.0, 1.0, -1.0) / s
    ));
}

/// The edge pairs listed from bit sets are the pairs the plain loop tests: the same query,
/// bit for bit, for random hulls (up to 54 edges) and boxes in random poses.
#[test]
fn edge_sets_give_the_plain_loops_query() {
    let mut rng = crate::scenes::rng::SplitMix64::new(0x9e37_79b9_7f4a_7c15);
    let mut unit = || rng.range(-1.0, 1.0);
    let mut hulls = Vec::new();
    for points in [6, 10, 20] {
        for _ in 0..3 {
            let cloud: Vec<DVec3> = (0..points).map(|_| DVec3::new(unit(), unit(), 0.6 * unit())).collect();
            hulls.push(crate::shape::ConvexHull::new(&cloud).expect("a hull of random points"));
        }
    }
    let mut shapes: Vec<Polytope> = hulls.iter().map(Polytope::Hull).collect();
    shapes.push(Polytope::Cuboid { half_extents: DVec3::new(0.5, 0.3, 0.2) });
    let (mut pairs_tested, mut edge_wins) = (0, 0);
    for a in &shapes {
        for b in &shapes {
            for _ in 0..40 {
                let axis = DVec3::new(unit(), unit(), unit()).normalize_or(DVec3::Z);
                let pose_b = Transform::new(
                    DVec3::new(unit(), unit(), unit()) * 1.5,
                    DQuat::from_axis_angle(axis, 3.2 * unit()),
                );
                let frames = Frames::new(a, &Transform::IDENTITY, b, &pose_b);
                let (Ok(listed), Ok(plain)) = (
                    frames.query_with_sets(f64::INFINITY, true),
                    frames.query_with_sets(f64::INFINITY, false),
                ) else {
                    unreachable!("no early out with an infinite margin");
                };
                let bits = |q: &SatQuery| {
                    (q.edges.0, q.edges.1, q.edges.2.to_bits(), q.edges.3.to_array().map(f64::to_bits))
                };
                assert_eq!(bits(&listed), bits(&plain), "pose {pose_b:?}");
                pairs_tested += 1;
                edge_wins += usize::from(listed.edges.2 > listed.face_a.1.max(listed.face_b.1));
            }
        }
    }
    assert!(edge_wins > pairs_tested / 20, "edge axes won {edge_wins} of {pairs_tested}");
}

#[test]
fn resting_box_uses_the_ground_face() {
    let ground = Polytope::Cuboid { half_extents: DVec3::new(10.0, 10.0, 1.0) };
    let cube = Polytope::Cuboid { half_extents: DVec3::splat(0.5) };
    let pose_g = Transform::IDENTITY;
    let pose_c = Transform::new(DVec3::new(0.3, -0.2, 1.49), DQuat::from_rotation_z(0.2));
    let mut cache = SatCache::default();
    let m = collide_polytopes(&ground, &pose_g, &cube, &pose_c, 0.02, &mut cache).unwrap();
    assert_eq!(m.len(), 4);
    assert!((m.normal_world - DVec3::Z).length() < 1e-12);
    for p in m.points() {
        assert!((p.separation + 0.01).abs() < 1e-12);
    }
    assert!(matches!(cache.feature, SatFeature::FaceA(_)));
}

/// Whatever the cache holds — last step's axis from far away, possibly an edge pair that is no
/// longer the closest pair of features — the early outs only ever skip pairs that are apart:
/// with the cache carried from a separated pose, the answer at any other pose (touching, or
/// not) is the one a fresh cache gives.
#[test]
fn a_carried_cache_never_hides_a_contact() {
    let a = Polytope::Cuboid { half_extents: DVec3::new(0.5, 0.3, 0.2) };
    let b = Polytope::Cuboid { half_extents: DVec3::new(0.4, 0.25, 0.15) };
    let mut rng = crate::scenes::rng::SplitMix64::new(0x2545_f491_4f6c_dd1d);
    let mut unit = || rng.range(-1.0, 1.0);
    let (mut edge_cached, mut touching) = (0, 0);
    for _ in 0..4000 {
        let axis = DVec3::new(unit(), unit(), unit()).normalize_or(DVec3::Z);
        let q = DQuat::from_axis_angle(axis, 3.2 * unit());
        let dir = DVec3::new(unit(), unit(), unit()).normalize_or(DVec3::X);
        let far = Transform::new(dir * (0.9 + 0.1 * unit().abs()), q);
        let turn =
            DQuat::from_axis_angle(DVec3::new(unit(), unit(), unit()).normalize_or(DVec3::Y), 3.2 * unit());
        let near = Transform::new(dir * (0.35 + 0.5 * unit().abs()), turn * q);
        let mut carried = SatCache::default();
        let apart = collide_polytopes(&a, &Transform::IDENTITY, &b, &far, 0.02, &mut carried);
        if apart.is_some() {
            continue;
        }
        edge_cached += usize::from(matches!(carried.feature, SatFeature::EdgePair(..)));
        let with_carried = collide_polytopes(&a, &Transform::IDENTITY, &b, &near, 0.02, &mut carried);
        let fresh = collide_polytopes(&a, &Transform::IDENTITY, &b, &near, 0.02, &mut SatCache::default());
        assert_eq!(with_carried.is_some(), fresh.is_some(), "near pose {near:?}");
        touching += usize::from(fresh.is_some());
    }
    // The sequence exercises both the carried edge axes and contacts found despite them.
    assert!(edge_cached > 100 && touching > 100, "edge-pair caches {edge_cached}, touching {touching}");
}
