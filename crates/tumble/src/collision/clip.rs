//! Clipping an incident feature against a reference face (Sutherland–Hodgman), with feature tags.
//!
//! A face contact is the overlap of two nearly parallel polygons. Take the reference face (the one
//! whose normal is the contact normal) and the incident polygon (the other shape's face, edge or
//! cap most anti-parallel to it). Cutting the incident polygon by the reference face's side planes
//! — the planes through each reference edge, perpendicular to the face — leaves the part of it that
//! lies over the reference face; each remaining vertex's height above the reference plane is its
//! separation.
//!
//! Every output vertex carries a 16-bit tag naming how it was made: an original incident vertex
//! `k` is tagged `k`; a vertex where the polygon crossed side plane `s` is tagged
//! `0x8000 | line << 7 | s`, with `line` the line it lies on (incident edge `e` → `e`, an earlier
//! side plane `s'` → `0x80 | s'`). The same features touching give the same tags, whatever the
//! exact pose, which is what lets contact points keep their identity from step to step.

use smallvec::SmallVec;

use crate::math::DVec3;

/// Distance, m, by which a vertex may lie outside a side plane and still count as inside. Equal
/// faces stacked exactly on each other put the incident corners *on* the side planes, and without
/// it round-off alone would decide, step by step, whether a corner stays or is cut — changing the
/// points' identities and dropping their warm-start impulses.
const SIDE_TOLERANCE: f64 = 1e-6;

/// A clipped polygon: on the stack up to 16 vertices (a box face clipped by a box face has at most
/// eight), so clipping allocates nothing in the usual cases.
pub type ClipPolygon = SmallVec<[ClipVertex; 16]>;

/// A vertex of a polygon being clipped.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ClipVertex {
    pub point: DVec3,
    /// How the vertex was made (see the module docs).
    pub tag: u16,
    /// The line the polygon edge leaving this vertex lies on: `e` for incident edge e, `0x80 | s`
    /// for side plane s.
    line: u8,
}

/// An incident point that survived clipping, with its height above the reference plane.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ClippedPoint {
    /// The point on the incident feature.
    pub point: DVec3,
    /// `reference_normal · (point − reference plane)`: positive means above (separated).
    pub separation: f64,
    pub tag: u16,
}

impl ClipVertex {
    /// Vertex `k` of the incident polygon.
    pub fn original(point: DVec3, k: usize) -> ClipVertex {
        ClipVertex { point, tag: (k & 0xFF) as u16, line: (k & 0x7F) as u8 }
    }
}

/// Keeps the part of `poly` on the negative side of the plane `normal · x ≤ offset` (the side
/// plane numbered `plane`), written to `out` (cleared first). Works for polygons (closed loops of
/// ≥ 3 vertices); see [`clip_segment`] for two points. Into a buffer the caller keeps rather than
/// a new polygon returned: a polygon on the stack is half a kilobyte, and returning one per side
/// plane copied it each time.
pub fn clip_polygon(poly: &[ClipVertex], normal: DVec3, offset: f64, plane: usize, out: &mut ClipPolygon) {
    let n = poly.len();
    let tolerance = SIDE_TOLERANCE * normal.length();
    out.clear();
    let s = (plane & 0x7F) as u16;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        let da = normal.dot(a.point) - offset;
        let db = normal.dot(b.point) - offset;
        if da <= tolerance {
            out.push(a);
        }
        if (da <= tolerance) != (db <= tolerance) {
            let t = da / (da - db);
            let point = a.point + (b.point - a.point) * t;
            let tag = 0x8000 | (u16::from(a.line) << 7) | s;
            // Leaving the half-space, the next polygon edge runs along the side plane; entering,
            // it continues along the incident edge.
            let line = if da <= tolerance { 0x80 | s as u8 } else { a.line };
            out.push(ClipVertex { point, tag, line });
        }
    }
}

