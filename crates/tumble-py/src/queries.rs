//! Reading the world's contacts and asking it questions: `World.contacts()` (a structured NumPy
//! array), `World.raycast` / `raycast_all` (`RayHit` objects), contact and sensor events, and
//! `World.from_scene` (via tumble-io). The `World` methods in `world.rs` call these.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyList;
use tumble::{BodyId as CoreBodyId, CollisionFilter, DVec3, QueryFilter};

use crate::arrays::{rows_out, vec3, vec3_out};
use crate::bodies::BodyId;
use crate::errors::value_error;

/// Where a ray hit a body: `body`, `distance` (m, along the unit direction), `point` and unit
/// surface `normal` (world frame).
#[pyclass(frozen, module = "tumble")]
pub struct RayHit {
    /// The body hit (`BodyId`).
    #[pyo3(get)]
    body: BodyId,
    /// Distance from the ray origin to the hit, m (along the unit direction).
    #[pyo3(get)]
    distance: f64,
    point_world: DVec3,
    normal_world: DVec3,
}

#[pymethods]
impl RayHit {
    /// The hit point, world frame, (3,).
    #[getter]
    fn point<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(py, self.point_world)
    }
    /// The unit surface normal at the hit, world frame, (3,).
    #[getter]
    fn normal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(py, self.normal_world)
    }
    fn __repr__(&self) -> String {
        format!(
            "RayHit(body={}, distance={}, point={:?}, normal={:?})",
            self.body.0,
            self.distance,
            self.point_world.to_array(),
            self.normal_world.to_array()
        )
    }
}

impl From<tumble::RayCastHit> for RayHit {
    fn from(h: tumble::RayCastHit) -> Self {
        RayHit { body: BodyId(h.body), distance: h.distance, point_world: h.point, normal_world: h.normal }
    }
}

/// The query filter from the keyword arguments of `raycast`.
pub fn filter(group: u32, mask: u32, include_sensors: bool) -> QueryFilter {
    QueryFilter { collision: CollisionFilter { group, mask }, include_sensors }
}

/// Checked ray arguments: origin and direction as 3-vectors.
pub fn ray_args(origin: &Bound<'_, PyAny>, direction: &Bound<'_, PyAny>) -> PyResult<(DVec3, DVec3)> {
    Ok((vec3(origin, "origin")?, vec3(direction, "direction")?))
}

pub fn query_error(e: tumble::QueryError) -> PyErr {
    value_error(e.to_string())
}

/// One row per contact point of every touching contact, in the world's fixed contact order:
/// `body_a`, `body_b` (int64 slot indices, `BodyId.index`), `point` (3,), `normal` (3,, from a
/// to b), `separation` (m, negative = overlap), `impulse` (normal impulse over the last step,
/// N·s), `sensor` (bool).
pub fn contacts_array<'py>(py: Python<'py>, world: &tumble::World) -> PyResult<Bound<'py, PyAny>> {
    let (mut a, mut b, mut points, mut normals, mut separations, mut impulses, mut sensors) =
        (vec![], vec![], vec![], vec![], vec![], vec![], vec![]);
    for contact in world.contacts() {
        for p in &contact.points {
            a.push(contact.body_a.index() as i64);
            b.push(contact.body_b.index() as i64);
            points.push(p.point.to_array());
            normals.push(contact.normal.to_array());
            separations.push(p.separation);
            impulses.push(p.normal_impulse);
            sensors.push(contact.sensor);
        }
    }
    let np = py.import("numpy")?;
    let fields = PyList::new(
        py,
        [
            ("body_a", "<i8").into_pyobject(py)?.into_any(),
            ("body_b", "<i8").into_pyobject(py)?.into_any(),
            ("point", "<f8", (3,)).into_pyobject(py)?.into_any(),
            ("normal", "<f8", (3,)).into_pyobject(py)?.into_any(),
            ("separation", "<f8").into_pyobject(py)?.into_any(),
            ("impulse", "<f8").into_pyobject(py)?.into_any(),
            ("sensor", "?").into_pyobject(py)?.into_any(),
        ],
    )?;
    let dtype = np.call_method1("dtype", (fields,))?;
    let array = np.call_method1("zeros", (a.len(), dtype))?;
    array.set_item("body_a", PyArray1::from_vec(py, a))?;
    array.set_item("body_b", PyArray1::from_vec(py, b))?;
    array.set_item("point", rows_out(py, &points)?)?;
    array.set_item("normal", rows_out(py, &normals)?)?;
    array.set_item("separation", PyArray1::from_vec(py, separations))?;
    array.set_item("impulse", PyArray1::from_vec(py, impulses))?;
    array.set_item("sensor", PyArray1::from_vec(py, sensors))?;
    Ok(array)
}

/// Event pairs as handles.
pub fn pairs(events: &[(CoreBodyId, CoreBodyId)]) -> Vec<(BodyId, BodyId)> {
    events.iter().map(|&(a, b)| (BodyId(a), BodyId(b))).collect()
}

/// Reads a scene file with tumble-io and builds its world.
pub fn world_from_scene(path: &std::path::Path) -> PyResult<tumble::World> {
    let io = |e: tumble_io::IoError| match e {
        tumble_io::IoError::File { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            pyo3::exceptions::PyFileNotFoundError::new_err(format!("{}: {source}", path.display()))
        }
        tumble_io::IoError::File { .. } => pyo3::exceptions::PyOSError::new_err(e.to_string()),
        other => value_error(other.to_string()),
    };
    let scene = tumble_io::Scene::from_file(path).map_err(io)?;
    Ok(scene.build_world().map_err(io)?.world)
}
