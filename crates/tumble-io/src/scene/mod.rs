//! Scene files: a TOML description of a world and its bodies, read into a checked [`Scene`] and
//! built into a [`World`].
//!
//! ```toml
//! [world]
//! gravity = [0.0, 0.0, -9.81]    # m/s², default (0, 0, -9.81)
//! dt = 0.004166666666666667      # s, default 1/240
//! duration = 20.0                # s, default 10
//! substeps = 8                   # solver (engine defaults): substeps, solve_iterations,
//! solve_iterations = 1           #   relax_iterations, contact_hertz, contact_damping_ratio,
//! contact_hertz = 60.0           #   joint_hertz, joint_damping_ratio, steady_load_time,
//!                                 #   joint_trees (true/false), joint_tree_limits (true/false),
//!                                 #   joint_projection_iterations, joint_projection_tolerance
//! sleep = true                   # may resting islands fall asleep
//!
//! [[body]]
//! name = "brick"                 # required, unique
//! shape = { type = "box", half_extents = [0.5, 1.0, 1.5] }
//! density = 1000.0               # kg/m³, default 1000; or `mass = ...` (not both)
//! position = [0.0, 0.0, 0.0]     # body-frame origin, world frame
//! orientation = [0.0, 0.0, 0.0, 1.0]   # x, y, z, w (unit)
//! linear_velocity = [0.0, 0.0, 0.0]    # of the centre of mass
//! angular_velocity = [0.0, 5.0, 0.0]   # world frame, rad/s
//! kind = "dynamic"               # or "static", "kinematic"
//! linear_damping = 0.0
//! angular_damping = 0.0
//! gravity_scale = 1.0
//! friction = 0.6                 # surface material: friction, restitution (0..1),
//! restitution = 0.0              #   rolling_friction, torsional_friction (engine defaults)
//! allow_sleep = true
//! group = 1                      # collision filter bits (u32): collide when
//! mask = 4294967295              #   a.group & b.mask != 0 and b.group & a.mask != 0
//! sensor = false                 # a sensor reports overlaps and makes no contact force
//! bullet = false                 # swept against static geometry each step (fast bodies)
//! ```
//! Shapes: `sphere {radius}`, `box {half_extents}`, `capsule|cylinder|cone {radius, half_height}`
//! (along local Z), `mesh {file}` (OBJ or STL, relative to the scene file), `hull {points}` or
//! `hull {file}` (the convex hull of the points, or of a mesh file's vertices), and
//! `compound {parts = [{shape, position, orientation}, ...]}`. (Plane and height field shapes
//! join when the core has them.)
//!
//! Joints: `[[joint]]` tables naming two bodies; see `joints.rs` for the keys.
//!
//! Every error names the file, the line and the key; see `check.rs` for the value checks and
//! [`serde_error`] for errors found while reading the TOML itself.

mod check;
mod joints;
mod raw;

use std::path::{Path, PathBuf};

use serde_path_to_error::Segment;
use tumble::{BodyDef, BodyId, DVec3, SleepSettings, SolverSettings, TriMesh, World, WorldDef};

use crate::error::{line_of, IoError};
pub use check::UNIT_QUATERNION_TOLERANCE;
pub use joints::SceneJoint;

/// Default time step, s (1/240: small enough for stiff contact later, a common engine default).
pub const DEFAULT_DT: f64 = 1.0 / 240.0;
/// Default simulated duration, s.
pub const DEFAULT_DURATION: f64 = 10.0;

/// A checked scene: every value is valid and every mesh is loaded.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The file the scene came from (or the name given for messages).
    pub path: PathBuf,
    pub gravity: DVec3,
    /// Time step, s (> 0).
    pub dt: f64,
    /// How long to simulate, s (>= 0).
    pub duration: f64,
    /// Solver settings (`[world]` keys over the engine's defaults).
    pub solver: SolverSettings,
    /// Sleep settings (`[world] sleep`).
    pub sleep: SleepSettings,
    /// The bodies in file order.
    pub bodies: Vec<SceneBody>,
    /// The joints in file order.
    pub joints: Vec<SceneJoint>,
}

/// One `[[body]]` of a scene.
#[derive(Clone, Debug)]
pub struct SceneBody {
    /// Ready for `World::add_body`.
    pub def: BodyDef,
    /// Line of the body's `name`, for errors found later (when the world computes its mass).
    pub line: usize,
}

/// A scene built into a world.
pub struct SceneWorld {
    pub world: World,
    /// The bodies' ids, in file order.
    pub bodies: Vec<BodyId>,
    /// The joints' ids, in file order.
    pub joints: Vec<tumble::JointId>,
    pub dt: f64,
    pub duration: f64,
}