/// Keeps the part of segment `seg` with `normal · x ≤ offset`; `None` if nothing is left.
pub fn clip_segment(
    seg: [ClipVertex; 2],
    normal: DVec3,
    offset: f64,
    plane: usize,
) -> Option<[ClipVertex; 2]> {
    let tolerance = SIDE_TOLERANCE * normal.length();
    let da = normal.dot(seg[0].point) - offset;
    let db = normal.dot(seg[1].point) - offset;
    if da > tolerance && db > tolerance {
        return None;
    }
    let mut out = seg;
    if da > tolerance || db > tolerance {
        let t = da / (da - db);
        let point = seg[0].point + (seg[1].point - seg[0].point) * t;
        let cut = ClipVertex {
            point,
            tag: 0x8000 | (u16::from(seg[0].line) << 7) | (plane & 0x7F) as u16,
            line: seg[0].line,
        };
        if da > tolerance {
            out[0] = cut;
        } else {
            out[1] = cut;
        }
    }
    Some(out)
}

/// Clips an incident polygon, segment or point against the reference face `ref_loop` (vertices
/// counter-clockwise about `ref_normal`), and returns the surviving points with their heights
/// above the reference plane. Points higher than `max_separation` are dropped.
pub fn clip_to_face(
    ref_loop: &[DVec3],
    ref_normal: DVec3,
    incident: &[DVec3],
    max_separation: f64,
) -> SmallVec<[ClippedPoint; 16]> {
    // Two buffers, clipped from one into the other in turn (`current` is the one clipped last).
    let mut buffers = [ClipPolygon::new(), ClipPolygon::new()];
    buffers[0].extend(incident.iter().enumerate().map(|(k, &p)| ClipVertex::original(p, k)));
    let mut current = 0;
    let m = ref_loop.len();
    for s in 0..m {
        let a = ref_loop[s];
        let b = ref_loop[(s + 1) % m];
        // Outward side-plane normal of a counter-clockwise loop.
        let side = (b - a).cross(ref_normal);
        let offset = side.dot(a);
        let [first, second] = &mut buffers;
        let (poly, out) = if current == 0 { (first, second) } else { (second, first) };
        match poly.len() {
            0 => break,
            1 => {
                if side.dot(poly[0].point) > offset + SIDE_TOLERANCE * side.length() {
                    poly.clear();
                }
                continue; // kept (or emptied) in place
            }
            2 => {
                out.clear();
                if let Some(seg) = clip_segment([poly[0], poly[1]], side, offset, s) {
                    out.extend(seg);
                }
            }
            _ => clip_polygon(poly, side, offset, s, out),
        }
        current = 1 - current;
    }
    let plane = ref_normal.dot(ref_loop[0]);
    let mut clipped = SmallVec::new();
    clipped.extend(
        buffers[current]
            .iter()
            .map(|v| ClippedPoint { point: v.point, separation: ref_normal.dot(v.point) - plane, tag: v.tag })
            .filter(|c| c.separation <= max_separation),
    );
    clipped
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(h: f64, z: f64) -> Vec<DVec3> {
        vec![DVec3::new(-h, -h, z), DVec3::new(h, -h, z), DVec3::new(h, h, z), DVec3::new(-h, h, z)]
    }

    #[test]
    fn small_square_over_big_square_keeps_its_corners() {
        let out = clip_to_face(&square(2.0, 0.0), DVec3::Z, &square(0.5, -0.01), 0.1);
        assert_eq!(out.len(), 4);
        for (k, c) in out.iter().enumerate() {
            assert_eq!(c.tag, k as u16);
            assert!((c.separation + 0.01).abs() < 1e-15);
        }
    }

    #[test]
    fn overhanging_square_is_cut_with_stable_tags() {
        let shifted: Vec<DVec3> = square(0.5, 0.02).iter().map(|p| *p + DVec3::X * 1.8).collect();
        let a = clip_to_face(&square(2.0, 0.0), DVec3::Z, &shifted, 0.1);
        let shifted2: Vec<DVec3> = shifted.iter().map(|p| *p + DVec3::new(0.01, -0.003, 0.0)).collect();
        let b = clip_to_face(&square(2.0, 0.0), DVec3::Z, &shifted2, 0.1);
        assert_eq!(a.len(), 4);
        assert!(a.iter().all(|c| c.point.x <= 2.0 + 1e-12));
        let tags_a: Vec<u16> = a.iter().map(|c| c.tag).collect();
        let tags_b: Vec<u16> = b.iter().map(|c| c.tag).collect();
        assert_eq!(tags_a, tags_b);
        // Too high above the reference plane: dropped.
        assert!(clip_to_face(&square(2.0, 0.0), DVec3::Z, &shifted, 0.01).is_empty());
    }
}
