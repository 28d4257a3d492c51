//! Closed triangle meshes: validation, and mass properties by the Mirtich–Eberly volume integrals.
//!
//! Validation runs cheapest and most basic checks first, so the error reported is the root cause:
//! empty → index range → finite vertices → degenerate triangles → closed (every edge in exactly two
//! triangles) → consistent winding (no directed edge used twice) → signed volume (outward, not
//! zero). Edge checks sort edge lists rather than hash them, so the edge reported is deterministic
//! (the smallest offending one).

use super::primitives::positive;
use super::volume_integrals::VolumeIntegrals;
use super::{MassError, MassProperties};
use crate::math::DVec3;

/// A triangle is degenerate when twice its area, `|(p1 − p0) × (p2 − p0)|`, is below this times
/// the squared bounding-box diagonal: a zero-area triangle up to the round-off of its coordinates.
const DEGENERATE_AREA: f64 = 16.0 * f64::EPSILON;

/// The enclosed volume counts as zero when it is below this fraction of the larger of the
/// bounding-box volume and `Σ |tetrahedron volumes|` (the round-off scale of the volume sum).
const ZERO_VOLUME: f64 = 1e-12;

/// Checks the parts of a mesh that every use needs — not empty, indices in range, finite vertices,
/// no degenerate triangles — but not closedness or winding (an open static collision mesh).
pub fn validate_mesh_surface(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), MassError> {
    if triangles.is_empty() {
        return Err(MassError::EmptyMesh);
    }
    check_indices(vertices.len(), triangles)?;
    check_finite(vertices)?;
    let (lo, hi) = bounds(vertices, triangles);
    check_degenerate(vertices, triangles, (hi - lo).length_squared())
}

/// Checks that a mesh is finite, non-degenerate, closed, consistently and outwardly wound.
pub fn validate_closed_mesh(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), MassError> {
    checked_integrals(vertices, triangles).map(|_| ())
}

impl MassProperties {
    /// Mass properties of the solid bounded by a closed, outward-wound triangle mesh.
    ///
    /// The mesh is validated first (see [`validate_closed_mesh`]); the inertia is about the
    /// centre of mass, in the mesh's axes.
    pub fn from_mesh(vertices: &[DVec3], triangles: &[[u32; 3]], density: f64) -> Result<Self, MassError> {
        let density = positive("density", density)?;
        let integrals = checked_integrals(vertices, triangles)?;
        Ok(Self::from_integrals(&integrals, density))
    }

    /// Mass properties of a convex hull from its faces fanned into triangles. The hull checked
    /// itself when it was built (finite, closed, outward, with volume), so the mesh checks are
    /// not repeated — in particular not the degenerate-triangle check: a face polygon that keeps
    /// a vertex on one of its edges (within the hull's merge tolerance) fans into a zero-area
    /// triangle, which adds nothing to the integrals and must not reject the hull.
    pub(crate) fn from_hull_triangles(
        vertices: &[DVec3],
        triangles: &[[u32; 3]],
        density: f64,
    ) -> Result<Self, MassError> {
        let density = positive("density", density)?;
        if triangles.is_empty() {
            return Err(MassError::EmptyMesh);
        }
        let integrals = oriented_integrals(vertices, triangles)?;
        Ok(Self::from_integrals(&integrals, density))
    }

    fn from_integrals(integrals: &VolumeIntegrals, density: f64) -> Self {
        let (center_of_mass, inertia_per_density) = integrals.center_and_inertia();
        MassProperties {
            volume: integrals.volume,
            mass: density * integrals.volume,
            center_of_mass,
            inertia: inertia_per_density * density,
        }
    }
}

