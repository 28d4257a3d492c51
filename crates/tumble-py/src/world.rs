//! `tumble.World` and `tumble.step_many`.
//!
//! Flat state arrays (MuJoCo style): `positions` (N, 3), `orientations` (N, 4, x y z w),
//! `linear_velocities` (N, 3), `angular_velocities` (N, 3), float64, one row per live body in
//! body-slot order (`body_ids` gives the handle of each row). Reading copies; setting checks the
//! whole array first, then writes (see `arrays::set_state_rows`).
//!
//! Stepping releases the GIL: other Python threads run while the core steps. The world is
//! mutably borrowed meanwhile, so another thread touching the same world gets a `RuntimeError`
//! ("Already borrowed") rather than a data race.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rayon::prelude::*;
use tumble::dynamics::SleepSettings;
use tumble::{DVec3, DistanceJoint, SolverSettings, WorldDef};

use crate::arrays::{self, opt_vec3, rows_out, vec3, vec3_out};
use crate::bodies::{Body, BodyArgs, BodyId};
use crate::errors::{value_error, IntoPyResult};
use crate::joints::{self, CommonArgs, Joint, JointId};
use crate::mass::MassProperties;
use crate::queries::{self, RayHit};
use crate::shapes::Shape;

/// A rigid-body world: bodies, joints and the solver that steps them.
///
/// `World(gravity=(0, 0, -9.81), substeps=8, sleep=True)`: gravity in m/s² (Z up), solver
/// substeps per step (default: the engine's, 8), and whether resting bodies may fall asleep. Add bodies with `add_body`,
/// joints with `add_*_joint`, advance with `step(dt, n=1)`; read and write the whole state as
/// NumPy arrays (`positions`, `orientations`, `linear_velocities`, `angular_velocities`, one row
/// per body in body-slot order, see `body_ids`). `World.from_scene(path)` builds a TOML scene,
/// `save()` / `World.load(data)` snapshot a world exactly.
#[pyclass(module = "tumble")]
pub struct World {
    pub inner: tumble::World,
}

/// Steps `world` `n` times; an invalid `dt` fails on the first step, before anything changes.
fn step_n(world: &mut tumble::World, dt: f64, n: u64) -> Result<(), tumble::WorldError> {
    (0..n).try_for_each(|_| world.step(dt))
}

#[pymethods]
impl World {
    #[new]
    #[pyo3(signature = (gravity = None, substeps = None, sleep = true))]
    fn new(gravity: Option<&Bound<'_, PyAny>>, substeps: Option<u32>, sleep: bool) -> PyResult<Self> {
        let def = WorldDef::default();
        let def = WorldDef {
            gravity: opt_vec3(gravity, "gravity")?.unwrap_or(def.gravity),
            solver: SolverSettings { substeps: substeps.unwrap_or(def.solver.substeps), ..def.solver },
            sleep: SleepSettings { enabled: sleep, ..def.sleep },
        };
        Ok(World { inner: tumble::World::new(def).py()? })
    }

    // ---- settings and counters ------------------------------------------------------------------

