//! Joints: `JointId` handles, the `Joint` view (`world.joint(id)`), and joint definitions.
//!
//! The core has the ball-and-socket joint today; hinge, slider, fixed and distance joints slot in
//! as one more `JointKind` each, built here by one more `*_def` function and exposed by one more
//! `World.add_*_joint` method.

use numpy::PyArray1;
use pyo3::prelude::*;
use tumble::{BallJoint, DVec3, JointDef, JointKind};

use crate::arrays::vec3_out;
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
}

fn def(a: BodyId, b: BodyId, anchor: DVec3, kind: JointKind, common: CommonArgs) -> JointDef {
    JointDef { name: common.name, break_force: common.break_force, ..JointDef::new(a.0, b.0, anchor, kind) }
}

/// A ball-and-socket joint: the two bodies share the point `anchor` (world frame, at creation).
pub fn ball_def(a: BodyId, b: BodyId, anchor: DVec3, common: CommonArgs) -> JointDef {
    def(a, b, anchor, JointKind::Ball(BallJoint::new()), common)
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
    #[getter]
    fn id(&self) -> JointId {
        self.id
    }
    #[getter]
    fn name(&self, py: Python<'_>) -> PyResult<String> {
        self.read(py, |_, j| Ok(j.name().to_string()))
    }
    /// "ball" (more kinds as the core gains them).
    #[getter]
    fn kind(&self, py: Python<'_>) -> PyResult<&'static str> {
        self.read(py, |_, j| Ok(j.kind().name()))
    }
    #[getter]
    fn body_a(&self, py: Python<'_>) -> PyResult<BodyId> {
        self.read(py, |_, j| Ok(BodyId(j.body_a())))
    }
    #[getter]
    fn body_b(&self, py: Python<'_>) -> PyResult<BodyId> {
        self.read(py, |_, j| Ok(BodyId(j.body_b())))
    }
    /// True once the constraint force exceeded `break_force`; a broken joint no longer acts.
    #[getter]
    fn is_broken(&self, py: Python<'_>) -> PyResult<bool> {
        self.read(py, |_, j| Ok(j.is_broken()))
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
