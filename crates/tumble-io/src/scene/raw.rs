//! The scene file exactly as written: serde structs mirroring the TOML, every value wrapped in
//! `Spanned` so the checks in `check.rs` can point at its line. Nothing here is validated beyond
//! the TOML types; `deny_unknown_fields` everywhere turns a misspelt key into an error instead of a
//! silently ignored setting.
//!
//! Shapes are one flat struct with every possible key optional, not a serde-tagged enum: a tagged
//! enum is deserialized through serde's internal buffer, which loses the spans (and with them the
//! line numbers) of everything inside it.

use serde::Deserialize;
use toml::Spanned;

pub(super) type Vec3 = Spanned<[f64; 3]>;
pub(super) type Quat = Spanned<[f64; 4]>;
pub(super) type Number = Spanned<f64>;
pub(super) type Integer = Spanned<i64>;
pub(super) type Pair = Spanned<[f64; 2]>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub world: Option<RawWorld>,
    #[serde(default)]
    pub body: Vec<Spanned<RawBody>>,
    #[serde(default)]
    pub joint: Vec<Spanned<RawJoint>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawWorld {
    pub gravity: Option<Vec3>,
    pub dt: Option<Number>,
    pub duration: Option<Number>,
    pub substeps: Option<Integer>,
    pub solve_iterations: Option<Integer>,
    pub relax_iterations: Option<Integer>,
    pub contact_hertz: Option<Number>,
    pub contact_damping_ratio: Option<Number>,
    pub joint_hertz: Option<Number>,
    pub joint_damping_ratio: Option<Number>,
    pub steady_load_time: Option<Number>,
    pub joint_trees: Option<bool>,
    pub joint_tree_limits: Option<bool>,
    pub joint_projection_iterations: Option<Integer>,
    pub joint_projection_tolerance: Option<Number>,
    pub sleep: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBody {
    pub name: Spanned<String>,
    pub shape: Spanned<RawShape>,
    pub kind: Option<Spanned<RawKind>>,
    pub density: Option<Number>,
    pub mass: Option<Number>,
    pub position: Option<Vec3>,
    pub orientation: Option<Quat>,
    pub linear_velocity: Option<Vec3>,
    pub angular_velocity: Option<Vec3>,
    pub linear_damping: Option<Number>,
    pub angular_damping: Option<Number>,
    pub gravity_scale: Option<Number>,
    pub allow_sleep: Option<bool>,
    pub friction: Option<Number>,
    pub restitution: Option<Number>,
    pub rolling_friction: Option<Number>,
    pub torsional_friction: Option<Number>,
    pub group: Option<Integer>,
    pub mask: Option<Integer>,
    pub sensor: Option<bool>,
    pub bullet: Option<bool>,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawKind {
    Dynamic,
    Static,
    Kinematic,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "lowercase")]
pub(super) enum ShapeType {
    Sphere,
    #[serde(rename = "box")]
    Cuboid,
    Capsule,
    Cylinder,
    Cone,
    Mesh,
    Hull,
    Compound,
    Plane,
    HeightField,
}

impl ShapeType {
    pub fn name(self) -> &'static str {
        match self {
            ShapeType::Sphere => "sphere",
            ShapeType::Cuboid => "box",
            ShapeType::Capsule => "capsule",
            ShapeType::Cylinder => "cylinder",
            ShapeType::Cone => "cone",
            ShapeType::Mesh => "mesh",
            ShapeType::Hull => "hull",
            ShapeType::Compound => "compound",
            ShapeType::Plane => "plane",
            ShapeType::HeightField => "heightfield",
        }
    }

    /// The keys (besides `type`) this shape type needs; it takes no others.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            ShapeType::Sphere => &["radius"],
            ShapeType::Cuboid => &["half_extents"],
            ShapeType::Capsule | ShapeType::Cylinder | ShapeType::Cone => &["radius", "half_height"],
            ShapeType::Mesh => &["file"],
            // One of the two: the points themselves, or a mesh file whose vertices they are.
            ShapeType::Hull => &["points", "file"],
            ShapeType::Compound => &["parts"],
            ShapeType::Plane => &["normal", "offset"],
            ShapeType::HeightField => &["heights", "scale"],
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawShape {
    #[serde(rename = "type")]
    pub kind: Spanned<ShapeType>,
    pub radius: Option<Number>,
    pub half_height: Option<Number>,
    pub half_extents: Option<Vec3>,
    pub file: Option<Spanned<String>>,
    pub points: Option<Spanned<Vec<[f64; 3]>>>,
    pub parts: Option<Spanned<Vec<RawPart>>>,
    pub normal: Option<Vec3>,
    pub offset: Option<Number>,
    pub heights: Option<Spanned<Vec<Vec<f64>>>>,
    pub scale: Option<Vec3>,
}

impl RawShape {
    /// The optional keys that are present, with the byte offset of their value.
    pub fn present_keys(&self) -> Vec<(&'static str, usize)> {
        let mut keys = Vec::new();
        if let Some(v) = &self.radius {
            keys.push(("radius", v.span().start));
        }
        if let Some(v) = &self.half_height {
            keys.push(("half_height", v.span().start));
        }
        if let Some(v) = &self.half_extents {
            keys.push(("half_extents", v.span().start));
        }
        if let Some(v) = &self.file {
            keys.push(("file", v.span().start));
        }
        if let Some(v) = &self.points {
            keys.push(("points", v.span().start));
        }
        if let Some(v) = &self.parts {
            keys.push(("parts", v.span().start));
        }
        if let Some(v) = &self.normal {
            keys.push(("normal", v.span().start));
        }
        if let Some(v) = &self.offset {
            keys.push(("offset", v.span().start));
        }
        if let Some(v) = &self.heights {
            keys.push(("heights", v.span().start));
        }
        if let Some(v) = &self.scale {
            keys.push(("scale", v.span().start));
        }
        keys
    }
}

/// One part of a compound shape.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPart {
    pub shape: Spanned<RawShape>,
    pub position: Option<Vec3>,
    pub orientation: Option<Quat>,
}

