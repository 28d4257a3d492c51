//! Convex shape against static triangles (a triangle mesh or a height field).
//!
//! 1. **Candidates.** The convex shape's bounds, in the mesh frame and fattened by the margin,
//!    query the mesh's BVH (or the height field's cells).
//! 2. **Per triangle.** Triangles are one-sided: a triangle is skipped when the shape's centre lies
//!    behind its plane, or when the shape's lowest point along `−n_T` is more than the margin
//!    above it (the triangle's plane separates them). A triangle whose edges are all internal
//!    (flat or concave neighbours) can only have its face normal, so it goes straight to the face
//!    contact, and so does a triangle the shape's core lies wholly above with its lowest point
//!    over the triangle (that point and its foot are then the closest pair, along the face
//!    normal), and a triangle whose convex edges bend too little for the rule to allow any normal
//!    outside the face cone ([`super::triangle::allows_only_face_normals`]). A triangle with a
//!    convex or boundary edge otherwise first runs GJK/EPA between the triangle and the shape's
//!    core; if the normal found passes the internal-edge rule (see [`super::triangle`]) and is
//!    not the face normal, the contact is the convex–convex manifold of the triangle and the
//!    shape (edge or vertex contact). Otherwise it is the face contact: the shape's feature
//!    facing `−n_T` clipped to the triangle, separations from its plane (with a cylinder's or
//!    cone's true lowest point added when its cap polygon's corners sit higher).
//! 3. **One manifold.** The normal is that of the deepest candidate; candidates within 30° of it
//!    are kept with their separations measured along it, the others dropped. Duplicates (a box
//!    corner over an edge shared by two triangles) are merged by feature id, and the rest reduced
//!    to four points: the deepest (among near-ties, the one farthest from the patch centre, so a
//!    box flat on the floor keeps its corners — unless that is more than 1 µm shallower than the
//!    deepest), then the farthest from it, the largest triangle, the largest quadrilateral.
//!
//! Feature ids: a point that is a vertex of the shape's feature (a box corner) is named by the
//! shape's feature alone, so it keeps its id — and its warm-start impulse — as it slides from one
//! triangle to the next. Points made by clipping against a triangle's edges include the triangle
//! index, so they are stable while the same triangle is touched.

use super::aabb::{shape_aabb, Aabb};
use super::clip::{clip_segment, clip_to_face, ClipVertex};
use super::convex_contact::collide_convex;
use super::epa::epa;
use super::feature::{
    is_round_cap, supporting_feature, CAP_MISS, EDGE, EDGE_SIN_TOLERANCE, FACE_COS_TOLERANCE, VERTEX,
};
use super::gjk::{gjk_within, ConvexPair};
use super::manifold::{ContactPoint, Manifold};
use super::support::{Core, Rounded};
use super::triangle::{normal_allowed, TriangleSource};
use crate::math::{DMat3, DVec3, Transform};
use crate::shape::Shape;
use smallvec::{smallvec, SmallVec};

/// Candidates whose normal is within this cosine (30°) of the dominant one join the manifold.
const MERGE_COS: f64 = 0.866;
/// Separations within this distance (m) of the deepest count as tied for the first point.
const TIE_DISTANCE: f64 = 1e-5;
/// The tied first point may be at most this much (m) shallower than the deepest candidate.
const DEPTH_SLACK: f64 = 1e-6;
/// Points closer than this (m) to the patch spanned so far add nothing to it.
const DISTINCT: f64 = 1e-6;

/// The clip tag of a round cap's true lowest point: below 0x8000 (an original point, named by the
/// shape's feature alone) and above any cap corner's index.
const LOWEST_TAG: u16 = 0x7FFF;

/// The candidates of one pair, on the stack up to 32 (a hull across four triangles can clip to
/// more than 16).
type Candidates = SmallVec<[Candidate; 32]>;

/// A contact point before reduction, in the mesh's local frame.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
struct Candidate {
    normal: DVec3,
    /// The point on the convex shape's surface.
    on_b: DVec3,
    separation: f64,
    id: u32,
}

/// Contact of static triangles `source` (A, at `pose_a`) with the convex `shape` (B). The normal
/// points from the triangles to the shape. `None` when nothing is within `margin`.
pub fn collide_triangles_convex<S: TriangleSource + ?Sized>(
    source: &S,
    pose_a: &Transform,
    shape: &Shape,
    pose_b: &Transform,
    margin: f64,
) -> Option<Manifold> {
    let rounded = Rounded::of(shape)?;
    let b_in_a = pose_a.inverse().mul_transform(pose_b);
    let query: Aabb = shape_aabb(shape, &b_in_a).fattened(margin);
    // On the stack for the usual handful of triangles and candidates (a step over a terrain
    // then allocates nothing).
    let mut triangles: SmallVec<[u32; 32]> = SmallVec::new();
    source.query(&query, &mut |t| triangles.push(t));
    let rot = DMat3::from_quat(b_in_a.rotation);
    let frame = Frame { rot, rot_t: rot.transpose() };
    let mut candidates = Candidates::new();
    for &t in &triangles {
        triangle_contact(source, t, &rounded, &b_in_a, &frame, margin, &mut candidates);
    }
    build_manifold(&mut candidates, pose_a, pose_b, margin)
}

