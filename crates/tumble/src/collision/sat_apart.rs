//! Two polyhedra that a face axis already shows apart: their distance and closest features by
//! GJK, in place of the separating-axis test's edge pairs.
//!
//! The separating-axis test spends most of its time on the edge pairs (E_A·E_B of them, pruned
//! on the Gauss map), and most of the pairs that reach it in a falling pile are apart, within the
//! speculative margin: a face axis separates them, and the question left is only whether an edge
//! pair separates them by clearly more. For shapes that are apart that has a direct answer. GJK
//! converges on the closest points of the two shapes, and its final simplex names the features
//! they lie on: a triangle spanned by two vertices of A and two of B is a face of the Minkowski
//! difference made by an edge of each, so those two edges are the closest features and their
//! separation is the distance. Any other simplex (a vertex against a face, a face against a
//! face, a vertex against a vertex or an edge) has no edge pair that realises the distance,
//! and a face axis is the contact's reference, as the test would choose it.
//!
//! So the edge pair this reports is the pair the full test would report whenever that pair could
//! win (an edge pair beats the faces only when it realises more than their separation, and the
//! distance bounds every axis's separation from above), and its separation is the exact
//! distance rather than a lower bound. Box2D v3 decides its polygon contacts the same way: closest
//! features from the distance query while apart, the separating-axis test only once overlapping.
//!
//! GJK starts along the separating face's normal, next to the answer, and takes a few support
//! steps over the vertices; the edge pairs took a few hundred sign tests.

use super::gjk::{gjk_within, ConvexPair, GjkResult};
use super::polytope::Polytope;
use super::sat::edge_cross;
use crate::math::{DVec3, Transform};

/// What GJK found for two polyhedra known to be apart.
#[derive(Clone, Copy, Debug)]
pub struct Apart {
    /// The distance, when within the query's limit; above it otherwise (a lower bound then).
    pub distance: f64,
    /// Unit direction from A's closest point to B's, in A's frame.
    pub normal: DVec3,
    /// The edges of A and of B whose closest points are the shapes' closest points, when the
    /// closest features are an edge of each.
    pub edges: Option<(usize, usize)>,
    /// The closest points, in A's frame.
    pub point_a: DVec3,
    pub point_b: DVec3,
}

/// The distance and closest features of `a` and `b` (B's pose in A's frame `b_in_a`), searched
/// from `start_dir` (A's frame, from A towards B), stopping once they are known to be more than
/// `max_distance` apart. `None` when GJK finds them touching or overlapping after all (round-off
/// at a separation of a few ulps): the caller then runs the full test.
pub fn apart(
    a: &Polytope,
    b: &Polytope,
    b_in_a: &Transform,
    start_dir: DVec3,
    max_distance: f64,
    verts_a: &[DVec3],
    verts_b_in_a: &[DVec3],
) -> Option<Apart> {
    let pair = ConvexPair { a: a.core(), b: b.core(), b_in_a: *b_in_a };
    let g = gjk_within(&pair, start_dir, max_distance);
    if g.overlapping || g.distance <= 1e-9 * pair.scale() {
        return None;
    }
    let normal = (g.point_b - g.point_a) / (g.point_b - g.point_a).length().max(f64::MIN_POSITIVE);
    let edges = closest_edges(a, b, &g, verts_a, verts_b_in_a);
    Some(Apart { distance: g.distance, normal, edges, point_a: g.point_a, point_b: g.point_b })
}

/// The edge of A and the edge of B that GJK's final simplex spans, if it is made of two vertices
/// of each: a triangle of the Minkowski face of two crossing edges, or the segment of its diagonal
/// when the closest points are on it (edges crossing at their middles).
fn closest_edges(
    a: &Polytope,
    b: &Polytope,
    g: &GjkResult,
    verts_a: &[DVec3],
    verts_b_in_a: &[DVec3],
) -> Option<(usize, usize)> {
    if g.simplex.len < 2 {
        return None;
    }
    let points = g.simplex.as_slice();
    let pair_a = two_distinct(points.iter().map(|p| nearest(verts_a, p.a)))?;
    let pair_b = two_distinct(points.iter().map(|p| nearest(verts_b_in_a, p.b)))?;
    let edge_of = |p: &Polytope, [i, j]: [u32; 2]| {
        p.edges().iter().position(|e| e.vertices == [i, j] || e.vertices == [j, i])
    };
    // Parallel edges (a segment of the two, side by side) have no axis of their own: the faces
    // beside them give it, as in the full test.
    let dir_a = verts_a[pair_a[1] as usize] - verts_a[pair_a[0] as usize];
    let dir_b = verts_b_in_a[pair_b[1] as usize] - verts_b_in_a[pair_b[0] as usize];
    edge_cross(dir_a, dir_b)?;
    Some((edge_of(a, pair_a)?, edge_of(b, pair_b)?))
}

