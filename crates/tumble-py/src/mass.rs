//! Mass properties: `tumble.MassProperties` and `tumble.mass_properties(vertices, triangles)`.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use tumble::{DMat3, DVec3};

use crate::arrays::{floats, mat3_out, vec3_out};
use crate::errors::IntoPyResult;
use crate::shapes;

/// Mass, centre of mass and inertia (about the centre of mass) of a solid, in its own frame.
///
/// `MassProperties(mass, inertia, center_of_mass=(0, 0, 0), volume=0.0)` builds one by hand for
/// `World.add_body(mass_properties=...)`: `inertia` is a (3, 3) tensor or its 3 diagonal entries.
#[pyclass(frozen, module = "tumble")]
#[derive(Clone)]
pub struct MassProperties(pub tumble::MassProperties);

#[pymethods]
impl MassProperties {
    #[new]
    #[pyo3(signature = (mass, inertia, center_of_mass = None, volume = 0.0))]
    fn new(
        mass: f64,
        inertia: &Bound<'_, PyAny>,
        center_of_mass: Option<&Bound<'_, PyAny>>,
        volume: f64,
    ) -> PyResult<Self> {
        let inertia = match floats(inertia, "inertia", &[Some(3)]) {
            Ok((_, d)) => DMat3::from_diagonal(DVec3::new(d[0], d[1], d[2])),
            Err(_) => crate::arrays::mat3(inertia, "inertia (3 diagonal entries or a (3, 3) tensor)")?,
        };
        let center_of_mass =
            crate::arrays::opt_vec3(center_of_mass, "center_of_mass")?.unwrap_or(DVec3::ZERO);
        Ok(MassProperties(tumble::MassProperties { volume, mass, center_of_mass, inertia }))
    }

    /// Volume, m³.
    #[getter]
    fn volume(&self) -> f64 {
        self.0.volume
    }
    /// Mass, kg.
    #[getter]
    fn mass(&self) -> f64 {
        self.0.mass
    }
    /// Centre of mass, (3,).
    #[getter]
    fn center_of_mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(py, self.0.center_of_mass)
    }
    /// Inertia tensor about the centre of mass, (3, 3), kg·m².
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        mat3_out(py, self.0.inertia)
    }
    /// Principal moments of inertia, ascending, (3,).
    #[getter]
    fn principal_moments<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(py, self.0.principal().moments)
    }
    /// Principal axes as the columns of a rotation matrix, (3, 3):
    /// `inertia == axes @ diag(moments) @ axes.T`.
    #[getter]
    fn principal_axes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        mat3_out(py, self.0.principal().axes)
    }

    /// The same solid rescaled to total `mass`.
    fn with_mass(&self, mass: f64) -> PyResult<Self> {
        Ok(MassProperties(self.0.with_mass(mass).py()?))
    }

    fn __repr__(&self) -> String {
        let p = &self.0;
        format!(
            "MassProperties(mass={}, volume={}, center_of_mass={:?}, principal_moments={:?})",
            p.mass,
            p.volume,
            p.center_of_mass.to_array(),
            p.principal().moments.to_array()
        )
    }
}

/// Mass properties of the solid bounded by a closed, outward-wound triangle mesh
/// (Mirtich–Eberly), in the mesh's frame. The mesh is validated first.
#[pyfunction]
#[pyo3(signature = (vertices, triangles, density = 1.0))]
pub fn mass_properties(
    vertices: &Bound<'_, PyAny>,
    triangles: &Bound<'_, PyAny>,
    density: f64,
) -> PyResult<MassProperties> {
    let v = shapes::vertices(vertices)?;
    let t = shapes::triangles(triangles)?;
    Ok(MassProperties(tumble::MassProperties::from_mesh(&v, &t, density).py()?))
}