/// The shape's rotation in the mesh frame as matrices (cheaper than quaternions for the many
/// support queries per triangle).
struct Frame {
    rot: DMat3,
    rot_t: DMat3,
}

/// Appends the contact candidates of triangle `t` with the shape (at `b_in_a`, mesh frame).
#[allow(clippy::too_many_arguments)]
fn triangle_contact<S: TriangleSource + ?Sized>(
    source: &S,
    t: u32,
    shape: &Rounded,
    b_in_a: &Transform,
    frame: &Frame,
    margin: f64,
    out: &mut Candidates,
) {
    let v = source.triangle(t);
    let n_t = source.triangle_normal(t);
    if n_t == DVec3::ZERO || n_t.dot(b_in_a.translation - v[0]) < 0.0 {
        return; // degenerate, or the shape's centre is behind the triangle
    }
    // Farthest point of the core along a mesh-frame direction, in the mesh frame.
    let support = |dir: DVec3| b_in_a.translation + frame.rot * shape.core.support_local(frame.rot_t * dir);
    let down_local = frame.rot_t * -n_t;
    let lowest = support(-n_t);
    let height = n_t.dot(lowest - v[0]);
    if height - shape.radius > margin {
        return;
    }
    // The triangle's edges as separating axes: the triangle lies inside each edge's in-plane
    // half-space, so a shape entirely beyond one (by more than the margin) cannot touch it.
    for k in 0..3 {
        let u = (v[(k + 1) % 3] - v[k]).cross(n_t);
        if u.dot(support(-u) - v[k]) > (shape.radius + margin) * u.length() {
            return;
        }
    }
    // The core wholly above the triangle's plane with its lowest point over the triangle: that
    // point and its foot on the triangle are the closest pair (no point of the core is lower, and
    // the foot is on the triangle), so the normal is the face normal and GJK would only confirm
    // it — the face contact below, whatever the edges (which are then not looked up: a height
    // field works them out per visit).
    let face_only = height > 0.0 && over_triangle(lowest, &v, n_t);
    if !face_only {
        let edges = source.edges(t, &v, n_t);
        if edges.sharp
            && !edges.only_face_normals
            && edge_contact(t, &v, n_t, &edges.bends, shape, b_in_a, margin, out)
        {
            return;
        }
    }
    face_contact(t, &v, n_t, shape, b_in_a, down_local, margin, out);
}

/// Does `p` lie over the triangle `v` (its foot on the plane strictly inside the triangle,
/// corners counter-clockwise about `n_t`)?
fn over_triangle(p: DVec3, v: &[DVec3; 3], n_t: DVec3) -> bool {
    (0..3).all(|k| (v[(k + 1) % 3] - v[k]).cross(p - v[k]).dot(n_t) > 0.0)
}

/// GJK/EPA between the triangle and the shape. If the normal is allowed by the internal-edge rule
/// and is not the face normal, appends the convex–convex manifold and returns true; returns false
/// when the face contact should be used instead (or nothing is within reach — the face contact
/// then finds nothing either).
#[allow(clippy::too_many_arguments)]
fn edge_contact(
    t: u32,
    v: &[DVec3; 3],
    n_t: DVec3,
    bends: &[Option<f64>; 3],
    shape: &Rounded,
    b_in_a: &Transform,
    margin: f64,
    out: &mut Candidates,
) -> bool {
    // Work relative to the triangle's centroid: small coordinates, small round-off.
    let centroid = (v[0] + v[1] + v[2]) / 3.0;
    let tri = Rounded { core: Core::Triangle(v.map(|p| p - centroid)), radius: 0.0 };
    let tri_pose = Transform::new(centroid, crate::math::DQuat::IDENTITY);
    let pair = ConvexPair::new(tri.core, &tri_pose, shape.core, b_in_a);
    let g = gjk_within(&pair, n_t, shape.radius + margin);
    if !g.overlapping && g.distance > shape.radius + margin {
        return true; // out of reach: no contact from this triangle at all
    }
    let normal = if !g.overlapping && g.distance > 1e-9 * pair.scale() {
        (g.point_b - g.point_a) / g.distance
    } else {
        match epa(&pair, &g.simplex) {
            Some(e) => e.normal,
            None => return false,
        }
    };
    if normal.dot(n_t) >= FACE_COS_TOLERANCE || !normal_allowed(v, n_t, bends, normal) {
        return false;
    }
    let mut warm = normal;
    let Some(m) = collide_convex(&tri, &tri_pose, shape, b_in_a, margin, &mut warm) else {
        return true;
    };
    // The manifold may have come out as a face contact after all (its own feature tolerance).
    if !normal_allowed(v, n_t, bends, m.normal_world) {
        return false;
    }
    for p in m.points() {
        out.push(Candidate {
            normal: m.normal_world,
            on_b: p.point_world + m.normal_world * (0.5 * p.separation),
            separation: p.separation,
            id: triangle_id(t, p.feature_id),
        });
    }
    true
}