impl Scene {
    /// Reads and checks a scene file; meshes are loaded relative to its folder.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Scene, IoError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| IoError::file(path, e))?;
        Scene::from_str(&text, path)
    }

    /// Reads and checks scene text. `path` names the file in messages, and its folder is where
    /// mesh files are looked for.
    pub fn from_str(text: &str, path: impl AsRef<Path>) -> Result<Scene, IoError> {
        Scene::from_str_with_meshes(text, path, &mut crate::mesh::load_mesh)
    }

    /// Like [`Scene::from_str`], with mesh files obtained from `mesh_loader` (given the resolved
    /// path) instead of the disk — for scenes embedded in a program together with their meshes.
    pub fn from_str_with_meshes(
        text: &str,
        path: impl AsRef<Path>,
        mesh_loader: &mut dyn FnMut(&Path) -> Result<TriMesh, IoError>,
    ) -> Result<Scene, IoError> {
        let path = path.as_ref();
        let deserializer = toml::Deserializer::parse(text).map_err(|e| IoError::AtLine {
            path: path.to_owned(),
            line: e.span().map_or(1, |s| line_of(text, s.start)),
            message: format!("invalid TOML: {}", e.message().trim_end()),
        })?;
        let raw: raw::RawScene =
            serde_path_to_error::deserialize(deserializer).map_err(|e| serde_error(text, path, &e))?;
        check::Checker { text, path, mesh_loader }.scene(raw)
    }

    /// Builds the world: settings from `[world]`, then the bodies and the joints in file order.
    pub fn build_world(&self) -> Result<SceneWorld, IoError> {
        let def = WorldDef { gravity: self.gravity, solver: self.solver.clone(), sleep: self.sleep.clone() };
        let mut world = World::new(def).map_err(|e| IoError::AtLine {
            path: self.path.clone(),
            line: 1,
            message: format!("world: {e}"),
        })?;
        let at_line = |line: usize, e: tumble::WorldError| IoError::AtLine {
            path: self.path.clone(),
            line,
            message: e.to_string(),
        };
        let mut bodies = Vec::with_capacity(self.bodies.len());
        for body in &self.bodies {
            bodies.push(world.add_body(body.def.clone()).map_err(|e| at_line(body.line, e))?);
        }
        let id_of = |name: &str| {
            let index = self.bodies.iter().position(|b| b.def.name == name);
            bodies[index.expect("joint bodies are checked to exist")]
        };
        let mut joints = Vec::with_capacity(self.joints.len());
        for joint in &self.joints {
            let def = tumble::JointDef {
                body_a: id_of(&joint.body_a),
                body_b: id_of(&joint.body_b),
                ..joint.def.clone()
            };
            joints.push(world.add_joint(def).map_err(|e| at_line(joint.line, e))?);
        }
        Ok(SceneWorld { world, bodies, joints, dt: self.dt, duration: self.duration })
    }

    /// The body definitions in file order.
    pub fn body_defs(&self) -> impl Iterator<Item = &BodyDef> {
        self.bodies.iter().map(|b| &b.def)
    }
}

/// An error found while reading the TOML into the raw structs (unknown key, wrong type, missing
/// key), as `file:line: body "name": key.path: message`.
fn serde_error(text: &str, path: &Path, error: &serde_path_to_error::Error<toml::de::Error>) -> IoError {
    let inner = error.inner();
    // serde says "f64"; a person editing a TOML file thinks "number".
    let message = inner.message().trim_end().replace("expected f64", "expected a number");
    // `Spanned` shows up in the path as a private wrapper key; it is not something the user wrote.
    let mut segments: Vec<&Segment> = error
        .path()
        .iter()
        .filter(|s| !matches!(s, Segment::Map { key } if key.starts_with("$__")))
        .collect();
    // "unknown field `x`" already names the key; the path up to its table is enough.
    if message.starts_with("unknown field") {
        segments.pop();
    }
    let mut context = String::new();
    let mut rest = segments.as_slice();
    if let [Segment::Map { key }, Segment::Seq { index }, tail @ ..] = rest {
        if key == "body" || key == "joint" {
            context = match table_name(text, key, *index) {
                Some(name) => format!("{key} \"{name}\": "),
                None => format!("{key} #{}: ", index + 1),
            };
            rest = tail;
        }
    }
    let mut key_path = String::new();
    for segment in rest {
        match segment {
            Segment::Seq { index } => key_path.push_str(&format!("[{index}]")),
            Segment::Map { key } | Segment::Enum { variant: key } => {
                if !key_path.is_empty() {
                    key_path.push('.');
                }
                key_path.push_str(key);
            }
            Segment::Unknown => {}
        }
    }
    if !key_path.is_empty() {
        key_path.push_str(": ");
    }
    IoError::AtLine {
        path: path.to_owned(),
        line: inner.span().map_or(1, |s| line_of(text, s.start)),
        message: format!("{context}{key_path}{message}"),
    }
}

/// The `name` of the `index`-th `[[body]]` (or `[[joint]]`: `key`), if the file says it as a
/// string. Read untyped so it works however broken the rest of that table is.
fn table_name(text: &str, key: &str, index: usize) -> Option<String> {
    let table: toml::Table = toml::from_str(text).ok()?;
    let body = table.get(key)?.as_array()?.get(index)?;
    Some(body.get("name")?.as_str()?.to_string())
}
