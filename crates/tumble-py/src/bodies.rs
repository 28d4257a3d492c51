//! Bodies: `BodyId` handles, the `Body` view (`world.body(id)`), and the body definition built
//! from `World.add_body`'s keyword arguments.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use tumble::{BodyDef, BodyKind, DQuat, DVec3, WorldError};

use crate::arrays::{mat3_out, quat, quat_out, vec3, vec3_out};
use crate::errors::{value_error, IntoPyResult};
use crate::mass::MassProperties;
use crate::shapes::{shape_to_py, Shape};
use crate::world::World;

crate::handle_class!(
    BodyId,
    tumble::BodyId,
    "Names a body in a World (slot index + generation). Stale once the body is removed."
);

pub fn kind_from_str(kind: &str) -> PyResult<BodyKind> {
    match kind {
        "dynamic" => Ok(BodyKind::Dynamic),
        "static" => Ok(BodyKind::Static),
        "kinematic" => Ok(BodyKind::Kinematic),
        _ => Err(value_error(format!("kind must be \"dynamic\", \"static\" or \"kinematic\", got {kind:?}"))),
    }
}

/// `World.add_body`'s arguments, before conversion. Unset vectors take `BodyDef`'s defaults.
pub struct BodyArgs<'a, 'py> {
    pub shape: Option<&'a Bound<'py, Shape>>,
    pub density: f64,
    pub mass: Option<f64>,
    pub mass_properties: Option<&'a Bound<'py, MassProperties>>,
    pub position: Option<&'a Bound<'py, PyAny>>,
    pub orientation: Option<&'a Bound<'py, PyAny>>,
    pub linear_velocity: Option<&'a Bound<'py, PyAny>>,
    pub angular_velocity: Option<&'a Bound<'py, PyAny>>,
    pub kind: &'a str,
    pub name: String,
    pub linear_damping: f64,
    pub angular_damping: f64,
    pub gravity_scale: f64,
    pub allow_sleep: bool,
    /// Surface material (friction, restitution, rolling and torsional friction).
    pub material: tumble::Material,
    /// Collision group and mask bits.
    pub filter: tumble::CollisionFilter,
    pub sensor: bool,
    /// Swept against static geometry each step.
    pub bullet: bool,
}

impl BodyArgs<'_, '_> {
    /// The core's definition; the core checks the values when the body is added.
    pub fn into_def(self) -> PyResult<BodyDef> {
        let d = BodyDef::default();
        let v = |o: Option<&Bound<'_, PyAny>>, what, default: DVec3| o.map_or(Ok(default), |o| vec3(o, what));
        Ok(BodyDef {
            name: self.name,
            kind: kind_from_str(self.kind)?,
            shape: self.shape.map(|s| s.get().0.clone()),
            density: self.density,
            mass: self.mass,
            mass_properties: self.mass_properties.map(|m| m.get().0),
            position: v(self.position, "position", d.position)?,
            orientation: self.orientation.map_or(Ok(DQuat::IDENTITY), |o| quat(o, "orientation"))?,
            linear_velocity: v(self.linear_velocity, "linear_velocity", d.linear_velocity)?,
            angular_velocity: v(self.angular_velocity, "angular_velocity", d.angular_velocity)?,
            linear_damping: self.linear_damping,
            angular_damping: self.angular_damping,
            gravity_scale: self.gravity_scale,
            allow_sleep: self.allow_sleep,
            material: self.material,
            filter: self.filter,
            is_sensor: self.sensor,
            bullet: self.bullet,
        })
    }
}

/// A view of one body of a World: `world.body(id)`. It reads the world on every access, so it is
/// always current, and raises `StaleHandleError` once the body is removed. Setting `position`,
/// `orientation` or a velocity changes the world (and wakes the body).
#[pyclass(frozen, module = "tumble")]
pub struct Body {
    pub world: Py<World>,
    pub id: BodyId,
}

impl Body {
    fn read<T>(&self, py: Python<'_>, f: impl FnOnce(&tumble::Body) -> T) -> PyResult<T> {
        let world = self.world.bind(py).try_borrow()?;
        Ok(f(world.inner.body(self.id.0).py()?))
    }

    fn write(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut tumble::World, tumble::BodyId) -> Result<(), WorldError>,
    ) -> PyResult<()> {
        let mut world = self.world.bind(py).try_borrow_mut()?;
        f(&mut world.inner, self.id.0).py()
    }
}

