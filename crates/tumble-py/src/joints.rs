//! Joints: `JointId` handles, the `Joint` view (`world.joint(id)`), and joint definitions.
//!
//! One `*_def` function per core `JointKind`, each exposed by one `World.add_*_joint` method.
//! Settings are plain tuples on the Python side: `limits = (lower, upper)`,
//! `motor = (target_speed, max_force)`, `spring = (hertz, damping_ratio)`; the core checks them.

use numpy::PyArray1;
use pyo3::prelude::*;
use tumble::{
    BallJoint, DVec3, DistanceJoint, FixedJoint, HingeJoint, JointDef, JointKind, Limits, Motor, SliderJoint,
    SpringSettings,
};

use crate::arrays::{floats, vec3_out};
use crate::bodies::BodyId;
use crate::errors::IntoPyResult;
use crate::world::World;

crate::handle_class!(
    JointId,
    tumble::JointId,
    "Names a joint in a World (slot index + generation). Stale once the joint is removed."
);

/// Options every joint takes.
pub struct CommonArgs {
    pub name: String,
    pub break_force: Option<f64>,
    pub break_torque: Option<f64>,
    pub collide_connected: bool,
}

/// Limits, motor and spring of a hinge or slider, as given in Python.
pub struct DriveArgs<'a, 'py> {
    pub limits: Option<&'a Bound<'py, PyAny>>,
    pub motor: Option<&'a Bound<'py, PyAny>>,
    pub spring: Option<&'a Bound<'py, PyAny>>,
    pub spring_target: f64,
}