/// The face contact: the shape's feature facing `−n_t` clipped to the triangle.
#[allow(clippy::too_many_arguments)]
fn face_contact(
    t: u32,
    v: &[DVec3; 3],
    n_t: DVec3,
    shape: &Rounded,
    b_in_a: &Transform,
    down_local: DVec3,
    margin: f64,
    out: &mut Candidates,
) {
    // Balls and capsules: their feature is a point or a segment, clipped here without allocating
    // (the common case for characters and debris on terrain).
    match shape.core {
        Core::Point => return point_contact(v, n_t, b_in_a.translation, shape.radius, margin, 0, out),
        Core::Segment { half_height } => {
            let d = down_local.normalize_or_zero();
            let end = |z: f64| b_in_a.transform_point(DVec3::new(0.0, 0.0, z));
            if d.z.abs() > EDGE_SIN_TOLERANCE {
                let (z, code) = if d.z > 0.0 { (half_height, VERTEX | 1) } else { (-half_height, VERTEX) };
                return point_contact(v, n_t, end(z), shape.radius, margin, u32::from(code) << 15, out);
            }
            let mut seg =
                Some([ClipVertex::original(end(-half_height), 0), ClipVertex::original(end(half_height), 1)]);
            for k in 0..3 {
                let side = (v[(k + 1) % 3] - v[k]).cross(n_t);
                seg = seg.and_then(|sg| clip_segment(sg, side, side.dot(v[k]), k));
            }
            let code = u32::from(EDGE);
            for c in seg.into_iter().flatten() {
                let height = n_t.dot(c.point - v[0]);
                if height - shape.radius <= margin {
                    out.push(Candidate {
                        normal: n_t,
                        on_b: c.point - n_t * shape.radius,
                        separation: height - shape.radius,
                        id: feature_id(t, code, c.tag),
                    });
                }
            }
            return;
        }
        _ => {}
    }
    let feature = supporting_feature(&shape.core, down_local);
    let incident: SmallVec<[DVec3; 16]> = feature.points.iter().map(|&p| b_in_a.transform_point(p)).collect();
    let code = u32::from(feature.code);
    let mut clipped = clip_to_face(v, n_t, &incident, margin + shape.radius);
    if is_round_cap(&shape.core, &feature) {
        // The cap polygon's corners can sit above the rim's true lowest point (0.44 mm for a 2.2 m
        // disc tipped 1.2°): when that point lies over this triangle and is lower than every
        // clipped point, it is a candidate too. Its tag names the shape alone, so the triangles
        // sharing an edge it lies on give one point, not two. (Not when a corner is as low, so a
        // cylinder standing flat keeps its fixed corners.)
        let lowest = b_in_a.transform_point(shape.core.support_local(down_local));
        let deepest = clipped.iter().map(|c| c.separation).fold(f64::INFINITY, f64::min);
        for mut c in clip_to_face(v, n_t, &[lowest], margin + shape.radius) {
            if c.separation < deepest - CAP_MISS {
                c.tag = LOWEST_TAG;
                clipped.push(c);
            }
        }
    }
    for c in clipped {
        let id = feature_id(t, code, c.tag);
        out.push(Candidate {
            normal: n_t,
            on_b: c.point - n_t * shape.radius,
            separation: c.separation - shape.radius,
            id,
        });
    }
}

/// A ball centre or a capsule end `c` (mesh frame) over the triangle, or nothing.
fn point_contact(
    v: &[DVec3; 3],
    n_t: DVec3,
    c: DVec3,
    radius: f64,
    margin: f64,
    id: u32,
    out: &mut Candidates,
) {
    let inside = (0..3).all(|k| (v[(k + 1) % 3] - v[k]).cross(c - v[k]).dot(n_t) >= 0.0);
    let height = n_t.dot(c - v[0]);
    if inside && height - radius <= margin {
        out.push(Candidate { normal: n_t, on_b: c - n_t * radius, separation: height - radius, id });
    }
}

/// The id of a face-contact point with clip tag `tag` of the shape's feature `code`: an original
/// vertex of the feature (a box corner) is named by the shape alone, so it keeps its id from one
/// triangle to the next; a point cut by a triangle edge also names the triangle.
#[inline]
fn feature_id(t: u32, code: u32, tag: u16) -> u32 {
    if tag < 0x8000 {
        (code << 15) | u32::from(tag)
    } else {
        triangle_id(t, (code << 16) | u32::from(tag))
    }
}