#[pymethods]
impl Body {
    /// The body's handle (`BodyId`).
    #[getter]
    fn id(&self) -> BodyId {
        self.id
    }
    /// The body's name ("" if none was given).
    #[getter]
    fn name(&self, py: Python<'_>) -> PyResult<String> {
        self.read(py, |b| b.name().to_string())
    }
    /// "dynamic", "static" or "kinematic".
    #[getter]
    fn kind(&self, py: Python<'_>) -> PyResult<&'static str> {
        self.read(py, |b| b.kind().name())
    }
    /// The body's shape, or None.
    #[getter]
    fn shape(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        self.read(py, |b| b.shape().cloned())?.map(|s| shape_to_py(py, &s)).transpose()
    }
    /// World position of the body frame's origin, (3,).
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.position()))
    }
    #[setter]
    fn set_position(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let p = vec3(value, "position")?;
        self.write(py, |w, id| {
            let q = w.body(id)?.orientation();
            w.set_pose(id, p, q)
        })
    }
    /// Orientation of the body frame, (x, y, z, w). Set: normalised.
    #[getter]
    fn orientation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| quat_out(py, b.orientation()))
    }
    #[setter]
    fn set_orientation(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let q = quat(value, "orientation")?;
        self.write(py, |w, id| {
            let p = w.body(id)?.position();
            w.set_pose(id, p, q)
        })
    }
    /// Velocity of the centre of mass, world frame, (3,).
    #[getter]
    fn linear_velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.linear_velocity()))
    }
    #[setter]
    fn set_linear_velocity(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = vec3(value, "linear_velocity")?;
        self.write(py, |w, id| w.set_linear_velocity(id, v))
    }
    /// Angular velocity, world frame, (3,).
    #[getter]
    fn angular_velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.angular_velocity()))
    }
    #[setter]
    fn set_angular_velocity(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let v = vec3(value, "angular_velocity")?;
        self.write(py, |w, id| w.set_angular_velocity(id, v))
    }
    /// Mass, kg.
    #[getter]
    fn mass(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.mass())
    }
    /// 1/mass; 0 for static and kinematic bodies.
    #[getter]
    fn inverse_mass(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.inverse_mass())
    }
    /// Centre of mass, world frame, (3,).
    #[getter]
    fn center_of_mass<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.com_world()))
    }
    /// Centre of mass in the body frame, (3,).
    #[getter]
    fn center_of_mass_local<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.com_local()))
    }
    /// Inertia tensor about the centre of mass in world axes, (3, 3).
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |b| mat3_out(py, b.inertia_world()))?
    }
    /// Inverse world inertia, (3, 3); zero for static and kinematic bodies.
    #[getter]
    fn inverse_inertia<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |b| mat3_out(py, b.inverse_inertia_world()))?
    }
    /// Principal moments of inertia, ascending, (3,).
    #[getter]
    fn principal_moments<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.inertia_principal()))
    }
    /// Orientation of the principal frame in the world, (x, y, z, w).
    #[getter]
    fn principal_orientation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| quat_out(py, b.principal_rotation_world()))
    }
    /// Mass properties in the body frame.
    #[getter]
    fn mass_properties(&self, py: Python<'_>) -> PyResult<MassProperties> {
        self.read(py, |b| MassProperties(*b.mass_properties()))
    }
    /// Force accumulated since the last step, world frame, (3,).
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.force()))
    }
    /// Torque about the centre of mass accumulated since the last step, world frame, (3,).
    #[getter]
    fn torque<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.torque()))
    }
    /// Linear velocity damping rate, 1/s.
    #[getter]
    fn linear_damping(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.linear_damping())
    }
    /// Angular velocity damping rate, 1/s.
    #[getter]
    fn angular_damping(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.angular_damping())
    }
    /// Multiplier on the world's gravity for this body.
    #[getter]
    fn gravity_scale(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.gravity_scale())
    }
    /// Coulomb friction coefficient of the body's surface.
    #[getter]
    fn friction(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.material().friction)
    }
    /// Coefficient of restitution of the body's surface.
    #[getter]
    fn restitution(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.material().restitution)
    }
    /// True for a sensor (reports overlaps, makes no contact force).
    #[getter]
    fn is_sensor(&self, py: Python<'_>) -> PyResult<bool> {
        self.read(py, |b| b.is_sensor())
    }
    /// True for a bullet: swept against static geometry after each step, so it cannot pass
    /// through thin walls. Settable.
    #[getter]
    fn bullet(&self, py: Python<'_>) -> PyResult<bool> {
        self.read(py, |b| b.is_bullet())
    }
    #[setter]
    fn set_bullet(&self, py: Python<'_>, value: bool) -> PyResult<()> {
        self.write(py, |w, id| w.set_bullet(id, value))
    }
    /// False while the body sleeps.
    #[getter]
    fn is_awake(&self, py: Python<'_>) -> PyResult<bool> {
        self.read(py, |b| b.is_awake())
    }
    /// ½ m v² + ½ ω·Iω (0 for static and kinematic bodies).
    #[getter]
    fn kinetic_energy(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |b| b.kinetic_energy())
    }
    /// m v, (3,).
    #[getter]
    fn linear_momentum<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.linear_momentum()))
    }
    /// Angular momentum about the centre of mass, I ω, world frame, (3,).
    #[getter]
    fn angular_momentum<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |b| vec3_out(py, b.angular_momentum_about_com()))
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        match self.read(py, |b| (b.name().to_string(), b.kind().name())) {
            Ok((name, kind)) => format!("Body({}, name={name:?}, kind={kind:?})", self.id.0),
            Err(_) => format!("Body({}, stale)", self.id.0),
        }
    }
}