/// One `[[joint]]`. Which keys a joint takes depends on its type (`JointType::keys`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawJoint {
    #[serde(rename = "type")]
    pub kind: Spanned<JointType>,
    pub name: Option<Spanned<String>>,
    pub body_a: Spanned<String>,
    pub body_b: Spanned<String>,
    pub anchor: Option<Vec3>,
    pub axis: Option<Vec3>,
    pub anchor_b: Option<Vec3>,
    pub limits: Option<Pair>,
    pub motor: Option<Spanned<RawMotor>>,
    pub spring: Option<Spanned<RawSpring>>,
    pub spring_target: Option<Number>,
    pub swing_limit: Option<Number>,
    pub twist_limits: Option<Pair>,
    pub friction_torque: Option<Number>,
    pub length: Option<Number>,
    pub min_length: Option<Number>,
    pub max_length: Option<Number>,
    pub break_force: Option<Number>,
    pub break_torque: Option<Number>,
    pub collide_connected: Option<bool>,
}

impl RawJoint {
    /// The type-specific keys that are present, with the byte offset of their value.
    pub fn present_keys(&self) -> Vec<(&'static str, usize)> {
        let mut keys = Vec::new();
        let mut push = |key: &'static str, span: Option<std::ops::Range<usize>>| {
            if let Some(span) = span {
                keys.push((key, span.start));
            }
        };
        push("axis", self.axis.as_ref().map(|v| v.span()));
        push("anchor_b", self.anchor_b.as_ref().map(|v| v.span()));
        push("limits", self.limits.as_ref().map(|v| v.span()));
        push("motor", self.motor.as_ref().map(|v| v.span()));
        push("spring", self.spring.as_ref().map(|v| v.span()));
        push("spring_target", self.spring_target.as_ref().map(|v| v.span()));
        push("swing_limit", self.swing_limit.as_ref().map(|v| v.span()));
        push("twist_limits", self.twist_limits.as_ref().map(|v| v.span()));
        push("friction_torque", self.friction_torque.as_ref().map(|v| v.span()));
        push("length", self.length.as_ref().map(|v| v.span()));
        push("min_length", self.min_length.as_ref().map(|v| v.span()));
        push("max_length", self.max_length.as_ref().map(|v| v.span()));
        keys
    }
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "lowercase")]
pub(super) enum JointType {
    Ball,
    Hinge,
    Slider,
    Fixed,
    Distance,
}

impl JointType {
    pub fn name(self) -> &'static str {
        match self {
            JointType::Ball => "ball",
            JointType::Hinge => "hinge",
            JointType::Slider => "slider",
            JointType::Fixed => "fixed",
            JointType::Distance => "distance",
        }
    }

    /// The type-specific keys this joint type takes (besides `type`, `name`, `body_a`, `body_b`,
    /// `anchor`, `break_force`, `break_torque`, `collide_connected`, which every joint takes).
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            JointType::Ball => &["axis", "swing_limit", "twist_limits", "friction_torque"],
            JointType::Hinge => &["axis", "limits", "motor", "spring", "spring_target", "friction_torque"],
            JointType::Slider => &["axis", "limits", "motor", "spring", "spring_target"],
            JointType::Fixed => &[],
            JointType::Distance => &["anchor_b", "length", "min_length", "max_length", "spring"],
        }
    }
}

/// `motor = { target_speed = 2.0, max_force = 10.0 }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMotor {
    pub target_speed: Number,
    pub max_force: Number,
}

/// `spring = { hertz = 2.0, damping_ratio = 0.5 }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSpring {
    pub hertz: Number,
    pub damping_ratio: Option<Number>,
}
