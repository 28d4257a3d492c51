//! The shape-pair table: one contact routine per pair of shape kinds.
//!
//! | pair | routine |
//! |---|---|
//! | sphere–sphere, sphere–capsule, capsule–capsule, sphere–box | closed forms (`round`) |
//! | box–box, box–hull, hull–hull | separating axes + face clipping (`sat`) |
//! | everything else convex (cylinder, cone, capsule–box, …) | GJK/EPA + feature clipping (`convex_contact`) |
//!
//! The table is written for one order of each pair (by [`kind_rank`]); the other order calls it
//! with the shapes swapped and flips the result, so `collide(a, b)` and `collide(b, a)` agree up to
//! the direction of the normal. Planes, height fields and triangle meshes go to
//! `static_pairs::collide_static` first; compounds are split into leaves by the contact manager.

use super::aabb::shape_aabb;
use super::convex_contact::collide_convex;
use super::manifold::Manifold;
use super::polytope::Polytope;
use super::round::{box_sphere, capsule_capsule, sphere_capsule, sphere_sphere};
use super::sat::{collide_polytopes, SatCache};
use super::static_pairs::{collide_static, is_static_geometry};
use super::support::Rounded;
use crate::math::{DVec3, Transform};
use crate::shape::Shape;

/// What a pair remembers between steps to make the next query cheaper and its answer stable.
/// Start with `PairCache::default()` and pass the same cache for the same ordered pair each step.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PairCache {
    /// The separating-axis test's last axis (box and hull pairs).
    pub sat: SatCache,
    /// Last contact normal in the first shape's frame, GJK's starting direction (other pairs).
    pub normal_local: DVec3,
}

/// Position of a shape kind in the table's pair order; `None` for shapes that are not convex.
pub fn kind_rank(shape: &Shape) -> Option<u8> {
    match shape {
        Shape::Sphere(_) => Some(0),
        Shape::Capsule(_) => Some(1),
        Shape::Cuboid(_) => Some(2),
        Shape::ConvexHull(_) => Some(3),
        Shape::Cylinder(_) => Some(4),
        Shape::Cone(_) => Some(5),
        Shape::TriMesh(_) | Shape::Compound(_) | Shape::Plane(_) | Shape::HeightField(_) => None,
    }
}

/// The contact manifold of two shapes (convex, or convex against static geometry: a plane, height
/// field or triangle mesh) at the given poses, or `None` when they are more
/// than `speculative_margin` apart (contacts within the margin are reported with positive
/// separation, so the solver can stop bodies before they meet). The normal points from A to B.
pub fn collide(
    shape_a: &Shape,
    pose_a: &Transform,
    shape_b: &Shape,
    pose_b: &Transform,
    speculative_margin: f64,
    cache: &mut PairCache,
) -> Option<Manifold> {
    if is_static_geometry(shape_a) || is_static_geometry(shape_b) {
        return collide_static(shape_a, pose_a, shape_b, pose_b, speculative_margin);
    }
    let (ra, rb) = (kind_rank(shape_a)?, kind_rank(shape_b)?);
    if ra > rb {
        return collide_ordered(shape_b, pose_b, shape_a, pose_a, speculative_margin, cache)
            .map(|m| m.flipped());
    }
    collide_ordered(shape_a, pose_a, shape_b, pose_b, speculative_margin, cache)
}

/// The table proper, for `kind_rank(a) <= kind_rank(b)`.
fn collide_ordered(
    a: &Shape,
    pose_a: &Transform,
    b: &Shape,
    pose_b: &Transform,
    margin: f64,
    cache: &mut PairCache,
) -> Option<Manifold> {
    match (a, b) {
        (Shape::Sphere(sa), Shape::Sphere(sb)) => sphere_sphere(sa, pose_a, sb, pose_b, margin),
        (Shape::Sphere(sa), Shape::Capsule(cb)) => sphere_capsule(sa, pose_a, cb, pose_b, margin),
        (Shape::Capsule(ca), Shape::Capsule(cb)) => {
            if bounds_apart(a, pose_a, b, pose_b, margin) {
                return None;
            }
            capsule_capsule(ca, pose_a, cb, pose_b, margin)
        }
        (Shape::Sphere(sa), Shape::Cuboid(bb)) => {
            box_sphere(bb, pose_b, sa, pose_a, margin).map(|m| m.flipped())
        }
        _ => match (polytope(a), polytope(b)) {
            (Some(pa), Some(pb)) => {
                // The balls about the shapes' origins that hold them, apart by more than the
                // margin: nothing is within reach, without the separating-axis test's cached
                // axis (whose cache keeps what it last found, a hint for the next query). Half
                // the convex pile's hull pairs whose fat boxes overlap end here.
                let reach = pa.bounding_radius() + pb.bounding_radius() + margin;
                if (pose_b.translation - pose_a.translation).length_squared() > reach * reach {
                    return None;
                }
                collide_polytopes(&pa, pose_a, &pb, pose_b, margin, &mut cache.sat)
            }
            _ => collide_convex(
                &Rounded::of(a)?,
                pose_a,
                &Rounded::of(b)?,
                pose_b,
                margin,
                &mut cache.normal_local,
            ),
        },
    }
}

