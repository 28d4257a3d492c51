//! Contact manifolds: the normal and up to four points through which two shapes touch.
//!
//! Four points suffice for a rigid contact patch: a solver needs the patch's support polygon, not
//! every vertex of it, and four well-spread points (deepest first, then the farthest, then the
//! largest triangle, then the largest quadrilateral) span it closely. Each point carries a feature
//! id naming the pair of features that made it, so the solver can match points between steps and
//! warm-start them with last step's impulses.

use smallvec::{smallvec, SmallVec};

use crate::math::{DVec3, Transform};

/// One contact point. `separation` is measured along the manifold normal: negative means the
/// shapes overlap by that much at this point.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactPoint {
    /// Midpoint between the two surfaces, world frame.
    pub point_world: DVec3,
    /// Signed distance between the surfaces along the normal (negative = penetration), m.
    pub separation: f64,
    /// Which features (faces, edges, vertices of A and B) produced this point; stable while the
    /// same features touch, so it survives small motions.
    pub feature_id: u32,
    /// The point on A's surface, in A's local frame.
    pub local_point_a: DVec3,
    /// The point on B's surface, in B's local frame.
    pub local_point_b: DVec3,
}

impl ContactPoint {
    /// A contact at `mid_world` with the surfaces `separation` apart along `normal_world`.
    pub fn new(
        pose_a: &Transform,
        pose_b: &Transform,
        normal_world: DVec3,
        mid_world: DVec3,
        separation: f64,
        feature_id: u32,
    ) -> ContactPoint {
        let on_a = mid_world - normal_world * (0.5 * separation);
        let on_b = mid_world + normal_world * (0.5 * separation);
        ContactPoint {
            point_world: mid_world,
            separation,
            feature_id,
            local_point_a: pose_a.inverse_transform_point(on_a),
            local_point_b: pose_b.inverse_transform_point(on_b),
        }
    }
}

/// The contact between two shapes: a unit normal from A towards B and 1–4 points.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Manifold {
    /// Unit normal, world frame, pointing from A towards B.
    pub normal_world: DVec3,
    points: [ContactPoint; 4],
    len: usize,
}

/// The most points a manifold holds.
pub const MAX_POINTS: usize = 4;

impl Manifold {
    pub fn new(normal_world: DVec3) -> Manifold {
        Manifold { normal_world, points: [ContactPoint::default(); MAX_POINTS], len: 0 }
    }

    pub fn points(&self) -> &[ContactPoint] {
        &self.points[..self.len]
    }

    pub fn points_mut(&mut self) -> &mut [ContactPoint] {
        &mut self.points[..self.len]
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Adds a point; returns false (and drops it) when the manifold is full.
    pub fn push(&mut self, point: ContactPoint) -> bool {
        if self.len == MAX_POINTS {
            return false;
        }
        self.points[self.len] = point;
        self.len += 1;
        true
    }

    /// The smallest separation (deepest penetration) of the points.
    pub fn min_separation(&self) -> f64 {
        self.points().iter().fold(f64::INFINITY, |m, p| m.min(p.separation))
    }

    /// The same contact seen with A and B swapped: the normal flips, the points stay.
    pub fn flipped(&self) -> Manifold {
        let mut out = *self;
        out.normal_world = -self.normal_world;
        for p in &mut out.points[..out.len] {
            std::mem::swap(&mut p.local_point_a, &mut p.local_point_b);
        }
        out
    }

    /// A manifold of the best four of `candidates` (see [`reduce`]), or `None` if there are none.
    pub fn from_candidates(normal_world: DVec3, candidates: &[ContactPoint]) -> Option<Manifold> {
        if candidates.is_empty() {
            return None;
        }
        let mut m = Manifold::new(normal_world);
        for i in reduce(candidates, normal_world) {
            m.push(candidates[i]);
        }
        Some(m)
    }
}

/// Indices of at most four points of `candidates` that span the contact patch: the deepest point,
/// the point farthest from it, the point making the largest triangle with those two, and the point
/// adding the most area outside that triangle. Areas are measured in the plane normal to `normal`.
/// Ties keep the earlier candidate, so the choice is deterministic.
pub fn reduce(candidates: &[ContactPoint], normal: DVec3) -> SmallVec<[usize; MAX_POINTS]> {
    let n = candidates.len();
    if n <= MAX_POINTS {
        return (0..n).collect();
    }
    let pos = |i: usize| candidates[i].point_world;
    let mut first = 0;
    for i in 1..n {
        if candidates[i].separation < candidates[first].separation {
            first = i;
        }
    }
    let along = |d: DVec3| d - normal * normal.dot(d);
    let argmax = |score: &dyn Fn(usize) -> f64| {
        let mut best = (usize::MAX, 0.0);
        for i in 0..n {
            let s = score(i);
            if s > best.1 {
                best = (i, s);
            }
        }
        best.0
    };
    let second = argmax(&|i| along(pos(i) - pos(first)).length_squared());
    if second == usize::MAX {
        return smallvec![first];
    }
    let signed_area = |a: DVec3, b: DVec3, c: DVec3| (b - a).cross(c - a).dot(normal);
    let third = argmax(&|i| signed_area(pos(first), pos(second), pos(i)).abs());
    if third == usize::MAX {
        return smallvec![first, second];
    }
    // Wind the triangle counter-clockwise about the normal; a point outside edge (p, q) has
    // negative signed area there, and that area is what it adds to the patch.
    let tri = if signed_area(pos(first), pos(second), pos(third)) > 0.0 {
        [first, second, third]
    } else {
        [first, third, second]
    };
    let fourth = argmax(&|i| {
        (0..3).fold(0.0_f64, |m, k| m.max(-signed_area(pos(tri[k]), pos(tri[(k + 1) % 3]), pos(i))))
    });
    if fourth == usize::MAX {
        smallvec![first, second, third]
    } else {
        smallvec![first, second, third, fourth]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduction_keeps_the_deepest_and_the_corners() {
        // A 5x5 grid on z = 0 with one deep point in the middle: the deepest plus the corners win.
        let mut c = Vec::new();
        for i in 0..5 {
            for j in 0..5 {
                let sep = if (i, j) == (2, 2) { -0.2 } else { -0.01 };
                let p = DVec3::new(i as f64, j as f64, 0.0);
                c.push(ContactPoint { point_world: p, separation: sep, ..Default::default() });
            }
        }
        let idx = reduce(&c, DVec3::Z);
        assert_eq!(idx.len(), 4);
        assert_eq!(c[idx[0]].point_world, DVec3::new(2.0, 2.0, 0.0));
        for &i in &idx[1..] {
            let p = c[i].point_world;
            assert!(p.x == 0.0 || p.x == 4.0, "{p}");
            assert!(p.y == 0.0 || p.y == 4.0, "{p}");
        }
    }
}
