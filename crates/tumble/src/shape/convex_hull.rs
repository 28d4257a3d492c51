//! A convex polyhedron built from a point cloud by quickhull.
//!
//! The hull keeps what the narrow phase needs: vertices, polygonal faces (coplanar triangles merged,
//! so the hull of a box's corners has 6 quads), outward face planes, and the unique edges with their
//! two adjacent faces (the Gauss-map arcs the separating-axis test prunes edge pairs with).
//!
//! Quickhull (Barber, Dobkin, Huhdanpaa 1996): start from a tetrahedron of extreme points; every
//! face owns the points in front of it ("outside set"); repeatedly take a face's farthest point,
//! find the connected faces it can see, replace them by a fan from the horizon to the point, and
//! hand the orphaned points to the new faces. Points within `eps` of a plane count as on it, which
//! is what makes nearly-coplanar input produce a few merged faces instead of slivers.

use std::collections::HashMap;

use crate::math::{is_finite_vec, DVec3};

/// Why a point set has no usable convex hull.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum HullError {
    #[error("convex hull needs at least 4 points, got {count}")]
    TooFewPoints { count: usize },
    #[error("convex hull point {index} is not finite: ({x}, {y}, {z})")]
    NonFinitePoint { index: usize, x: f64, y: f64, z: f64 },
    #[error("convex hull points all coincide (extent {extent}); a hull needs volume")]
    Coincident { extent: f64 },
    #[error("convex hull points are collinear: they span a line, not a volume")]
    Collinear,
    #[error("convex hull points are coplanar: they span a plane, not a volume")]
    Coplanar,
    #[error("convex hull construction failed: {reason} (the input is numerically degenerate)")]
    Degenerate { reason: &'static str },
}

/// A polygonal face of a hull, in the hull's local frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HullFace {
    /// Outward unit normal.
    pub normal: DVec3,
    /// Plane offset: points `x` of the face satisfy `normal · x = offset`.
    pub offset: f64,
    /// Indices into the hull's vertices, counter-clockwise seen from outside.
    pub vertices: Vec<u32>,
}

/// An edge of a hull with its two faces. `faces[0]` walks it `vertices[0] → vertices[1]`,
/// `faces[1]` walks it the other way, so `faces[0].normal × faces[1].normal` points along
/// `vertices[1] − vertices[0]`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HullEdge {
    pub vertices: [u32; 2],
    pub faces: [u32; 2],
}

/// A convex polyhedron in its local frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ConvexHull {
    vertices: Vec<DVec3>,
    faces: Vec<HullFace>,
    edges: Vec<HullEdge>,
    /// The vertex average: strictly inside, used to orient edge-pair axes outward.
    interior_point: DVec3,
    /// The farthest vertex's distance from the origin: the radius of the ball about the origin
    /// the hull stays in however it turns (speculative margins, spinning proxies, manifold reuse).
    bounding_radius: f64,
}

impl ConvexHull {
    /// The convex hull of `points` (local frame). Points inside the hull or on its faces are
    /// dropped; at least four finite points not all on one plane are needed.
    pub fn new(points: &[DVec3]) -> Result<ConvexHull, HullError> {
        if points.len() < 4 {
            return Err(HullError::TooFewPoints { count: points.len() });
        }
        if let Some((index, p)) = points.iter().enumerate().find(|(_, p)| !is_finite_vec(**p)) {
            return Err(HullError::NonFinitePoint { index, x: p.x, y: p.y, z: p.z });
        }
        let triangles = quickhull(points)?;
        let tolerances = Tolerances::of(points);
        let faces = merge_coplanar(points, &triangles, tolerances.merge)?;
        Self::from_polygons(points, faces)
    }

    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    pub fn faces(&self) -> &[HullFace] {
        &self.faces
    }

    pub fn edges(&self) -> &[HullEdge] {
        &self.edges
    }

    /// A point strictly inside the hull (the vertex average).
    pub fn interior_point(&self) -> DVec3 {
        self.interior_point
    }

    /// The radius of the smallest ball about the origin that holds the hull.
    pub fn bounding_radius(&self) -> f64 {
        self.bounding_radius
    }

    /// Index of the vertex farthest along `dir_local` (the lowest index on ties; 0 when no
    /// product is a number). (Four lanes of running maxima with selections in place of the
    /// branch gave the same answers but ran the convex pile's narrow phase about 5% slower.)
    pub fn support_index(&self, dir_local: DVec3) -> usize {
        let mut best = 0;
        let mut best_dot = f64::NEG_INFINITY;
        for (i, v) in self.vertices.iter().enumerate() {
            let d = v.dot(dir_local);
            if d > best_dot {
                best_dot = d;
                best = i;
            }
        }
        best
    }

