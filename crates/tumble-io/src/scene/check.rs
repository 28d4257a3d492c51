//! Turning the raw file into a checked [`Scene`]: every impossible value is an error that names
//! the file, the line and the key (`scene.toml:14: body "arm": density must be > 0, got -2`).
//!
//! The checks here repeat some the core does (`Sphere::new`, `World::add_body`) on purpose: the
//! core cannot know the line or the key a value came from, and a user fixing a file needs both.

use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use toml::Spanned;
use tumble::{
    BodyDef, BodyKind, Capsule, CollisionFilter, Compound, CompoundChild, Cone, ConvexHull, Cuboid, Cylinder,
    DQuat, DVec3, Shape, SleepSettings, SolverSettings, Sphere, TriMesh,
};

use super::raw::{Integer, Number, Quat, RawBody, RawKind, RawScene, RawShape, RawWorld, ShapeType, Vec3};
use super::{Scene, SceneBody, DEFAULT_DT, DEFAULT_DURATION};
use crate::error::{line_of, IoError};

/// How far from 1 a quaternion's length may be (rounding in a hand-written file, not a typo).
pub const UNIT_QUATERNION_TOLERANCE: f64 = 1e-6;

/// What the checks need to report errors and to load meshes.
pub(super) struct Checker<'a> {
    pub text: &'a str,
    pub path: &'a Path,
    pub mesh_loader: &'a mut dyn FnMut(&Path) -> std::result::Result<TriMesh, IoError>,
}

/// Results of the checks.
type Result<T> = std::result::Result<T, IoError>;

