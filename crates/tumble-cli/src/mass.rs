//! `tumble mass MESH`: a mesh's mass properties as JSON, for checking a model before using it.

use std::path::Path;

use serde::Serialize;
use tumble::{DMat3, MassProperties};

/// The JSON printed. Matrices are arrays of rows.
#[derive(Serialize)]
struct MassReport {
    /// m³
    volume: f64,
    /// kg
    mass: f64,
    /// In the mesh's coordinates, m.
    center_of_mass: [f64; 3],
    /// About the centre of mass, in the mesh's axes, kg·m².
    inertia: [[f64; 3]; 3],
    /// Ascending, kg·m².
    principal_moments: [f64; 3],
    /// The rotation R (rows of the matrix) whose columns are the principal axes:
    /// inertia = R · diag(principal_moments) · Rᵀ, det R = +1.
    principal_axes: [[f64; 3]; 3],
}

fn rows(m: DMat3) -> [[f64; 3]; 3] {
    // glam stores columns; element (r, c) is col(c)[r].
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| m.col(c)[r]))
}

pub fn print_mass(path: &Path, density: f64) -> Result<String, String> {
    if !(density.is_finite() && density > 0.0) {
        return Err(format!("--density must be finite and > 0, got {density}"));
    }
    let mesh = tumble_io::load_mesh(path).map_err(|e| e.to_string())?;
    let mp = MassProperties::from_mesh(mesh.vertices(), mesh.triangles(), density)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let principal = mp.principal();
    let report = MassReport {
        volume: mp.volume,
        mass: mp.mass,
        center_of_mass: mp.center_of_mass.to_array(),
        inertia: rows(mp.inertia),
        principal_moments: principal.moments.to_array(),
        principal_axes: rows(principal.axes),
    };
    let mut text = serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}