    /// Gravity, m/s², (3,).
    #[getter]
    fn gravity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(py, self.inner.gravity())
    }
    #[setter]
    fn set_gravity(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.set_gravity(vec3(value, "gravity")?).py()
    }
    /// Solver substeps per step.
    #[getter]
    fn substeps(&self) -> u32 {
        self.inner.solver_settings().substeps
    }
    #[setter]
    fn set_substeps(&mut self, substeps: u32) -> PyResult<()> {
        let settings = SolverSettings { substeps, ..self.inner.solver_settings().clone() };
        self.inner.set_solver_settings(settings).py()
    }
    /// Simulated time, s.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }
    /// Number of steps taken so far.
    #[getter]
    fn step_count(&self) -> u64 {
        self.inner.step_count()
    }
    /// Number of live bodies (also `len(world)`).
    #[getter]
    fn body_count(&self) -> usize {
        self.inner.body_count()
    }
    /// Number of dynamic bodies that are awake (not sleeping).
    #[getter]
    fn awake_body_count(&self) -> usize {
        self.inner.awake_body_count()
    }
    /// Number of live joints.
    #[getter]
    fn joint_count(&self) -> usize {
        self.inner.joint_count()
    }
    fn __len__(&self) -> usize {
        self.inner.body_count()
    }
    /// Handles of the live bodies in body-slot order: row i of every state array is body_ids[i].
    #[getter]
    fn body_ids(&self) -> Vec<BodyId> {
        self.inner.bodies().map(|(id, _)| BodyId(id)).collect()
    }
    /// Handles of the joints in slot order.
    #[getter]
    fn joint_ids(&self) -> Vec<JointId> {
        self.inner.joints().map(|(id, _)| JointId(id)).collect()
    }

    // ---- bodies ---------------------------------------------------------------------------------

    /// Adds a body and returns its handle. Checked in full by the core first; on error nothing
    /// changes. Give `shape` with `density` (kg/m³) or `mass` (kg), or `mass_properties`.
    /// `friction`, `restitution`, `rolling_friction` and `torsional_friction` make the surface
    /// material; `group`/`mask` the collision filter bits; a `sensor` reports overlaps only; a
    /// `bullet` is swept against static geometry each step, so it cannot pass through thin walls.
    #[pyo3(signature = (shape = None, *, density = 1000.0, mass = None, mass_properties = None,
        position = None, orientation = None, linear_velocity = None, angular_velocity = None,
        kind = "dynamic", name = "", linear_damping = 0.0, angular_damping = 0.0,
        gravity_scale = 1.0, allow_sleep = true, friction = 0.6, restitution = 0.0,
        rolling_friction = 0.0, torsional_friction = 0.0, group = 1, mask = 4294967295, sensor = false,
        bullet = false))]
    #[allow(clippy::too_many_arguments)]
    fn add_body(
        &mut self,
        shape: Option<&Bound<'_, Shape>>,
        density: f64,
        mass: Option<f64>,
        mass_properties: Option<&Bound<'_, MassProperties>>,
        position: Option<&Bound<'_, PyAny>>,
        orientation: Option<&Bound<'_, PyAny>>,
        linear_velocity: Option<&Bound<'_, PyAny>>,
        angular_velocity: Option<&Bound<'_, PyAny>>,
        kind: &str,
        name: &str,
        linear_damping: f64,
        angular_damping: f64,
        gravity_scale: f64,
        allow_sleep: bool,
        friction: f64,
        restitution: f64,
        rolling_friction: f64,
        torsional_friction: f64,
        group: u32,
        mask: u32,
        sensor: bool,
        bullet: bool,
    ) -> PyResult<BodyId> {
        let def = BodyArgs {
            shape,
            density,
            mass,
            mass_properties,
            position,
            orientation,
            linear_velocity,
            angular_velocity,
            kind,
            name: name.to_string(),
            linear_damping,
            angular_damping,
            gravity_scale,
            allow_sleep,
            material: tumble::Material { friction, restitution, rolling_friction, torsional_friction },
            filter: tumble::CollisionFilter { group, mask },
            sensor,
            bullet,
        }
        .into_def()?;
        Ok(BodyId(self.inner.add_body(def).py()?))
    }

    /// Removes a body and the joints attached to it; its handle becomes stale.
    fn remove_body(&mut self, body: BodyId) -> PyResult<()> {
        self.inner.remove_body(body.0).py().map(drop)
    }

    /// A live view of one body.
    fn body(slf: &Bound<'_, Self>, body: BodyId) -> PyResult<Body> {
        slf.borrow().inner.body(body.0).py()?;
        Ok(Body { world: slf.clone().unbind(), id: body })
    }

    /// The first body with this name, or None.
    fn find_body(&self, name: &str) -> Option<BodyId> {
        self.inner.find_body(name).map(BodyId)
    }

    /// Places the body frame's origin at `position` with `orientation` (x, y, z, w; normalised).
    fn set_pose(
        &mut self,
        body: BodyId,
        position: &Bound<'_, PyAny>,
        orientation: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (p, q) = (vec3(position, "position")?, arrays::quat(orientation, "orientation")?);
        self.inner.set_pose(body.0, p, q).py()
    }

    /// Wakes `body` (and the island it rests in) if it is asleep.
    fn wake_body(&mut self, body: BodyId) -> PyResult<()> {
        self.inner.wake_body(body.0).py()
    }

    // ---- joints ---------------------------------------------------------------------------------

    /// Ball-and-socket joint: bodies `a` and `b` share the world point `anchor` (at creation).
    /// `swing_limit` (rad) bounds the angle between the bodies' `axis`; `twist_limits` (lower,
    /// upper) the twist about it; `friction_torque` (N·m) resists relative rotation.
    #[pyo3(signature = (a, b, anchor, *, axis = None, swing_limit = None, twist_limits = None,
        friction_torque = 0.0, name = "", break_force = None, break_torque = None,
        collide_connected = false))]
    #[allow(clippy::too_many_arguments)]
    fn add_ball_joint(
        &mut self,
        a: BodyId,
        b: BodyId,
        anchor: &Bound<'_, PyAny>,
        axis: Option<&Bound<'_, PyAny>>,
        swing_limit: Option<f64>,
        twist_limits: Option<&Bound<'_, PyAny>>,
        friction_torque: f64,
        name: &str,
        break_force: Option<f64>,
        break_torque: Option<f64>,
        collide_connected: bool,
    ) -> PyResult<JointId> {
        let common = CommonArgs { name: name.into(), break_force, break_torque, collide_connected };
        let axis = opt_vec3(axis, "axis")?.unwrap_or(DVec3::Z);
        let twist = joints::limits(twist_limits, "twist_limits")?;
        let def = joints::ball_def(
            (a, b, vec3(anchor, "anchor")?, axis),
            (swing_limit, twist, friction_torque),
            common,
        );
        Ok(JointId(self.inner.add_joint(def).py()?))
    }

    /// Hinge joint about `axis` through `anchor` (world frame, at creation). `limits` =
    /// (lower, upper) angle in rad, `motor` = (target_speed rad/s, max_torque N·m), `spring` =
    /// (hertz, damping_ratio) towards `spring_target` (rad).
    #[pyo3(signature = (a, b, anchor, axis, limits = None, motor = None, spring = None, *,
        spring_target = 0.0, name = "", break_force = None, break_torque = None, collide_connected = false))]
    #[allow(clippy::too_many_arguments)]
    fn add_hinge_joint(
        &mut self,
        a: BodyId,
        b: BodyId,
        anchor: &Bound<'_, PyAny>,
        axis: &Bound<'_, PyAny>,
        limits: Option<&Bound<'_, PyAny>>,
        motor: Option<&Bound<'_, PyAny>>,
        spring: Option<&Bound<'_, PyAny>>,
        spring_target: f64,
        name: &str,
        break_force: Option<f64>,
        break_torque: Option<f64>,
        collide_connected: bool,
    ) -> PyResult<JointId> {
        let common = CommonArgs { name: name.into(), break_force, break_torque, collide_connected };
        let drive = joints::DriveArgs { limits, motor, spring, spring_target };
        let (anchor, axis) = (vec3(anchor, "anchor")?, vec3(axis, "axis")?);
        Ok(JointId(self.inner.add_joint(joints::hinge_def(a, b, anchor, axis, drive, common)?).py()?))
    }

    /// Slider joint along `axis`: `limits` (m), `motor` = (target_speed m/s, max_force N),
    /// `spring` = (hertz, damping_ratio) towards `spring_target` (m).
    #[pyo3(signature = (a, b, anchor, axis, limits = None, motor = None, spring = None, *,
        spring_target = 0.0, name = "", break_force = None, break_torque = None, collide_connected = false))]
    #[allow(clippy::too_many_arguments)]
    fn add_slider_joint(
        &mut self,
        a: BodyId,
        b: BodyId,
        anchor: &Bound<'_, PyAny>,
        axis: &Bound<'_, PyAny>,
        limits: Option<&Bound<'_, PyAny>>,
        motor: Option<&Bound<'_, PyAny>>,
        spring: Option<&Bound<'_, PyAny>>,
        spring_target: f64,
        name: &str,
        break_force: Option<f64>,
        break_torque: Option<f64>,
        collide_connected: bool,
    ) -> PyResult<JointId> {
        let common = CommonArgs { name: name.into(), break_force, break_torque, collide_connected };
        let drive = joints::DriveArgs { limits, motor, spring, spring_target };
        let (anchor, axis) = (vec3(anchor, "anchor")?, vec3(axis, "axis")?);
        Ok(JointId(self.inner.add_joint(joints::slider_def(a, b, anchor, axis, drive, common)?).py()?))
    }

    /// Fixed (weld) joint at `anchor`: no relative motion.
    #[pyo3(signature = (a, b, anchor, *, name = "", break_force = None, break_torque = None,
        collide_connected = false))]
    #[allow(clippy::too_many_arguments)]
    fn add_fixed_joint(
        &mut self,
        a: BodyId,
        b: BodyId,
        anchor: &Bound<'_, PyAny>,
        name: &str,
        break_force: Option<f64>,
        break_torque: Option<f64>,
        collide_connected: bool,
    ) -> PyResult<JointId> {
        let common = CommonArgs { name: name.into(), break_force, break_torque, collide_connected };
        Ok(JointId(self.inner.add_joint(joints::fixed_def(a, b, vec3(anchor, "anchor")?, common)).py()?))
    }

    /// Distance joint between `anchor_a` on a and `anchor_b` on b (world frame, at creation):
    /// rigid at `length` (default: the distance now), or a `spring` = (hertz, damping_ratio);
    /// always within [`min_length`, `max_length`] (default 0 and infinity).
    #[pyo3(signature = (a, b, anchor_a, anchor_b, *, length = None, min_length = 0.0,
        max_length = f64::INFINITY, spring = None, name = "", break_force = None, collide_connected = false))]
    #[allow(clippy::too_many_arguments)]
    fn add_distance_joint(
        &mut self,
        a: BodyId,
        b: BodyId,
        anchor_a: &Bound<'_, PyAny>,
        anchor_b: &Bound<'_, PyAny>,
        length: Option<f64>,
        min_length: f64,
        max_length: f64,
        spring: Option<&Bound<'_, PyAny>>,
        name: &str,
        break_force: Option<f64>,
        collide_connected: bool,
    ) -> PyResult<JointId> {
        let common = CommonArgs { name: name.into(), break_force, break_torque: None, collide_connected };
        let settings = DistanceJoint { length, min_length, max_length, spring: joints::spring(spring)? };
        let anchors = (a, b, vec3(anchor_a, "anchor_a")?, vec3(anchor_b, "anchor_b")?);
        Ok(JointId(self.inner.add_joint(joints::distance_def(anchors, settings, common)).py()?))
    }

    /// Removes a joint; its handle becomes stale.
    fn remove_joint(&mut self, joint: JointId) -> PyResult<()> {
        self.inner.remove_joint(joint.0).py().map(drop)
    }

    /// A live view of one joint.
    fn joint(slf: &Bound<'_, Self>, joint: JointId) -> PyResult<Joint> {
        slf.borrow().inner.joint(joint.0).py()?;
        Ok(Joint { world: slf.clone().unbind(), id: joint })
    }

    // ---- forces and impulses ----------------------------------------------------------------------

    /// Adds `force` (world frame, N) at world `point`, or at the centre of mass when `point` is
    /// None. Acts during the next step only.
    #[pyo3(signature = (body, force, point = None))]
    fn apply_force(
        &mut self,
        body: BodyId,
        force: &Bound<'_, PyAny>,
        point: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let f = vec3(force, "force")?;
        match opt_vec3(point, "point")? {
            Some(p) => self.inner.apply_force_at_point(body.0, f, p),
            None => self.inner.apply_force(body.0, f),
        }
        .py()
    }

    /// Adds a torque about the centre of mass (world frame, N·m) for the next step.
    fn apply_torque(&mut self, body: BodyId, torque: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.apply_torque(body.0, vec3(torque, "torque")?).py()
    }

    /// Applies `impulse` (N·s) now at world `point` (the centre of mass when None).
    #[pyo3(signature = (body, impulse, point = None))]
    fn apply_impulse(
        &mut self,
        body: BodyId,
        impulse: &Bound<'_, PyAny>,
        point: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let j = vec3(impulse, "impulse")?;
        let p = match opt_vec3(point, "point")? {
            Some(p) => p,
            None => self.inner.body(body.0).py()?.com_world(),
        };
        self.inner.apply_impulse_at_point(body.0, j, p).py()
    }

    /// Applies an angular impulse (world frame, N·m·s) now.
    fn apply_angular_impulse(&mut self, body: BodyId, angular_impulse: &Bound<'_, PyAny>) -> PyResult<()> {
        self.inner.apply_angular_impulse(body.0, vec3(angular_impulse, "angular_impulse")?).py()
    }

    // ---- queries --------------------------------------------------------------------------------

    /// Velocity of the body's material point now at world `point`, (3,).
    fn point_velocity<'py>(
        &self,
        py: Python<'py>,
        body: BodyId,
        point: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        Ok(vec3_out(py, self.inner.point_velocity(body.0, vec3(point, "point")?).py()?))
    }

    /// Acceleration of the body's material point now at world `point` from gravity and the
    /// accumulated forces, (3,).
    fn point_acceleration<'py>(
        &self,
        py: Python<'py>,
        body: BodyId,
        point: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        Ok(vec3_out(py, self.inner.point_acceleration(body.0, vec3(point, "point")?).py()?))
    }

    /// The point inverse mass matrix K(r1, r2) = (1/m)·1 − [r2]× I⁻¹ [r1]×, (3, 3): an impulse j
    /// at offset r1 from the centre of mass changes the velocity of the point at offset r2 by K j.
    fn inverse_mass_matrix<'py>(
        &self,
        py: Python<'py>,
        body: BodyId,
        r1: &Bound<'_, PyAny>,
        r2: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let k = self.inner.inverse_mass_matrix(body.0, vec3(r1, "r1")?, vec3(r2, "r2")?).py()?;
        arrays::mat3_out(py, k)
    }

    /// Total kinetic energy of the dynamic bodies, J.
    fn kinetic_energy(&self) -> f64 {
        self.inner.kinetic_energy()
    }
    /// Total gravitational potential energy of the dynamic bodies, −m g·x, J.
    fn potential_energy(&self) -> f64 {
        self.inner.potential_energy()
    }
    /// Total linear momentum of the dynamic bodies, (3,).
    fn linear_momentum<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(py, self.inner.linear_momentum())
    }
    /// Total angular momentum of the dynamic bodies about the fixed world point `about`, (3,).
    #[pyo3(signature = (about = None))]
    fn angular_momentum<'py>(
        &self,
        py: Python<'py>,
        about: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let origin = opt_vec3(about, "about")?.unwrap_or(DVec3::ZERO);
        Ok(vec3_out(py, self.inner.angular_momentum(origin)))
    }

    /// Touching contacts, one row per contact point: a structured array with fields `body_a`,
    /// `body_b` (int64 slot indices, `BodyId.index`), `point` (3,), `normal` (3,, from a to b),
    /// `separation`, `impulse` (normal impulse of the last step, N·s) and `sensor`.
    fn contacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        queries::contacts_array(py, &self.inner)
    }
    /// Number of touching contact manifolds.
    #[getter]
    fn contact_count(&self) -> usize {
        self.inner.contact_count()
    }

    /// The closest body hit by the ray from `origin` along `direction` (normalised) within
    /// `max_distance` (default infinity), as a `RayHit`, or None. Sensors are skipped unless `include_sensors`; the
    /// ray's `group`/`mask` filter bodies like a shape's.
    #[pyo3(signature = (origin, direction, max_distance = f64::INFINITY, *, include_sensors = false,
        group = 4294967295, mask = 4294967295))]
    fn raycast(
        &self,
        origin: &Bound<'_, PyAny>,
        direction: &Bound<'_, PyAny>,
        max_distance: f64,
        include_sensors: bool,
        group: u32,
        mask: u32,
    ) -> PyResult<Option<RayHit>> {
        let (o, d) = queries::ray_args(origin, direction)?;
        let filter = queries::filter(group, mask, include_sensors);
        let hit = self.inner.ray_cast(o, d, max_distance, Some(&filter)).map_err(queries::query_error)?;
        Ok(hit.map(RayHit::from))
    }

    /// Every body the ray hits (each once, its closest hit), sorted by distance then body.
    #[pyo3(signature = (origin, direction, max_distance = f64::INFINITY, *, include_sensors = false,
        group = 4294967295, mask = 4294967295))]
    fn raycast_all(
        &self,
        origin: &Bound<'_, PyAny>,
        direction: &Bound<'_, PyAny>,
        max_distance: f64,
        include_sensors: bool,
        group: u32,
        mask: u32,
    ) -> PyResult<Vec<RayHit>> {
        let (o, d) = queries::ray_args(origin, direction)?;
        let filter = queries::filter(group, mask, include_sensors);
        let hits =
            self.inner.ray_cast_all(o, d, max_distance, Some(&filter)).map_err(queries::query_error)?;
        Ok(hits.into_iter().map(RayHit::from).collect())
    }

    /// Pairs of bodies that began touching in the last step, [(a, b), ...], a < b.
    fn contact_begin_events(&self) -> Vec<(BodyId, BodyId)> {
        queries::pairs(self.inner.contact_begin_events())
    }
    /// Pairs of bodies that stopped touching in the last step.
    fn contact_end_events(&self) -> Vec<(BodyId, BodyId)> {
        queries::pairs(self.inner.contact_end_events())
    }
    /// Pairs (sensor and other body, by id) that began to overlap in the last step.
    fn sensor_begin_events(&self) -> Vec<(BodyId, BodyId)> {
        queries::pairs(self.inner.sensor_begin_events())
    }
    /// Pairs (sensor and other body, by id) that stopped overlapping in the last step.
    fn sensor_end_events(&self) -> Vec<(BodyId, BodyId)> {
        queries::pairs(self.inner.sensor_end_events())
    }

    /// A world built from a scene file (TOML, see the scene format); errors name the file, the
    /// line and the key. Find bodies by name with `find_body`.
    #[staticmethod]
    fn from_scene(path: std::path::PathBuf) -> PyResult<World> {
        Ok(World { inner: queries::world_from_scene(&path)? })
    }

    // ---- snapshots --------------------------------------------------------------------------------

    /// The world's complete state as bytes: `World.load(data)` rebuilds a world whose future is
    /// bit-identical to this one's.
    fn save<'py>(&self, py: Python<'py>) -> Bound<'py, pyo3::types::PyBytes> {
        pyo3::types::PyBytes::new(py, &self.inner.snapshot())
    }

    /// A world rebuilt from `save()` bytes; a truncated, foreign or damaged snapshot raises
    /// `TumbleValueError` saying which.
    #[staticmethod]
    fn load(data: &[u8]) -> PyResult<World> {
        tumble::World::restore(data)
            .map(|inner| World { inner })
            .map_err(|e| crate::errors::value_error(e.to_string()))
    }

    /// A 64-bit fingerprint of the exact state: equal hashes mean bit-identical worlds.
    fn state_hash(&self) -> u64 {
        self.inner.state_hash()
    }

    // ---- stepping -------------------------------------------------------------------------------

    /// Advances the world by `n` steps of `dt` seconds, with the GIL released.
    #[pyo3(signature = (dt, n = 1))]
    fn step(mut slf: PyRefMut<'_, Self>, dt: f64, n: u64) -> PyResult<()> {
        let py = slf.py();
        let world = &mut slf.inner;
        py.detach(|| step_n(world, dt, n)).py()
    }

    // ---- flat state arrays ----------------------------------------------------------------------

    /// Body-frame origins, (N, 3), body-slot order. Set: moves every body (keeps orientations).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        rows_out(py, &arrays::state_rows(&self.inner, |b| b.position().to_array()))
    }
    #[setter]
    fn set_positions(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        arrays::set_state_rows::<3>(
            &mut self.inner,
            value,
            "positions",
            |_| None,
            |w, id, p| {
                let q = w.body(id)?.orientation();
                w.set_pose(id, DVec3::from_array(p), q)
            },
        )
    }
    /// Orientations (x, y, z, w), (N, 4), body-slot order. Set: unit quaternions, positions kept.
    #[getter]
    fn orientations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        rows_out(py, &arrays::state_rows(&self.inner, |b| b.orientation().to_array()))
    }
    #[setter]
    fn set_orientations(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        arrays::set_state_rows::<4>(
            &mut self.inner,
            value,
            "orientations",
            arrays::unit_quat_check,
            |w, id, q| {
                let p = w.body(id)?.position();
                w.set_pose(id, p, tumble::DQuat::from_array(q))
            },
        )
    }
    /// Velocities of the centres of mass, world frame, (N, 3). Set: ignored for static bodies.
    #[getter]
    fn linear_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        rows_out(py, &arrays::state_rows(&self.inner, |b| b.linear_velocity().to_array()))
    }
    #[setter]
    fn set_linear_velocities(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        arrays::set_state_rows::<3>(
            &mut self.inner,
            value,
            "linear_velocities",
            |_| None,
            |w, id, v| w.set_linear_velocity(id, DVec3::from_array(v)),
        )
    }
    /// Angular velocities, world frame, (N, 3). Set: ignored for static bodies.
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        rows_out(py, &arrays::state_rows(&self.inner, |b| b.angular_velocity().to_array()))
    }
    #[setter]
    fn set_angular_velocities(&mut self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        arrays::set_state_rows::<3>(
            &mut self.inner,
            value,
            "angular_velocities",
            |_| None,
            |w, id, v| w.set_angular_velocity(id, DVec3::from_array(v)),
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "World(bodies={}, joints={}, time={}, gravity={:?})",
            self.inner.body_count(),
            self.inner.joint_count(),
            self.inner.time(),
            self.inner.gravity().to_array()
        )
    }
}