/// Two numbers (a tuple, list or array).
pub fn pair(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(f64, f64)> {
    let (_, v) = floats(obj, what, &[Some(2)])?;
    Ok((v[0], v[1]))
}

fn opt_pair(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<(f64, f64)>> {
    obj.filter(|o| !o.is_none()).map(|o| pair(o, what)).transpose()
}

/// `(lower, upper)`.
pub fn limits(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Limits>> {
    Ok(opt_pair(obj, what)?.map(|(lo, hi)| Limits::new(lo, hi)))
}

/// `(hertz, damping_ratio)`.
pub fn spring(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<SpringSettings>> {
    Ok(opt_pair(obj, "spring")?.map(|(hz, zeta)| SpringSettings::new(hz, zeta)))
}

impl DriveArgs<'_, '_> {
    fn parts(&self) -> PyResult<(Option<Limits>, Option<Motor>, Option<SpringSettings>)> {
        let motor = opt_pair(self.motor, "motor")?.map(|(speed, force)| Motor::new(speed, force));
        Ok((limits(self.limits, "limits")?, motor, spring(self.spring)?))
    }
}

fn def(a: BodyId, b: BodyId, anchor: DVec3, kind: JointKind, common: CommonArgs) -> JointDef {
    JointDef {
        name: common.name,
        break_force: common.break_force,
        break_torque: common.break_torque,
        collide_connected: common.collide_connected,
        ..JointDef::new(a.0, b.0, anchor, kind)
    }
}

/// A ball-and-socket joint: the two bodies share the point `anchor` (world frame, at creation);
/// optional swing cone (half-angle, rad) about `axis` and twist limits.
pub fn ball_def(
    (a, b, anchor, axis): (BodyId, BodyId, DVec3, DVec3),
    (swing_limit, twist_limits, friction_torque): (Option<f64>, Option<Limits>, f64),
    common: CommonArgs,
) -> JointDef {
    let kind = JointKind::Ball(BallJoint { swing_limit, twist_limits, friction_torque });
    JointDef { axis_world: axis, ..def(a, b, anchor, kind, common) }
}

/// A hinge about `axis` through `anchor`.
pub fn hinge_def(
    a: BodyId,
    b: BodyId,
    anchor: DVec3,
    axis: DVec3,
    drive: DriveArgs,
    common: CommonArgs,
) -> PyResult<JointDef> {
    let (limits, motor, spring) = drive.parts()?;
    let kind = JointKind::Hinge(HingeJoint {
        limits,
        motor,
        spring,
        spring_target_angle: drive.spring_target,
        ..Default::default()
    });
    Ok(JointDef { axis_world: axis, ..def(a, b, anchor, kind, common) })
}

/// A slider along `axis`.
pub fn slider_def(
    a: BodyId,
    b: BodyId,
    anchor: DVec3,
    axis: DVec3,
    drive: DriveArgs,
    common: CommonArgs,
) -> PyResult<JointDef> {
    let (limits, motor, spring) = drive.parts()?;
    let kind =
        JointKind::Slider(SliderJoint { limits, motor, spring, spring_target_position: drive.spring_target });
    Ok(JointDef { axis_world: axis, ..def(a, b, anchor, kind, common) })
}

/// A weld at `anchor`.
pub fn fixed_def(a: BodyId, b: BodyId, anchor: DVec3, common: CommonArgs) -> JointDef {
    def(a, b, anchor, JointKind::Fixed(FixedJoint::new()), common)
}

/// A distance joint between `anchor_a` on a and `anchor_b` on b.
pub fn distance_def(
    (a, b, anchor_a, anchor_b): (BodyId, BodyId, DVec3, DVec3),
    settings: DistanceJoint,
    common: CommonArgs,
) -> JointDef {
    JointDef { anchor_b_world: Some(anchor_b), ..def(a, b, anchor_a, JointKind::Distance(settings), common) }
}

/// A view of one joint of a World: `world.joint(id)`. Reads the world on every access; raises
/// `StaleHandleError` once the joint (or one of its bodies) is removed.
#[pyclass(frozen, module = "tumble")]
pub struct Joint {
    pub world: Py<World>,
    pub id: JointId,
}

impl Joint {
    fn read<T>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&tumble::World, &tumble::Joint) -> PyResult<T>,
    ) -> PyResult<T> {
        let world = self.world.bind(py).try_borrow()?;
        let joint = world.inner.joint(self.id.0).py()?;
        f(&world.inner, joint)
    }
}

#[pymethods]
impl Joint {
    /// The joint's handle (`JointId`).
    #[getter]
    fn id(&self) -> JointId {
        self.id
    }
    /// The joint's name ("" if none was given).
    #[getter]
    fn name(&self, py: Python<'_>) -> PyResult<String> {
        self.read(py, |_, j| Ok(j.name().to_string()))
    }
    /// "ball", "hinge", "slider", "fixed" or "distance".
    #[getter]
    fn kind(&self, py: Python<'_>) -> PyResult<&'static str> {
        self.read(py, |_, j| Ok(j.kind().name()))
    }
    /// The first body (`BodyId`).
    #[getter]
    fn body_a(&self, py: Python<'_>) -> PyResult<BodyId> {
        self.read(py, |_, j| Ok(BodyId(j.body_a())))
    }
    /// The second body (`BodyId`).
    #[getter]
    fn body_b(&self, py: Python<'_>) -> PyResult<BodyId> {
        self.read(py, |_, j| Ok(BodyId(j.body_b())))
    }
    /// True once the constraint force exceeded `break_force`; a broken joint no longer acts.
    #[getter]
    fn is_broken(&self, py: Python<'_>) -> PyResult<bool> {
        self.read(py, |_, j| Ok(j.is_broken()))
    }
    /// Magnitude of the linear constraint force over the last step, N.
    #[getter]
    fn constraint_force(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |_, j| Ok(j.constraint_force()))
    }
    /// Magnitude of the angular constraint torque over the last step, N·m.
    #[getter]
    fn constraint_torque(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |_, j| Ok(j.constraint_torque()))
    }
    /// The anchor point on body a, world frame, (3,).
    #[getter]
    fn anchor_a<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |w, j| Ok(vec3_out(py, j.anchor_a_world(w.body(j.body_a()).py()?))))
    }
    /// The anchor point on body b, world frame, (3,).
    #[getter]
    fn anchor_b<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |w, j| Ok(vec3_out(py, j.anchor_b_world(w.body(j.body_b()).py()?))))
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        match self.read(py, |_, j| Ok((j.kind().name(), j.body_a(), j.body_b()))) {
            Ok((kind, a, b)) => format!("Joint({}, kind={kind:?}, body_a={a}, body_b={b})", self.id.0),
            Err(_) => format!("Joint({}, stale)", self.id.0),
        }
    }
}