    /// The faces fanned into outward-wound triangles (for mass properties and drawing).
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        for face in &self.faces {
            for k in 1..face.vertices.len() - 1 {
                out.push([face.vertices[0], face.vertices[k], face.vertices[k + 1]]);
            }
        }
        out
    }

    /// Builds the hull from polygon loops given as indices into `points`: drops unused points,
    /// fits planes, derives the edge list and checks the result is a closed polyhedron.
    fn from_polygons(points: &[DVec3], loops: Vec<Vec<u32>>) -> Result<ConvexHull, HullError> {
        // Keep used points in input order so the numbering is deterministic.
        let mut remap = vec![u32::MAX; points.len()];
        for l in &loops {
            for &v in l {
                remap[v as usize] = 0;
            }
        }
        let mut vertices = Vec::new();
        for (i, slot) in remap.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = vertices.len() as u32;
                vertices.push(points[i]);
            }
        }
        let mut faces = Vec::with_capacity(loops.len());
        for l in loops {
            let vs: Vec<u32> = l.iter().map(|&v| remap[v as usize]).collect();
            // Newell's method: robust normal of a (nearly) planar polygon.
            // Sums taken relative to the first vertex keep round-off small far from the origin.
            let origin = vertices[vs[0] as usize];
            let mut n = DVec3::ZERO;
            let mut centre = DVec3::ZERO;
            for k in 0..vs.len() {
                let a = vertices[vs[k] as usize] - origin;
                let b = vertices[vs[(k + 1) % vs.len()] as usize] - origin;
                n += a.cross(b);
                centre += a;
            }
            centre = origin + centre / vs.len() as f64;
            let normal = n.try_normalize().ok_or(HullError::Degenerate { reason: "a face has no area" })?;
            faces.push(HullFace { normal, offset: normal.dot(centre), vertices: vs });
        }
        let mut owner: HashMap<(u32, u32), u32> = HashMap::new();
        for (f, face) in faces.iter().enumerate() {
            let n = face.vertices.len();
            for k in 0..n {
                let key = (face.vertices[k], face.vertices[(k + 1) % n]);
                if owner.insert(key, f as u32).is_some() {
                    return Err(HullError::Degenerate { reason: "an edge is used twice in one direction" });
                }
            }
        }
        let mut edges = Vec::new();
        for (f, face) in faces.iter().enumerate() {
            let n = face.vertices.len();
            for k in 0..n {
                let (a, b) = (face.vertices[k], face.vertices[(k + 1) % n]);
                if a < b {
                    let twin = *owner
                        .get(&(b, a))
                        .ok_or(HullError::Degenerate { reason: "the surface is not closed" })?;
                    edges.push(HullEdge { vertices: [a, b], faces: [f as u32, twin] });
                }
            }
        }
        if 2 * edges.len() != owner.len() {
            return Err(HullError::Degenerate { reason: "the surface is not closed" });
        }
        let euler = vertices.len() as i64 - edges.len() as i64 + faces.len() as i64;
        if euler != 2 {
            return Err(HullError::Degenerate { reason: "the surface is not a sphere (V - E + F != 2)" });
        }
        let interior_point = vertices.iter().copied().sum::<DVec3>() / vertices.len() as f64;
        let bounding_radius = vertices.iter().fold(0.0_f64, |m, v| m.max(v.length()));
        Ok(ConvexHull { vertices, faces, edges, interior_point, bounding_radius })
    }
}

/// Distances below which points count as on a plane, scaled to the input so that metres and
/// millimetres behave alike, and far-from-origin input keeps room for round-off.
#[derive(Clone, Copy, serde::Serialize, serde::Deserialize)]
struct Tolerances {
    /// A point must be this far in front of a face to be outside it.
    outside: f64,
    /// Triangles whose vertices are this close to a common plane merge into one face.
    merge: f64,
}

impl Tolerances {
    fn of(points: &[DVec3]) -> Tolerances {
        let (mut lo, mut hi) = (points[0], points[0]);
        let mut max_abs = 0.0_f64;
        for p in points {
            lo = lo.min(*p);
            hi = hi.max(*p);
            max_abs = max_abs.max(p.abs().max_element());
        }
        let extent = (hi - lo).length();
        let roundoff = 1e-14 * max_abs;
        Tolerances { outside: 1e-10 * extent + roundoff, merge: 1e-7 * extent + 10.0 * roundoff }
    }
}

