//! Closest points between points and segments (Ericson, *Real-Time Collision Detection*, 5.1.9):
//! the closed forms behind sphere and capsule contacts and polyhedral edge–edge contacts.

use crate::math::DVec3;

/// Parameter `t ∈ [0, 1]` of the point of segment `p → q` closest to `x`.
pub fn closest_on_segment(x: DVec3, p: DVec3, q: DVec3) -> f64 {
    let d = q - p;
    let dd = d.length_squared();
    if dd <= 0.0 {
        return 0.0;
    }
    ((x - p).dot(d) / dd).clamp(0.0, 1.0)
}

/// Parameters `(s, t)` of the closest points `p1 + s (q1 − p1)` and `p2 + t (q2 − p2)` of two
/// segments. Parallel segments pick the pair nearest the middle of their overlap, so the answer
/// does not jump as the segments slide along each other.
pub fn closest_segment_segment(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (f64, f64) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    if a <= 0.0 && e <= 0.0 {
        return (0.0, 0.0);
    }
    if a <= 0.0 {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= 0.0 {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    if denom <= 1e-12 * a * e {
        // Parallel: take the middle of the overlap of segment 2's projection onto segment 1.
        let t0 = (-c / a).clamp(0.0, 1.0);
        let t1 = ((d2 - r).dot(d1) / a).clamp(0.0, 1.0);
        let s = 0.5 * (t0 + t1);
        let t = closest_on_segment(p1 + d1 * s, p2, q2);
        return (s, t);
    }
    let mut s = ((b * f - c * e) / denom).clamp(0.0, 1.0);
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_and_parallel_segments() {
        let (s, t) = closest_segment_segment(
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, -1.0, 2.0),
            DVec3::new(0.5, 1.0, 2.0),
        );
        assert!((s - 0.75).abs() < 1e-15 && (t - 0.5).abs() < 1e-15);
        let (s, t) = closest_segment_segment(
            DVec3::ZERO,
            DVec3::X * 2.0,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(3.0, 1.0, 0.0),
        );
        assert!((s - 0.75).abs() < 1e-15 && (t - 0.25).abs() < 1e-15, "{s} {t}");
    }
}