/// The two indices among two or three, if exactly two differ.
fn two_distinct(mut indices: impl Iterator<Item = u32>) -> Option<[u32; 2]> {
    let first = indices.next()?;
    let mut second = None;
    for i in indices {
        match second {
            _ if i == first => {}
            None => second = Some(i),
            Some(s) if s == i => {}
            Some(_) => return None,
        }
    }
    Some([first, second?])
}

/// The index of the vertex nearest `p` (GJK's support points are the vertices themselves, mapped
/// the same way, so the nearest is the one at distance zero).
fn nearest(vertices: &[DVec3], p: DVec3) -> u32 {
    let mut best = (0, f64::INFINITY);
    for (i, v) in vertices.iter().enumerate() {
        let d = v.distance_squared(p);
        if d < best.1 {
            best = (i as u32, d);
        }
    }
    best.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DQuat;
    use crate::shape::ConvexHull;

    fn verts(p: &Polytope, pose: &Transform) -> Vec<DVec3> {
        (0..p.vertex_count()).map(|i| pose.transform_point(p.vertex(i))).collect()
    }

    /// Two boxes turned so that an edge of each faces the other, crossed at right angles, 3 cm
    /// apart: the closest features are those two edges and the distance is the gap.
    #[test]
    fn crossed_edges_are_found_with_their_distance() {
        let a = Polytope::Cuboid { half_extents: DVec3::splat(0.5) };
        let b = Polytope::Cuboid { half_extents: DVec3::splat(0.5) };
        // A turned about y by 45° has an edge along y on top, at height h = √2/2 (half a unit
        // cube's face diagonal); B turned about x by 45° has one along x at its bottom, h below
        // its centre.
        let h = 0.5 * 2f64.sqrt();
        let pose_b = Transform::new(
            DVec3::new(0.0, 0.0, 2.0 * h + 0.03),
            DQuat::from_rotation_x(0.25 * std::f64::consts::PI),
        );
        let pose_a = Transform::new(DVec3::ZERO, DQuat::from_rotation_y(0.25 * std::f64::consts::PI));
        let b_in_a = pose_a.inverse().mul_transform(&pose_b);
        let ident = Transform::IDENTITY;
        let found = apart(&a, &b, &b_in_a, b_in_a.translation, 1.0, &verts(&a, &ident), &verts(&b, &b_in_a))
            .expect("apart");
        assert!((found.distance - 0.03).abs() < 1e-9, "distance {}", found.distance);
        let (ea, eb) = found.edges.expect("an edge of each");
        let dir = |p: &Polytope, pose: &Transform, e: usize| {
            let [i, j] = p.edges()[e].vertices;
            pose.rotation * (p.vertex(j as usize) - p.vertex(i as usize)).normalize()
        };
        // In the world, A's edge runs along y and B's along x.
        assert!(dir(&a, &pose_a, ea).dot(DVec3::Y).abs() > 1.0 - 1e-9);
        assert!(dir(&b, &pose_b, eb).dot(DVec3::X).abs() > 1.0 - 1e-9);
        let normal_world = pose_a.rotation * found.normal;
        assert!(normal_world.dot(DVec3::Z) > 1.0 - 1e-9);
    }

    /// A box above a hull's face, tilted so one corner is lowest: a vertex against a face has
    /// no edge pair, and the distance is the corner's height above the face.
    #[test]
    fn a_corner_over_a_face_is_no_edge_pair() {
        let slab = ConvexHull::new(&[
            DVec3::new(-2.0, -2.0, -0.5),
            DVec3::new(2.0, -2.0, -0.5),
            DVec3::new(2.0, 2.0, -0.5),
            DVec3::new(-2.0, 2.0, -0.5),
            DVec3::new(-2.0, -2.0, 0.0),
            DVec3::new(2.0, -2.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(-2.0, 2.0, 0.0),
        ])
        .expect("a slab");
        let a = Polytope::Hull(&slab);
        let b = Polytope::Cuboid { half_extents: DVec3::new(0.3, 0.2, 0.1) };
        let turn = DQuat::from_axis_angle(DVec3::new(1.0, 1.0, 0.3).normalize(), 0.7);
        let lowest = (0..8).map(|i| (turn * b.vertex(i)).z).fold(f64::INFINITY, f64::min);
        let gap = 0.012;
        let pose_b = Transform::new(DVec3::new(0.1, -0.2, gap - lowest), turn);
        let found = apart(
            &a,
            &b,
            &pose_b,
            pose_b.translation,
            1.0,
            &verts(&a, &Transform::IDENTITY),
            &verts(&b, &pose_b),
        )
        .expect("apart");
        assert!((found.distance - gap).abs() < 1e-9, "distance {}", found.distance);
        assert_eq!(found.edges, None);
        assert!(found.normal.dot(DVec3::Z) > 1.0 - 1e-9);
    }

    /// Random pile hulls and a box, each brought to a random distance within the speculative
    /// margin of another from a random direction: the contact is never missed, and its nearest
    /// point reports no more separation than the shapes have, beyond the tolerance within which
    /// a face counts as realising the distance (5% plus the slop). Each kind of answer — face,
    /// edge pair, closest points — comes up.
    #[test]
    fn contacts_within_the_margin_are_kept_and_not_too_far() {
        use crate::collision::gjk::gjk;
        use crate::collision::sat::{collide_polytopes, SatCache};
        use crate::scenes::rng::SplitMix64;
        let mut rng = SplitMix64::new(0x243f_6a88_85a3_08d3);
        let mut hulls = Vec::new();
        for _ in 0..6 {
            let radii = DVec3::new(rng.range(0.25, 0.45), rng.range(0.25, 0.45), rng.range(0.25, 0.45));
            let cloud: Vec<DVec3> = (0..10)
                .map(|_| {
                    let d = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
                    d.normalize_or(DVec3::Z) * radii
                })
                .collect();
            hulls.push(ConvexHull::new(&cloud).expect("a hull"));
        }
        let mut shapes: Vec<Polytope> = hulls.iter().map(Polytope::Hull).collect();
        shapes.push(Polytope::Cuboid { half_extents: DVec3::new(0.4, 0.3, 0.2) });
        let margin = 0.03;
        let (mut faces, mut edges, mut closest) = (0, 0, 0);
        for (k, a) in shapes.iter().enumerate() {
            for b in &shapes[k..] {
                for _ in 0..60 {
                    let mut unit = || rng.range(-1.0, 1.0);
                    let dir = DVec3::new(unit(), unit(), unit()).normalize_or(DVec3::X);
                    let axis = DVec3::new(unit(), unit(), unit()).normalize_or(DVec3::Z);
                    let target = 0.002 + 0.026 * unit().abs();
                    let mut pose_b = Transform::new(2.0 * dir, DQuat::from_axis_angle(axis, 3.2 * unit()));
                    // Close the gap along the closest points' line until it is the target.
                    let pair = |pose_b: &Transform| ConvexPair { a: a.core(), b: b.core(), b_in_a: *pose_b };
                    let mut g = gjk(&pair(&pose_b), pose_b.translation);
                    for _ in 0..50 {
                        if g.overlapping || (g.distance - target).abs() < 1e-7 {
                            break;
                        }
                        let n = (g.point_b - g.point_a) / g.distance;
                        pose_b.translation -= n * (g.distance - target);
                        g = gjk(&pair(&pose_b), pose_b.translation);
                    }
                    if g.overlapping || (g.distance - target).abs() > 1e-6 {
                        continue;
                    }
                    let m = collide_polytopes(
                        a,
                        &Transform::IDENTITY,
                        b,
                        &pose_b,
                        margin,
                        &mut SatCache::default(),
                    )
                    .unwrap_or_else(|| panic!("no contact {} apart, pose {pose_b:?}", g.distance));
                    let slop = 0.0025_f64.min(0.01 * a.bounding_radius().min(b.bounding_radius()));
                    let nearest = m.min_separation();
                    assert!(
                        nearest <= 1.05 * g.distance + slop + 1e-9,
                        "reported {nearest}, distance {}, pose {pose_b:?}",
                        g.distance
                    );
                    let id = m.points()[0].feature_id;
                    if id == 0xC000_0000 {
                        closest += 1;
                        assert!((nearest - g.distance).abs() < 1e-9, "closest points at the distance");
                    } else if id & 0x8000_0000 != 0 {
                        edges += 1;
                        // No axis separates by more than the distance.
                        assert!(nearest <= g.distance + 1e-9, "an edge pair beyond the distance");
                    } else {
                        faces += 1;
                    }
                }
            }
        }
        assert!(
            faces > 100 && edges > 100 && closest > 50,
            "faces {faces}, edges {edges}, closest {closest}"
        );
    }

    /// Past the limit the search stops with a lower bound above it.
    #[test]
    fn beyond_the_limit_reports_a_bound_above_it() {
        let a = Polytope::Cuboid { half_extents: DVec3::splat(0.5) };
        let pose_b = Transform::new(DVec3::new(0.0, 0.0, 1.5), DQuat::from_rotation_z(0.4));
        let found =
            apart(&a, &a, &pose_b, DVec3::Z, 0.1, &verts(&a, &Transform::IDENTITY), &verts(&a, &pose_b))
                .expect("apart");
        assert!(found.distance > 0.1 && found.distance <= 0.5 + 1e-12, "{}", found.distance);
    }
}