struct Tri {
    v: [u32; 3],
    normal: DVec3,
    offset: f64,
    outside: Vec<u32>,
    alive: bool,
}

impl Tri {
    fn new(points: &[DVec3], v: [u32; 3]) -> Tri {
        let [a, b, c] = v.map(|i| points[i as usize]);
        let normal = (b - a).cross(c - a).normalize_or_zero();
        Tri { v, normal, offset: normal.dot(a), outside: Vec::new(), alive: true }
    }

    fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }
}

/// Quickhull proper: returns the hull's outward triangles as indices into `points`.
fn quickhull(points: &[DVec3]) -> Result<Vec<[u32; 3]>, HullError> {
    let eps = Tolerances::of(points).outside;
    let p = |i: u32| points[i as usize];

    // Initial simplex from extreme points: the widest axis pair, then the farthest point from
    // their line, then the farthest from their plane.
    let mut ext = [0u32; 6];
    for (i, q) in points.iter().enumerate() {
        for axis in 0..3 {
            if q[axis] < p(ext[2 * axis])[axis] {
                ext[2 * axis] = i as u32;
            }
            if q[axis] > p(ext[2 * axis + 1])[axis] {
                ext[2 * axis + 1] = i as u32;
            }
        }
    }
    let (mut i0, mut i1, mut widest) = (0, 0, -1.0);
    for axis in 0..3 {
        let d = p(ext[2 * axis]).distance(p(ext[2 * axis + 1]));
        if d > widest {
            (i0, i1, widest) = (ext[2 * axis], ext[2 * axis + 1], d);
        }
    }
    if widest <= eps {
        return Err(HullError::Coincident { extent: widest });
    }
    let dir = (p(i1) - p(i0)) / widest;
    let farthest = |score: &dyn Fn(DVec3) -> f64| {
        let mut best = (0u32, -1.0);
        for (i, q) in points.iter().enumerate() {
            let s = score(*q);
            if s > best.1 {
                best = (i as u32, s);
            }
        }
        best
    };
    let (i2, d2) = farthest(&|q| (q - p(i0)).cross(dir).length());
    if d2 <= eps {
        return Err(HullError::Collinear);
    }
    let n = (p(i1) - p(i0)).cross(p(i2) - p(i0)).normalize();
    let (i3, d3) = farthest(&|q| n.dot(q - p(i0)).abs());
    if d3 <= eps {
        return Err(HullError::Coplanar);
    }
    // Orient so that the fourth point lies behind the first face.
    let (i1, i2) = if n.dot(p(i3) - p(i0)) > 0.0 { (i2, i1) } else { (i1, i2) };

    let mut tris: Vec<Tri> = Vec::new();
    let mut edge_owner: HashMap<(u32, u32), usize> = HashMap::new();
    let add_tri = |tris: &mut Vec<Tri>, owner: &mut HashMap<(u32, u32), usize>, v: [u32; 3]| {
        let id = tris.len();
        for k in 0..3 {
            owner.insert((v[k], v[(k + 1) % 3]), id);
        }
        tris.push(Tri::new(points, v));
        id
    };
    for v in [[i0, i1, i2], [i0, i3, i1], [i1, i3, i2], [i2, i3, i0]] {
        add_tri(&mut tris, &mut edge_owner, v);
    }
    let simplex = [i0, i1, i2, i3];
    assign_outside(
        points,
        &mut tris,
        &[0, 1, 2, 3],
        (0..points.len() as u32).filter(|i| !simplex.contains(i)),
        eps,
    );

    let mut iterations = 0;
    let mut next_face = 0;
    while let Some(f) = (next_face..tris.len()).find(|&f| tris[f].alive && !tris[f].outside.is_empty()) {
        next_face = f; // earlier faces are finished or dead; they never gain points again
        iterations += 1;
        if iterations > points.len() + 8 {
            return Err(HullError::Degenerate { reason: "quickhull did not converge" });
        }
        let apex = *tris[f]
            .outside
            .iter()
            .max_by(|&&a, &&b| tris[f].distance(p(a)).total_cmp(&tris[f].distance(p(b))))
            .expect("outside set is not empty");
        let apex_pos = p(apex);

        // Flood the faces the apex sees, starting from `f`, so the visible region is connected.
        let mut visible = vec![f];
        let mut is_visible: HashMap<usize, bool> = HashMap::from([(f, true)]);
        let mut k = 0;
        while k < visible.len() {
            let t = visible[k];
            k += 1;
            for e in 0..3 {
                let (a, b) = (tris[t].v[e], tris[t].v[(e + 1) % 3]);
                let g = *edge_owner
                    .get(&(b, a))
                    .ok_or(HullError::Degenerate { reason: "quickhull lost an edge" })?;
                if let std::collections::hash_map::Entry::Vacant(slot) = is_visible.entry(g) {
                    let sees = tris[g].distance(apex_pos) > eps;
                    slot.insert(sees);
                    if sees {
                        visible.push(g);
                    }
                }
            }
        }
        let mut horizon = Vec::new();
        for &t in &visible {
            for e in 0..3 {
                let (a, b) = (tris[t].v[e], tris[t].v[(e + 1) % 3]);
                if !is_visible[&edge_owner[&(b, a)]] {
                    horizon.push((a, b));
                }
            }
        }
        let mut orphans = Vec::new();
        for &t in &visible {
            tris[t].alive = false;
            orphans.append(&mut tris[t].outside);
            for e in 0..3 {
                let key = (tris[t].v[e], tris[t].v[(e + 1) % 3]);
                if edge_owner.get(&key) == Some(&t) {
                    edge_owner.remove(&key);
                }
            }
        }
        let new_faces: Vec<usize> =
            horizon.iter().map(|&(a, b)| add_tri(&mut tris, &mut edge_owner, [a, b, apex])).collect();
        if new_faces.iter().any(|&t| tris[t].normal == DVec3::ZERO) {
            return Err(HullError::Degenerate { reason: "quickhull made a zero-area face" });
        }
        assign_outside(points, &mut tris, &new_faces, orphans.into_iter().filter(|&i| i != apex), eps);
    }
    Ok(tris.iter().filter(|t| t.alive).map(|t| t.v).collect())
}

