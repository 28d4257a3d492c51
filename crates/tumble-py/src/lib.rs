//! Python bindings of Tumble: `import tumble`.
//!
//! A thin face over the core crate: every check and every computation is the core's; this crate
//! converts arguments (NumPy in and out), maps errors to Python exceptions and releases the GIL
//! while stepping. One file per area:
//!
//! | file | what |
//! |---|---|
//! | `world.rs` | `World`: settings, bodies and joints, forces, queries, `step`, `step_many` |
//! | `arrays.rs` | NumPy conversion and the flat state arrays (positions, orientations, velocities) |
//! | `bodies.rs` | `BodyId` handles, the `Body` view, body definitions from keyword arguments |
//! | `joints.rs` | `JointId` handles, the `Joint` view, joint definitions |
//! | `shapes.rs` | `Shape` and its subclasses |
//! | `queries.rs` | `contacts()` as a structured array, ray casts (`RayHit`), events, `from_scene` |
//! | `mass.rs` | `MassProperties`, `mass_properties(vertices, triangles)` |
//! | `errors.rs` | core errors as `tumble.TumbleError` subclasses |

use pyo3::prelude::*;

mod arrays;
mod bodies;
mod errors;
mod joints;
mod mass;
mod queries;
mod shapes;
mod world;

/// Defines a frozen, hashable Python handle class around a core id (index + generation).
/// A handle from a removed object is stale: using it raises `StaleHandleError`.
macro_rules! handle_class {
    ($name:ident, $core:ty, $doc:literal) => {
        #[doc = $doc]
        #[pyclass(frozen, eq, hash, ord, from_py_object, module = "tumble")]
        #[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub struct $name(pub $core);

        #[pymethods]
        impl $name {
            /// The slot index (reused after removal).
            #[getter]
            fn index(&self) -> usize {
                self.0.index()
            }
            /// The slot's generation when this handle was made.
            #[getter]
            fn generation(&self) -> u32 {
                self.0.generation()
            }
            fn __repr__(&self) -> String {
                format!("{}", self.0)
            }
        }
    };
}
pub(crate) use handle_class;

/// Tumble: a 3D rigid-body dynamics engine (f64, SI units, Z up, quaternions (x, y, z, w)).
#[pymodule]
fn _tumble(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<world::World>()?;
    m.add_function(wrap_pyfunction!(world::step_many, m)?)?;
    m.add_class::<bodies::BodyId>()?;
    m.add_class::<bodies::Body>()?;
    m.add_class::<joints::JointId>()?;
    m.add_class::<joints::Joint>()?;
    m.add_class::<queries::RayHit>()?;
    m.add_class::<shapes::Shape>()?;
    m.add_class::<shapes::SphereShape>()?;
    m.add_class::<shapes::BoxShape>()?;
    m.add_class::<shapes::CapsuleShape>()?;
    m.add_class::<shapes::CylinderShape>()?;
    m.add_class::<shapes::ConeShape>()?;
    m.add_class::<shapes::TriMeshShape>()?;
    m.add_class::<shapes::CompoundShape>()?;
    m.add_class::<shapes::ConvexHullShape>()?;
    m.add_class::<shapes::PlaneShape>()?;
    m.add_class::<shapes::HeightFieldShape>()?;
    m.add_class::<mass::MassProperties>()?;
    m.add_function(wrap_pyfunction!(mass::mass_properties, m)?)?;
    Ok(())
}