/// Whether the tight boxes of the two shapes (`shape_aabb`) are farther apart than `margin` along
/// a world axis, so the shapes are too and have no contact. Taken by two capsules, whose segments'
/// closest points cost several times the boxes: in a pile of ragdolls, most limb pairs whose fat
/// boxes overlap end here. Not before GJK: a pair turned away keeps a stale start direction
/// (`collide_convex`'s `warm_dir`), the ragdolls' results then differed from round-off on, and
/// over eleven nearby damping ratios their largest joint separation came out higher (median
/// 6.35 cm against 5.7), not told apart from their chaos but not worth the risk for a narrow phase
/// 5% faster. Spheres' closed forms are as cheap as the boxes, and polytope pairs keep their
/// separating axis in their cache even while apart.
fn bounds_apart(a: &Shape, pose_a: &Transform, b: &Shape, pose_b: &Transform, margin: f64) -> bool {
    shape_aabb(a, pose_a).gap(&shape_aabb(b, pose_b)) > margin
}

fn polytope(shape: &Shape) -> Option<Polytope<'_>> {
    match shape {
        Shape::Cuboid(c) => Some(Polytope::Cuboid { half_extents: c.half_extents }),
        Shape::ConvexHull(h) => Some(Polytope::Hull(h)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::DQuat;
    use crate::scenes::rng::SplitMix64;
    use crate::shape::{Capsule, Cone, ConvexHull, Cuboid, Cylinder, Sphere};

    fn unit(rng: &mut SplitMix64) -> DVec3 {
        DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)).normalize()
    }

    fn turn(rng: &mut SplitMix64) -> DQuat {
        DQuat::from_axis_angle(unit(rng), rng.range(0.0, 6.3))
    }

    /// The hull of ten points 0.1-0.25 from the origin in random directions.
    fn random_hull(rng: &mut SplitMix64) -> Shape {
        let points: Vec<DVec3> = (0..10).map(|_| unit(rng) * rng.range(0.1, 0.25)).collect();
        Shape::ConvexHull(ConvexHull::new(&points).expect("a hull"))
    }

    /// The bounding-ball early out never drops a contact: over random hulls and boxes brought
    /// to about the sum of their radii from random directions, every pair it turns away also
    /// gets no manifold from the separating-axis test run from a fresh cache. Both outcomes
    /// occur, and some pairs just within reach touch.
    #[test]
    fn the_bounding_ball_early_out_drops_no_contact() {
        let mut rng = SplitMix64::new(11);
        let mut shapes = Vec::new();
        for k in 0..12 {
            shapes.push(if k % 4 == 0 {
                let h = DVec3::new(rng.range(0.05, 0.3), rng.range(0.05, 0.3), rng.range(0.05, 0.3));
                Shape::Cuboid(Cuboid::new(h).expect("positive half extents"))
            } else {
                random_hull(&mut rng)
            });
        }
        let radius = |s: &Shape| polytope(s).expect("a polytope").bounding_radius();
        let (mut turned_away, mut touching_within_reach) = (0, 0);
        for trial in 0..4000 {
            let (a, b) = (&shapes[trial % shapes.len()], &shapes[(trial * 7 + 3) % shapes.len()]);
            let margin = rng.range(0.0, 0.1);
            let pose_a = Transform::new(DVec3::new(1.0, -2.0, 0.5), turn(&mut rng));
            let reach = radius(a) + radius(b) + margin;
            let offset = unit(&mut rng) * reach * rng.range(0.6, 1.3);
            let pose_b = Transform::new(pose_a.translation + offset, turn(&mut rng));
            let found = collide(a, &pose_a, b, &pose_b, margin, &mut PairCache::default());
            let (pa, pb) = (polytope(a).expect("a polytope"), polytope(b).expect("a polytope"));
            let full = collide_polytopes(&pa, &pose_a, &pb, &pose_b, margin, &mut SatCache::default());
            if offset.length() > reach {
                turned_away += 1;
                assert!(found.is_none(), "trial {trial}: a pair out of reach got a manifold");
                assert!(full.is_none(), "trial {trial}: the early out dropped a contact");
            } else {
                assert_eq!(found.is_some(), full.is_some(), "trial {trial}");
                touching_within_reach += usize::from(found.is_some() && offset.length() > 0.9 * reach);
            }
        }
        assert!(turned_away > 500, "{turned_away} pairs turned away");
        assert!(touching_within_reach > 0, "no pair touched near the edge of reach");
    }

    /// The boxes' test never drops a contact: over random pairs of capsules, cylinders, cones,
    /// boxes, hulls and a sphere (the pairs that go to GJK or to two segments' closest points),
    /// brought to about where their boxes part from random directions, every pair it calls apart
    /// gets no manifold from the query itself. Both outcomes occur, and some pairs the
    /// bounding balls would not turn away are turned away.
    #[test]
    fn the_bounding_box_early_out_drops_no_contact() {
        let mut rng = SplitMix64::new(23);
        let mut shapes = Vec::new();
        for k in 0..15 {
            let (r, h) = (rng.range(0.03, 0.2), rng.range(0.05, 0.4));
            shapes.push(match k % 5 {
                0 => Shape::Capsule(Capsule::new(r, h).expect("a capsule")),
                1 => Shape::Cylinder(Cylinder::new(r, h).expect("a cylinder")),
                2 => Shape::Cone(Cone::new(r, h).expect("a cone")),
                3 => Shape::Cuboid(Cuboid::new(DVec3::new(r, h, 0.5 * (r + h))).expect("a box")),
                _ => random_hull(&mut rng),
            });
        }
        shapes.push(Shape::Sphere(Sphere::new(0.1).expect("a sphere")));
        let reach = |s: &Shape| Rounded::of(s).expect("convex").bounding_radius();
        let (mut turned_away, mut kept, mut touching, mut inside_balls) = (0, 0, 0, 0);
        for trial in 0..6000 {
            let (a, b) = (&shapes[trial % shapes.len()], &shapes[(trial * 7 + 3) % shapes.len()]);
            let (a, b) = if kind_rank(a) <= kind_rank(b) { (a, b) } else { (b, a) };
            let margin = rng.range(0.0, 0.1);
            let pose_a = Transform::new(DVec3::new(1.0, -2.0, 0.5), turn(&mut rng));
            let offset = unit(&mut rng) * (reach(a) + reach(b) + margin) * rng.range(0.3, 1.1);
            let pose_b = Transform::new(pose_a.translation + offset, turn(&mut rng));
            let full = match (a, b) {
                (Shape::Capsule(ca), Shape::Capsule(cb)) => capsule_capsule(ca, &pose_a, cb, &pose_b, margin),
                (Shape::Sphere(_), Shape::Sphere(_) | Shape::Capsule(_) | Shape::Cuboid(_)) => continue,
                _ if polytope(a).is_some() && polytope(b).is_some() => continue,
                _ => {
                    let (ra, rb) = (Rounded::of(a).expect("convex"), Rounded::of(b).expect("convex"));
                    collide_convex(&ra, &pose_a, &rb, &pose_b, margin, &mut DVec3::default())
                }
            };
            let found = collide(a, &pose_a, b, &pose_b, margin, &mut PairCache::default());
            if bounds_apart(a, &pose_a, b, &pose_b, margin) {
                turned_away += 1;
                inside_balls += usize::from(offset.length() < reach(a) + reach(b) + margin);
                assert!(full.is_none(), "trial {trial}: the early out dropped a contact");
                assert!(found.is_none(), "trial {trial}");
            } else {
                kept += 1;
                touching += usize::from(full.is_some());
                assert_eq!(found.is_some(), full.is_some(), "trial {trial}");
            }
        }
        assert!(turned_away > 500 && kept > 500, "{turned_away} turned away, {kept} kept");
        assert!(touching > 100, "{touching} pairs touching");
        assert!(inside_balls > 100, "{inside_balls} pairs within the bounding balls turned away");
    }
}