/// Gives each point to the face it is farthest in front of; points behind all faces are inside.
fn assign_outside(
    points: &[DVec3],
    tris: &mut [Tri],
    faces: &[usize],
    candidates: impl Iterator<Item = u32>,
    eps: f64,
) {
    for i in candidates {
        let q = points[i as usize];
        let mut best = None;
        let mut best_d = eps;
        for &f in faces {
            let d = tris[f].distance(q);
            if d > best_d {
                best_d = d;
                best = Some(f);
            }
        }
        if let Some(f) = best {
            tris[f].outside.push(i);
        }
    }
}

/// Merges neighbouring triangles that lie on one plane into polygons, then removes vertices that
/// only two faces share (they sit in the middle of a straight edge). Returns CCW vertex loops.
fn merge_coplanar(points: &[DVec3], tris: &[[u32; 3]], tol: f64) -> Result<Vec<Vec<u32>>, HullError> {
    let p = |i: u32| points[i as usize];
    let mut owner: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, v) in tris.iter().enumerate() {
        for k in 0..3 {
            owner.insert((v[k], v[(k + 1) % 3]), t);
        }
    }
    let normal = |t: usize| {
        let [a, b, c] = tris[t].map(p);
        (b - a).cross(c - a).normalize_or_zero()
    };
    let mut group = vec![usize::MAX; tris.len()];
    let mut loops = Vec::new();
    for seed in 0..tris.len() {
        if group[seed] != usize::MAX {
            continue;
        }
        let g = loops.len();
        let n = normal(seed);
        let d = n.dot(p(tris[seed][0]));
        group[seed] = g;
        let mut members = vec![seed];
        let mut k = 0;
        while k < members.len() {
            let t = members[k];
            k += 1;
            for e in 0..3 {
                let (a, b) = (tris[t][e], tris[t][(e + 1) % 3]);
                let u = owner[&(b, a)];
                let coplanar =
                    normal(u).dot(n) > 0.99 && tris[u].iter().all(|&v| (n.dot(p(v)) - d).abs() <= tol);
                if group[u] == usize::MAX && coplanar {
                    group[u] = g;
                    members.push(u);
                }
            }
        }
        // The group's boundary: directed edges whose twin lies in another group.
        let mut next: HashMap<u32, u32> = HashMap::new();
        let mut start = u32::MAX;
        for &t in &members {
            for e in 0..3 {
                let (a, b) = (tris[t][e], tris[t][(e + 1) % 3]);
                if group[owner[&(b, a)]] != g {
                    if next.insert(a, b).is_some() {
                        return Err(HullError::Degenerate { reason: "a merged face touches itself" });
                    }
                    start = start.min(a);
                }
            }
        }
        let mut lp = vec![start];
        let mut v = next[&start];
        while v != start {
            if lp.len() > next.len() {
                return Err(HullError::Degenerate { reason: "a merged face has no simple boundary" });
            }
            lp.push(v);
            v = next[&v];
        }
        if lp.len() != next.len() {
            return Err(HullError::Degenerate { reason: "a merged face has a hole" });
        }
        loops.push(lp);
    }
    // A vertex on only two faces lies on a straight edge between them: drop it from both.
    let mut degree: HashMap<u32, usize> = HashMap::new();
    for lp in &loops {
        for &v in lp {
            *degree.entry(v).or_default() += 1;
        }
    }
    for lp in &mut loops {
        lp.retain(|v| degree[v] >= 3);
        if lp.len() < 3 {
            return Err(HullError::Degenerate { reason: "a merged face collapsed" });
        }
    }
    Ok(loops)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_points() -> Vec<DVec3> {
        (0..8)
            .map(|i| {
                DVec3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 },
                    if i & 2 == 0 { -2.0 } else { 2.0 },
                    if i & 4 == 0 { -3.0 } else { 3.0 },
                )
            })
            .collect()
    }

    fn check_convex(hull: &ConvexHull, points: &[DVec3]) {
        for face in hull.faces() {
            assert!((face.normal.length() - 1.0).abs() < 1e-12);
            for q in points {
                assert!(face.normal.dot(*q) - face.offset < 1e-9, "point outside a face");
            }
            for &v in &face.vertices {
                assert!((face.normal.dot(hull.vertices()[v as usize]) - face.offset).abs() < 1e-9);
            }
        }
        for e in hull.edges() {
            let [a, b] = e.vertices.map(|v| hull.vertices()[v as usize]);
            let n0 = hull.faces()[e.faces[0] as usize].normal;
            let n1 = hull.faces()[e.faces[1] as usize].normal;
            assert!(n0.cross(n1).dot(b - a) > 0.0, "edge orientation convention");
        }
    }

    #[test]
    fn box_hull_has_six_quads_and_twelve_edges() {
        let mut pts = cube_points();
        // Interior, face-centre and edge-midpoint points must all disappear.
        pts.push(DVec3::ZERO);
        pts.push(DVec3::new(1.0, 0.0, 0.0));
        pts.push(DVec3::new(1.0, 2.0, 0.0));
        let hull = ConvexHull::new(&pts).unwrap();
        assert_eq!(hull.vertices().len(), 8);
        assert_eq!(hull.faces().len(), 6);
        assert!(hull.faces().iter().all(|f| f.vertices.len() == 4));
        assert_eq!(hull.edges().len(), 12);
        check_convex(&hull, &pts);
        assert_eq!(hull.triangles().len(), 12);
    }

    #[test]
    fn random_cloud_hull_contains_every_point() {
        // A deterministic pseudo-random cloud (xorshift), plus points on a sphere.
        let mut s = 0x2545F4914F6CDD1Du64;
        let mut rnd = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let pts: Vec<DVec3> = (0..300).map(|_| DVec3::new(rnd(), rnd(), rnd())).collect();
        let hull = ConvexHull::new(&pts).unwrap();
        check_convex(&hull, &pts);
        let sphere: Vec<DVec3> =
            (0..200).map(|_| DVec3::new(rnd(), rnd(), rnd()).normalize() * 3.0 + DVec3::X * 100.0).collect();
        let hull = ConvexHull::new(&sphere).unwrap();
        check_convex(&hull, &sphere);
    }

    #[test]
    fn bad_input_is_rejected_with_a_reason() {
        let c = cube_points();
        assert_eq!(ConvexHull::new(&c[..3]), Err(HullError::TooFewPoints { count: 3 }));
        let mut nan = c.clone();
        nan[5].y = f64::NAN;
        assert!(matches!(ConvexHull::new(&nan), Err(HullError::NonFinitePoint { index: 5, .. })));
        assert!(matches!(ConvexHull::new(&[DVec3::ONE; 6]), Err(HullError::Coincident { .. })));
        let line: Vec<DVec3> = (0..5).map(|i| DVec3::splat(i as f64)).collect();
        assert_eq!(ConvexHull::new(&line), Err(HullError::Collinear));
        let plane: Vec<DVec3> = (0..9).map(|i| DVec3::new((i % 3) as f64, (i / 3) as f64, 2.0)).collect();
        assert_eq!(ConvexHull::new(&plane), Err(HullError::Coplanar));
    }
}