/// An id that names triangle `t` and a local feature id (top bit set, so it never equals an id
/// that names the shape's feature alone).
#[inline]
fn triangle_id(t: u32, local: u32) -> u32 {
    0x8000_0000 | ((t.wrapping_mul(0x9E37_79B1) ^ local.rotate_left(7)) & 0x7FFF_FFFF)
}

/// One manifold from all candidates (mesh frame) — see the module docs.
/// `candidates` are taken by reference: two kilobytes on the stack, copied whole when moved.
fn build_manifold(
    candidates: &mut Candidates,
    pose_a: &Transform,
    pose_b: &Transform,
    margin: f64,
) -> Option<Manifold> {
    let deepest = candidates.iter().enumerate().min_by(|x, y| x.1.separation.total_cmp(&y.1.separation))?.0;
    let normal = candidates[deepest].normal;
    candidates.retain_mut(|c| {
        let cos = c.normal.dot(normal);
        c.separation *= cos;
        cos >= MERGE_COS && c.separation <= margin
    });
    // Merge duplicates: keep the deepest point of each id (stable sort: deterministic order).
    candidates.sort_by(|x, y| x.id.cmp(&y.id).then(x.separation.total_cmp(&y.separation)));
    candidates.dedup_by_key(|c| c.id);
    let normal_world = pose_a.rotation * normal;
    let mut m = Manifold::new(normal_world);
    for i in reduce(candidates, normal) {
        let c = candidates[i];
        let on_b = pose_a.transform_point(c.on_b);
        let mid = on_b - normal_world * (0.5 * c.separation);
        m.push(ContactPoint::new(pose_a, pose_b, normal_world, mid, c.separation, c.id));
    }
    (!m.is_empty()).then_some(m)
}

/// Up to four candidates spanning the patch (see the module docs); areas in the plane normal to
/// `normal`. Candidates that add nothing to the patch are dropped even when there are few, so a
/// capsule lying across several triangles keeps just its two ends.
fn reduce(c: &[Candidate], normal: DVec3) -> SmallVec<[usize; 4]> {
    let n = c.len();
    if n <= 1 {
        return (0..n).collect();
    }
    let flat = |d: DVec3| d - normal * normal.dot(d);
    let min_sep = c.iter().fold(f64::INFINITY, |m, p| m.min(p.separation));
    let centre = c.iter().map(|p| p.on_b).sum::<DVec3>() / n as f64;
    // Scores must beat `floor` to count: points that add nothing (inside the patch so far, or on
    // a line with it) are left out even when there are four or fewer.
    let argmax_above = |floor: f64, score: &dyn Fn(usize) -> f64| {
        let mut best = (usize::MAX, floor);
        for i in 0..n {
            let s = score(i);
            if s > best.1 {
                best = (i, s);
            }
        }
        best.0
    };
    let argmax = |score: &dyn Fn(usize) -> f64| argmax_above(0.0, score);
    let tied = argmax(&|i| {
        if c[i].separation <= min_sep + TIE_DISTANCE {
            1.0 + flat(c[i].on_b - centre).length_squared()
        } else {
            0.0
        }
    });
    // The tie must not hide depth from the solver: a point deeper than the tied choice by more
    // than `DEPTH_SLACK` (a round cap's true lowest point, a few µm below the cap polygon's
    // corners, which may be farther out) leads instead.
    let deepest = (0..n).min_by(|&i, &j| c[i].separation.total_cmp(&c[j].separation)).unwrap_or(tied);
    let first = if c[tied].separation > c[deepest].separation + DEPTH_SLACK { deepest } else { tied };
    let p = |i: usize| c[i].on_b;
    let second = argmax_above(DISTINCT * DISTINCT, &|i| flat(p(i) - p(first)).length_squared());
    if second == usize::MAX {
        return smallvec![first];
    }
    let area = |a: DVec3, b: DVec3, q: DVec3| (b - a).cross(q - a).dot(normal);
    let min_area = DISTINCT * flat(p(second) - p(first)).length();
    let third = argmax_above(min_area, &|i| area(p(first), p(second), p(i)).abs());
    if third == usize::MAX {
        return smallvec![first, second];
    }
    let tri = if area(p(first), p(second), p(third)) > 0.0 {
        [first, second, third]
    } else {
        [first, third, second]
    };
    let fourth = argmax_above(min_area, &|i| {
        (0..3).fold(0.0_f64, |m, k| m.max(-area(p(tri[k]), p(tri[(k + 1) % 3]), p(i))))
    });
    if fourth == usize::MAX {
        smallvec![first, second, third]
    } else {
        smallvec![first, second, third, fourth]
    }
}
