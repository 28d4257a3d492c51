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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub world: Option<RawWorld>,
    #[serde(default)]
    pub body: Vec<Spanned<RawBody>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawWorld {
    pub gravity: Option<Vec3>,
    pub dt: Option<Number>,
    pub duration: Option<Number>,
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
    Compound,
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
            ShapeType::Compound => "compound",
        }
    }

    /// The keys (besides `type`) this shape type needs; it takes no others.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            ShapeType::Sphere => &["radius"],
            ShapeType::Cuboid => &["half_extents"],
            ShapeType::Capsule | ShapeType::Cylinder | ShapeType::Cone => &["radius", "half_height"],
            ShapeType::Mesh => &["file"],
            ShapeType::Compound => &["parts"],
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
    pub parts: Option<Spanned<Vec<RawPart>>>,
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
        if let Some(v) = &self.parts {
            keys.push(("parts", v.span().start));
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