impl Checker<'_> {
    pub fn error(&self, span: Range<usize>, message: String) -> IoError {
        IoError::AtLine { path: self.path.to_owned(), line: line_of(self.text, span.start), message }
    }

    pub fn scene(&mut self, raw: RawScene) -> Result<Scene> {
        let (gravity, dt, duration) = match &raw.world {
            Some(w) => (
                self.vec3_or("world: ", "gravity", &w.gravity, DVec3::new(0.0, 0.0, -9.81))?,
                match &w.dt {
                    Some(dt) => self.number("world: ", "dt", dt, |v| v > 0.0, "> 0")?,
                    None => DEFAULT_DT,
                },
                match &w.duration {
                    Some(d) => self.number("world: ", "duration", d, |v| v >= 0.0, ">= 0")?,
                    None => DEFAULT_DURATION,
                },
            ),
            None => (DVec3::new(0.0, 0.0, -9.81), DEFAULT_DT, DEFAULT_DURATION),
        };

        let mut first_line_of_name: HashMap<String, usize> = HashMap::new();
        let mut bodies = Vec::with_capacity(raw.body.len());
        for raw_body in &raw.body {
            let name = raw_body.get_ref().name.get_ref();
            let name_line = line_of(self.text, raw_body.get_ref().name.span().start);
            if let Some(first) = first_line_of_name.get(name) {
                return Err(self.error(
                    raw_body.get_ref().name.span(),
                    format!(
                        "body name \"{name}\" is used twice (first on line {first}); names must be unique"
                    ),
                ));
            }
            first_line_of_name.insert(name.clone(), name_line);
            bodies.push(self.body(raw_body)?);
        }
        let (solver, sleep) = self.solver(raw.world.as_ref())?;
        let joints = self.joints(&raw.joint, &first_line_of_name)?;
        Ok(Scene { path: self.path.to_owned(), gravity, dt, duration, solver, sleep, bodies, joints })
    }

    /// The solver and sleep keys of `[world]`; unset keys keep the engine's defaults.
    fn solver(&self, world: Option<&RawWorld>) -> Result<(SolverSettings, SleepSettings)> {
        let (mut solver, mut sleep) = (SolverSettings::default(), SleepSettings::default());
        let Some(w) = world else { return Ok((solver, sleep)) };
        let at = "world: ";
        let count = |key: &str, v: &Option<Integer>, min: i64, default: u32| match v {
            Some(v) => self.integer(at, key, v, min, 1000).map(|n| n as u32),
            None => Ok(default),
        };
        solver.substeps = count("substeps", &w.substeps, 1, solver.substeps)?;
        solver.solve_iterations = count("solve_iterations", &w.solve_iterations, 1, solver.solve_iterations)?;
        solver.relax_iterations = count("relax_iterations", &w.relax_iterations, 0, solver.relax_iterations)?;
        solver.joint_projection_iterations = count(
            "joint_projection_iterations",
            &w.joint_projection_iterations,
            0,
            solver.joint_projection_iterations,
        )?;
        let non_negative = |v: f64| v >= 0.0;
        for (key, value, target) in [
            ("contact_hertz", &w.contact_hertz, &mut solver.contact_hertz),
            ("contact_damping_ratio", &w.contact_damping_ratio, &mut solver.contact_damping_ratio),
            ("joint_hertz", &w.joint_hertz, &mut solver.joint_hertz),
            ("joint_damping_ratio", &w.joint_damping_ratio, &mut solver.joint_damping_ratio),
            ("steady_load_time", &w.steady_load_time, &mut solver.steady_load_time),
            (
                "joint_projection_tolerance",
                &w.joint_projection_tolerance,
                &mut solver.joint_projection_tolerance,
            ),
        ] {
            *target = self.number_or(at, key, value, *target, non_negative, ">= 0")?;
        }
        solver.joint_trees = w.joint_trees.unwrap_or(solver.joint_trees);
        solver.joint_tree_limits = w.joint_tree_limits.unwrap_or(solver.joint_tree_limits);
        sleep.enabled = w.sleep.unwrap_or(sleep.enabled);
        Ok((solver, sleep))
    }

    /// A whole number in `[min, max]`.
    pub fn integer(&self, at: &str, key: &str, v: &Integer, min: i64, max: i64) -> Result<i64> {
        let value = *v.get_ref();
        if !(min..=max).contains(&value) {
            return Err(
                self.error(v.span(), format!("{at}{key} must be between {min} and {max}, got {value}"))
            );
        }
        Ok(value)
    }

    fn body(&mut self, spanned: &Spanned<RawBody>) -> Result<SceneBody> {
        let raw = spanned.get_ref();
        let name = raw.name.get_ref().clone();
        if name.trim().is_empty() {
            return Err(self.error(raw.name.span(), "body: name must not be empty".into()));
        }
        let at = format!("body \"{name}\": ");
        let at = at.as_str();

        let defaults = BodyDef::default();
        let kind = match raw.kind.as_ref().map(|k| *k.get_ref()) {
            None | Some(RawKind::Dynamic) => BodyKind::Dynamic,
            Some(RawKind::Static) => BodyKind::Static,
            Some(RawKind::Kinematic) => BodyKind::Kinematic,
        };
        let positive = |v: f64| v > 0.0;
        let non_negative = |v: f64| v >= 0.0;
        let mass = match (&raw.density, &raw.mass) {
            (Some(_), Some(mass)) => {
                return Err(self.error(mass.span(), format!("{at}give either density or mass, not both")))
            }
            (_, Some(mass)) => Some(self.number(at, "mass", mass, positive, "> 0")?),
            _ => None,
        };
        let density = match &raw.density {
            Some(d) => self.number(at, "density", d, positive, "> 0")?,
            None => defaults.density,
        };
        let shape = self.shape(at, "shape", &raw.shape)?;
        // `..defaults` is there for fields the core adds later: they take the engine's default
        // until the scene format learns them, instead of breaking this crate's build.
        #[allow(clippy::needless_update)]
        let def = BodyDef {
            name,
            kind,
            shape: Some(shape),
            density,
            mass,
            mass_properties: None,
            position: self.vec3_or(at, "position", &raw.position, DVec3::ZERO)?,
            orientation: self.quat_or_identity(at, "orientation", &raw.orientation)?,
            linear_velocity: self.vec3_or(at, "linear_velocity", &raw.linear_velocity, DVec3::ZERO)?,
            angular_velocity: self.vec3_or(at, "angular_velocity", &raw.angular_velocity, DVec3::ZERO)?,
            linear_damping: self.number_or(
                at,
                "linear_damping",
                &raw.linear_damping,
                0.0,
                non_negative,
                ">= 0",
            )?,
            angular_damping: self.number_or(
                at,
                "angular_damping",
                &raw.angular_damping,
                0.0,
                non_negative,
                ">= 0",
            )?,
            gravity_scale: self.number_or(at, "gravity_scale", &raw.gravity_scale, 1.0, |_| true, "")?,
            allow_sleep: raw.allow_sleep.unwrap_or(defaults.allow_sleep),
            material: self.material(at, raw)?,
            filter: self.filter(at, raw)?,
            is_sensor: raw.sensor.unwrap_or(defaults.is_sensor),
            bullet: raw.bullet.unwrap_or(defaults.bullet),
            ..defaults
        };
        Ok(SceneBody { def, line: line_of(self.text, raw.name.span().start) })
    }

    /// Surface material; unset coefficients keep the engine's defaults.
    fn material(&self, at: &str, raw: &RawBody) -> Result<tumble::Material> {
        let d = tumble::Material::default();
        let non_negative = |v: f64| v >= 0.0;
        Ok(tumble::Material {
            friction: self.number_or(at, "friction", &raw.friction, d.friction, non_negative, ">= 0")?,
            restitution: self.number_or(
                at,
                "restitution",
                &raw.restitution,
                d.restitution,
                |v| (0.0..=1.0).contains(&v),
                "in [0, 1]",
            )?,
            rolling_friction: self.number_or(
                at,
                "rolling_friction",
                &raw.rolling_friction,
                d.rolling_friction,
                non_negative,
                ">= 0",
            )?,
            torsional_friction: self.number_or(
                at,
                "torsional_friction",
                &raw.torsional_friction,
                d.torsional_friction,
                non_negative,
                ">= 0",
            )?,
        })
    }

    /// Collision group and mask bits (u32); unset ones keep the defaults (group 1, mask all).
    fn filter(&self, at: &str, raw: &RawBody) -> Result<CollisionFilter> {
        let d = CollisionFilter::default();
        let bits = |key: &str, v: &Option<Integer>, default: u32| match v {
            Some(v) => self.integer(at, key, v, 0, i64::from(u32::MAX)).map(|n| n as u32),
            None => Ok(default),
        };
        Ok(CollisionFilter {
            group: bits("group", &raw.group, d.group)?,
            mask: bits("mask", &raw.mask, d.mask)?,
        })
    }

    /// A shape at `key` (e.g. `shape` or `shape.parts[2].shape`).
    fn shape(&mut self, at: &str, key: &str, spanned: &Spanned<RawShape>) -> Result<Shape> {
        let raw = spanned.get_ref();
        let ty = *raw.kind.get_ref();
        let wanted = ty.keys();
        for (present, offset) in raw.present_keys() {
            if !wanted.contains(&present) {
                return Err(self.error(
                    offset..offset,
                    format!(
                        "{at}{key}.{present}: a {} shape takes no `{present}` (it takes {})",
                        ty.name(),
                        list_keys(wanted)
                    ),
                ));
            }
        }
        let missing = |this: &Self, what: &str| {
            this.error(
                spanned.span(),
                format!("{at}{key}: a {} shape needs `{what}` (it takes {})", ty.name(), list_keys(wanted)),
            )
        };
        let length = |this: &Self, name: &str, v: &Option<Number>| match v {
            Some(v) => this.number(at, &format!("{key}.{name}"), v, |x| x > 0.0, "> 0"),
            None => Err(missing(this, name)),
        };
        // The core constructors check the same things; their messages lack the line, so map them.
        let (text, path, start) = (self.text, self.path, spanned.span().start);
        let core = move |e: tumble::MassError| IoError::AtLine {
            path: path.to_owned(),
            line: line_of(text, start),
            message: format!("{at}{key}: {e}"),
        };
        Ok(match ty {
            ShapeType::Sphere => {
                let r = length(self, "radius", &raw.radius)?;
                Shape::Sphere(Sphere::new(r).map_err(core)?)
            }
            ShapeType::Cuboid => {
                let Some(h) = &raw.half_extents else { return Err(missing(self, "half_extents")) };
                for (axis, &value) in ["x", "y", "z"].iter().zip(h.get_ref()) {
                    if !(value.is_finite() && value > 0.0) {
                        return Err(self.error(
                            h.span(),
                            format!("{at}{key}.half_extents: {axis} must be finite and > 0, got {value}"),
                        ));
                    }
                }
                Shape::Cuboid(Cuboid::new(DVec3::from_array(*h.get_ref())).map_err(core)?)
            }
            ShapeType::Capsule | ShapeType::Cylinder | ShapeType::Cone => {
                let r = length(self, "radius", &raw.radius)?;
                let h = length(self, "half_height", &raw.half_height)?;
                match ty {
                    ShapeType::Capsule => Shape::Capsule(Capsule::new(r, h).map_err(core)?),
                    ShapeType::Cylinder => Shape::Cylinder(Cylinder::new(r, h).map_err(core)?),
                    _ => Shape::Cone(Cone::new(r, h).map_err(core)?),
                }
            }
            ShapeType::Plane | ShapeType::HeightField => {
                let at_line = |message: String| IoError::AtLine {
                    path: path.to_owned(),
                    line: line_of(text, start),
                    message: format!("{at}{key}: {message}"),
                };
                let shape_error = |e: tumble::ShapeError| at_line(e.to_string());
                if ty == ShapeType::Plane {
                    let Some(normal) = &raw.normal else { return Err(missing(self, "normal")) };
                    let offset = raw.offset.as_ref().map_or(0.0, |o| *o.get_ref());
                    let normal = DVec3::from_array(*normal.get_ref());
                    Shape::Plane(tumble::Plane::new(normal, offset).map_err(shape_error)?)
                } else {
                    let Some(heights) = &raw.heights else { return Err(missing(self, "heights")) };
                    let scale = raw.scale.as_ref().map_or(DVec3::ONE, |s| DVec3::from_array(*s.get_ref()));
                    let rows = heights.get_ref().len();
                    let cols = heights.get_ref().first().map_or(0, Vec::len);
                    if let Some(r) = heights.get_ref().iter().position(|row| row.len() != cols) {
                        return Err(self.error(
                            heights.span(),
                            format!(
                                "{at}{key}.heights: row {r} has {} values, row 0 has {cols}",
                                heights.get_ref()[r].len()
                            ),
                        ));
                    }
                    let flat: Vec<f64> = heights.get_ref().iter().flatten().copied().collect();
                    Shape::HeightField(
                        tumble::HeightField::new(flat, rows, cols, scale).map_err(shape_error)?,
                    )
                }
            }
            ShapeType::Mesh => {
                let Some(file) = &raw.file else { return Err(missing(self, "file")) };
                let resolved = self.resolve(file.get_ref());
                let mesh = (self.mesh_loader)(&resolved)
                    .map_err(|e| self.error(file.span(), format!("{at}{key}.file: {e}")))?;
                Shape::TriMesh(mesh)
            }
            ShapeType::Hull => {
                let points: Vec<DVec3> = match (&raw.points, &raw.file) {
                    (Some(_), Some(file)) => {
                        return Err(self.error(
                            file.span(),
                            format!("{at}{key}: a hull takes either `points` or `file`, not both"),
                        ))
                    }
                    (Some(points), None) => {
                        let points = points.get_ref();
                        if let Some(p) = points.iter().find(|p| p.iter().any(|x| !x.is_finite())) {
                            return Err(self.error(
                                spanned.span(),
                                format!(
                                    "{at}{key}.points must be finite, got [{}, {}, {}]",
                                    p[0], p[1], p[2]
                                ),
                            ));
                        }
                        points.iter().map(|&p| DVec3::from_array(p)).collect()
                    }
                    (None, Some(file)) => {
                        let resolved = self.resolve(file.get_ref());
                        let mesh = (self.mesh_loader)(&resolved)
                            .map_err(|e| self.error(file.span(), format!("{at}{key}.file: {e}")))?;
                        mesh.vertices().to_vec()
                    }
                    (None, None) => return Err(missing(self, "points` or `file")),
                };
                let hull = ConvexHull::new(&points)
                    .map_err(|e| self.error(spanned.span(), format!("{at}{key}: convex hull: {e}")))?;
                Shape::ConvexHull(hull)
            }
            ShapeType::Compound => {
                let Some(parts) = &raw.parts else { return Err(missing(self, "parts")) };
                if parts.get_ref().is_empty() {
                    return Err(self.error(
                        parts.span(),
                        format!("{at}{key}.parts: a compound needs at least one part"),
                    ));
                }
                let mut children = Vec::with_capacity(parts.get_ref().len());
                for (i, part) in parts.get_ref().iter().enumerate() {
                    let part_key = format!("{key}.parts[{i}]");
                    let shape = self.shape(at, &format!("{part_key}.shape"), &part.shape)?;
                    let translation =
                        self.vec3_or(at, &format!("{part_key}.position"), &part.position, DVec3::ZERO)?;
                    let rotation =
                        self.quat_or_identity(at, &format!("{part_key}.orientation"), &part.orientation)?;
                    children
                        .push(CompoundChild { pose: tumble::Transform::new(translation, rotation), shape });
                }
                Shape::Compound(Compound::new(children).map_err(core)?)
            }
        })
    }

    /// Mesh paths are relative to the scene file, so a scene and its meshes move together.
    fn resolve(&self, file: &str) -> PathBuf {
        let file = Path::new(file);
        if file.is_absolute() {
            return file.to_owned();
        }
        match self.path.parent() {
            Some(dir) => dir.join(file),
            None => file.to_owned(),
        }
    }

    pub fn number(
        &self,
        at: &str,
        key: &str,
        v: &Number,
        ok: impl Fn(f64) -> bool,
        rule: &str,
    ) -> Result<f64> {
        let value = *v.get_ref();
        if !value.is_finite() {
            return Err(self.error(v.span(), format!("{at}{key} must be finite, got {value}")));
        }
        if !ok(value) {
            return Err(self.error(v.span(), format!("{at}{key} must be {rule}, got {value}")));
        }
        Ok(value)
    }

    pub fn number_or(
        &self,
        at: &str,
        key: &str,
        v: &Option<Number>,
        default: f64,
        ok: impl Fn(f64) -> bool,
        rule: &str,
    ) -> Result<f64> {
        match v {
            Some(v) => self.number(at, key, v, ok, rule),
            None => Ok(default),
        }
    }

    pub fn vec3_or(&self, at: &str, key: &str, v: &Option<Vec3>, default: DVec3) -> Result<DVec3> {
        let Some(v) = v else { return Ok(default) };
        let a = *v.get_ref();
        if a.iter().any(|x| !x.is_finite()) {
            return Err(
                self.error(v.span(), format!("{at}{key} must be finite, got [{}, {}, {}]", a[0], a[1], a[2]))
            );
        }
        Ok(DVec3::from_array(a))
    }

    /// A unit quaternion (x, y, z, w). It is normalised to full precision after the check.
    fn quat_or_identity(&self, at: &str, key: &str, q: &Option<Quat>) -> Result<DQuat> {
        let Some(q) = q else { return Ok(DQuat::IDENTITY) };
        let [x, y, z, w] = *q.get_ref();
        let shown = format!("[{x}, {y}, {z}, {w}]");
        if [x, y, z, w].iter().any(|c| !c.is_finite()) {
            return Err(self.error(q.span(), format!("{at}{key} must be finite, got {shown}")));
        }
        let length = (x * x + y * y + z * z + w * w).sqrt();
        if length == 0.0 {
            return Err(self.error(
                q.span(),
                format!("{at}{key} is the zero quaternion; the identity is [0, 0, 0, 1] (x, y, z, w)"),
            ));
        }
        if (length - 1.0).abs() > UNIT_QUATERNION_TOLERANCE {
            return Err(self.error(
                q.span(),
                format!(
                    "{at}{key} must be a unit quaternion [x, y, z, w] (length within {UNIT_QUATERNION_TOLERANCE:e} of 1), got {shown} of length {length}"
                ),
            ));
        }
        Ok(DQuat::from_xyzw(x, y, z, w).normalize())
    }
}

fn list_keys(keys: &[&str]) -> String {
    keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(" and ")
}