/// Runs every check and returns the volume integrals of a valid mesh.
fn checked_integrals(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<VolumeIntegrals, MassError> {
    if triangles.is_empty() {
        return Err(MassError::EmptyMesh);
    }
    check_indices(vertices.len(), triangles)?;
    check_finite(vertices)?;
    let (lo, hi) = bounds(vertices, triangles);
    check_degenerate(vertices, triangles, (hi - lo).length_squared())?;
    check_closed_and_wound(triangles)?;
    oriented_integrals(vertices, triangles)
}

/// The volume integrals of a closed, consistently wound mesh; an error unless its volume is
/// positive (outward winding) and above round-off.
fn oriented_integrals(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<VolumeIntegrals, MassError> {
    let (lo, hi) = bounds(vertices, triangles);
    let extent = hi - lo;
    // Integrate relative to the bounding-box centre: near the solid, so the second moments are
    // not swamped by m|c|² terms when the mesh sits far from the frame's origin.
    let integrals = VolumeIntegrals::compute(vertices, triangles, 0.5 * (lo + hi));
    let volume = integrals.volume;
    let scale = (extent.x * extent.y * extent.z).max(integrals.abs_volume);
    if volume.abs() <= ZERO_VOLUME * scale {
        return Err(MassError::ZeroVolume { volume });
    }
    if volume < 0.0 {
        return Err(MassError::InvertedMesh { volume });
    }
    Ok(integrals)
}

fn check_indices(vertex_count: usize, triangles: &[[u32; 3]]) -> Result<(), MassError> {
    for (triangle, tri) in triangles.iter().enumerate() {
        if let Some(&vertex) = tri.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(MassError::IndexOutOfRange { triangle, vertex, count: vertex_count });
        }
    }
    Ok(())
}

/// Every vertex must be finite, used or not: a NaN in the input is a bug worth reporting.
fn check_finite(vertices: &[DVec3]) -> Result<(), MassError> {
    match vertices.iter().position(|v| !v.is_finite()) {
        Some(index) => {
            let v = vertices[index];
            Err(MassError::NonFiniteVertex { index, x: v.x, y: v.y, z: v.z })
        }
        None => Ok(()),
    }
}

/// The axis-aligned bounds of the vertices the triangles use.
fn bounds(vertices: &[DVec3], triangles: &[[u32; 3]]) -> (DVec3, DVec3) {
    let first = vertices[triangles[0][0] as usize];
    triangles.iter().flatten().fold((first, first), |(lo, hi), &i| {
        let v = vertices[i as usize];
        (lo.min(v), hi.max(v))
    })
}

fn check_degenerate(vertices: &[DVec3], triangles: &[[u32; 3]], diagonal2: f64) -> Result<(), MassError> {
    let min_double_area = DEGENERATE_AREA * diagonal2;
    for (triangle, &[a, b, c]) in triangles.iter().enumerate() {
        let repeated = a == b || b == c || c == a;
        let [p0, p1, p2] = [a, b, c].map(|i| vertices[i as usize]);
        if repeated || (p1 - p0).cross(p2 - p0).length() <= min_double_area {
            return Err(MassError::DegenerateTriangle { triangle });
        }
    }
    Ok(())
}

/// Closed: every undirected edge is in exactly two triangles. Consistent: those two triangles
/// traverse it in opposite directions, i.e. no directed edge appears twice.
fn check_closed_and_wound(triangles: &[[u32; 3]]) -> Result<(), MassError> {
    // (from, to, triangle) for every directed edge.
    let mut directed: Vec<(u32, u32, usize)> =
        triangles.iter().enumerate().flat_map(|(t, &[a, b, c])| [(a, b, t), (b, c, t), (c, a, t)]).collect();

    let mut undirected: Vec<(u32, u32)> = directed.iter().map(|&(a, b, _)| (a.min(b), a.max(b))).collect();
    undirected.sort_unstable();
    for run in undirected.chunk_by(|x, y| x == y) {
        if run.len() != 2 {
            let (a, b) = run[0];
            return Err(MassError::OpenMesh { a, b, count: run.len() });
        }
    }

    directed.sort_unstable();
    for pair in directed.windows(2) {
        let ((a, b, t1), (a2, b2, t2)) = (pair[0], pair[1]);
        if (a, b) == (a2, b2) {
            return Err(MassError::InconsistentWinding { a, b, t1, t2 });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron with one vertex at `apex`, outward wound when `apex.z > 0`.
    fn tetra(apex: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y, apex];
        let t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        (v, t)
    }

    #[test]
    fn valid_tetrahedron() {
        let (v, t) = tetra(DVec3::Z);
        assert_eq!(validate_closed_mesh(&v, &t), Ok(()));
        let p = MassProperties::from_mesh(&v, &t, 6.0).unwrap();
        assert!((p.mass - 1.0).abs() < 1e-15);
        assert!((p.center_of_mass - DVec3::splat(0.25)).length() < 1e-15);
    }

    #[test]
    fn check_order_reports_the_root_cause() {
        let (mut v, mut t) = tetra(DVec3::Z);
        assert_eq!(validate_closed_mesh(&v, &[]), Err(MassError::EmptyMesh));
        v[3].x = f64::NAN;
        t[1][2] = 9;
        // An out-of-range index is reported before the NaN vertex.
        assert!(matches!(validate_closed_mesh(&v, &t), Err(MassError::IndexOutOfRange { .. })));
        t[1][2] = 3;
        assert!(matches!(validate_closed_mesh(&v, &t), Err(MassError::NonFiniteVertex { index: 3, .. })));
    }

    #[test]
    fn degenerate_and_flat() {
        let (v, mut t) = tetra(DVec3::Z);
        t[0] = [0, 0, 1];
        assert_eq!(validate_closed_mesh(&v, &t), Err(MassError::DegenerateTriangle { triangle: 0 }));
        // Apex in the base plane: closed and consistently wound, but flat.
        let (v, t) = tetra(DVec3::new(0.2, 0.3, 0.0));
        assert!(matches!(validate_closed_mesh(&v, &t), Err(MassError::ZeroVolume { .. })));
    }

    #[test]
    fn inverted_open_and_inconsistent() {
        let (v, t) = tetra(DVec3::new(0.0, 0.0, -1.0));
        assert!(matches!(validate_closed_mesh(&v, &t), Err(MassError::InvertedMesh { .. })));
        let (v, t) = tetra(DVec3::Z);
        assert_eq!(validate_closed_mesh(&v, &t[..3]), Err(MassError::OpenMesh { a: 1, b: 2, count: 1 }));
        let mut flipped = t.clone();
        flipped[3] = [1, 3, 2];
        assert!(matches!(validate_closed_mesh(&v, &flipped), Err(MassError::InconsistentWinding { .. })));
    }
}