/// Steps every world in `worlds` `n` times by `dt`, in parallel on all cores with the GIL
/// released. Each world is stepped on its own, so the results are identical to stepping them one
/// by one. A world may appear only once. NumPy's OpenBLAS threads spin for a while after any
/// BLAS call and compete for the same cores: set `OPENBLAS_NUM_THREADS=1` for full speed.
#[pyfunction]
#[pyo3(signature = (worlds, dt, n = 1))]
pub fn step_many(py: Python<'_>, worlds: &Bound<'_, PyAny>, dt: f64, n: u64) -> PyResult<()> {
    let mut borrowed: Vec<PyRefMut<'_, World>> = Vec::new();
    for (i, item) in worlds.try_iter()?.enumerate() {
        let item = item?;
        let world = item.cast::<World>().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(format!("worlds[{i}] is not a tumble.World"))
        })?;
        let world = world.try_borrow_mut().map_err(|_| {
            value_error(format!("worlds[{i}] appears twice in worlds (or is in use by another thread)"))
        })?;
        borrowed.push(world);
    }
    let mut inner: Vec<&mut tumble::World> = borrowed.iter_mut().map(|w| &mut w.inner).collect();
    py.detach(|| inner.par_iter_mut().try_for_each(|w| step_n(w, dt, n))).py()
}
