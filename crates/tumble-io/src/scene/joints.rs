//! `[[joint]]` tables: checked into [`SceneJoint`]s, built after the bodies.
//!
//! ```toml
//! [[joint]]
//! type = "hinge"              # ball | hinge | slider | fixed | distance
//! name = "elbow"              # optional
//! body_a = "upper_arm"        # body names
//! body_b = "forearm"
//! anchor = [0.0, 0.0, 1.0]    # world frame, at creation (required)
//! axis = [0.0, 1.0, 0.0]      # hinge/slider axis, ball cone axis (required for hinge and slider)
//! limits = [-1.0, 1.0]        # hinge: rad; slider: m
//! motor = { target_speed = 2.0, max_force = 10.0 }   # rad/s and N·m, or m/s and N
//! spring = { hertz = 2.0, damping_ratio = 0.5 }
//! spring_target = 0.0         # hinge: rest angle (rad); slider: rest position (m)
//! break_force = 1000.0        # N; break_torque in N·m
//! collide_connected = false
//! ```
//! Ball joints take `swing_limit` (rad) and `twist_limits` ([lower, upper], rad); ball and hinge
//! joints take `friction_torque` (N·m, default 0); distance joints
//! take `anchor_b` (the anchor on body b; default `anchor`), `length`, `min_length`,
//! `max_length` and `spring`. Each type rejects the keys of the others.

use std::collections::HashMap;

use toml::Spanned;
use tumble::{
    BallJoint, BodyId, DistanceJoint, FixedJoint, HingeJoint, JointDef, JointKind, Limits, Motor,
    SliderJoint, SpringSettings,
};

use super::check::Checker;
use super::raw::{JointType, Pair, RawJoint};
use crate::error::{line_of, IoError};

type Result<T> = std::result::Result<T, IoError>;

/// One `[[joint]]` of a scene.
#[derive(Clone, Debug)]
pub struct SceneJoint {
    /// Ready for `World::add_joint` once `body_a` and `body_b` are set to the built bodies' ids
    /// (they hold placeholders until then).
    pub def: JointDef,
    /// The names of the two bodies (checked: both exist in the scene).
    pub body_a: String,
    pub body_b: String,
    /// Line of the joint's `type`, for errors found when the world adds it.
    pub line: usize,
}

/// Stands in for a body id until the world is built.
const PLACEHOLDER: u32 = u32::MAX;

impl Checker<'_> {
    /// Checks every joint; `bodies` maps body names to their lines.
    pub fn joints(
        &self,
        raw: &[Spanned<RawJoint>],
        bodies: &HashMap<String, usize>,
    ) -> Result<Vec<SceneJoint>> {
        raw.iter().enumerate().map(|(i, j)| self.joint(i, j.get_ref(), bodies)).collect()
    }

    fn joint(&self, index: usize, raw: &RawJoint, bodies: &HashMap<String, usize>) -> Result<SceneJoint> {
        let ty = *raw.kind.get_ref();
        let name = raw.name.as_ref().map_or_else(String::new, |n| n.get_ref().clone());
        let at =
            if name.is_empty() { format!("joint #{}: ", index + 1) } else { format!("joint \"{name}\": ") };
        let at = at.as_str();
        for (present, offset) in raw.present_keys() {
            if !ty.keys().contains(&present) {
                let takes = match ty.keys() {
                    [] => "only the common keys".to_string(),
                    keys => keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", "),
                };
                return Err(self.error(
                    offset..offset,
                    format!("{at}{present}: a {} joint takes no `{present}` (it takes {takes})", ty.name()),
                ));
            }
        }
        for (key, body) in [("body_a", &raw.body_a), ("body_b", &raw.body_b)] {
            if !bodies.contains_key(body.get_ref()) {
                return Err(self.error(
                    body.span(),
                    format!("{at}{key}: there is no body named \"{}\" in this scene", body.get_ref()),
                ));
            }
        }
        if raw.body_a.get_ref() == raw.body_b.get_ref() {
            return Err(
                self.error(raw.body_b.span(), format!("{at}body_b: a joint needs two different bodies"))
            );
        }
        if raw.anchor.is_none() {
            return Err(self.error(raw.kind.span(), format!("{at}a {} joint needs `anchor`", ty.name())));
        }
        let anchor = self.vec3_or(at, "anchor", &raw.anchor, tumble::DVec3::ZERO)?;
        let axis = match &raw.axis {
            Some(axis) => {
                let v = self.vec3_or(at, "axis", &raw.axis, tumble::DVec3::Z)?;
                if v.length() < 1e-9 {
                    return Err(
                        self.error(axis.span(), format!("{at}axis must be a non-zero vector, got {v}"))
                    );
                }
                v
            }
            None if matches!(ty, JointType::Hinge | JointType::Slider) => {
                return Err(self.error(raw.kind.span(), format!("{at}a {} joint needs `axis`", ty.name())))
            }
            None => tumble::DVec3::Z,
        };
        let positive = |key: &str, v: &Option<Spanned<f64>>| {
            v.as_ref().map(|v| self.number(at, key, v, |x| x > 0.0, "> 0")).transpose()
        };
        let placeholder = BodyId::from_parts(PLACEHOLDER, PLACEHOLDER);
        let def = JointDef {
            name,
            anchor_b_world: match &raw.anchor_b {
                Some(_) => Some(self.vec3_or(at, "anchor_b", &raw.anchor_b, anchor)?),
                None => None,
            },
            axis_world: axis,
            break_force: positive("break_force", &raw.break_force)?,
            break_torque: positive("break_torque", &raw.break_torque)?,
            collide_connected: raw.collide_connected.unwrap_or(false),
            ..JointDef::new(placeholder, placeholder, anchor, self.kind(at, ty, raw)?)
        };
        Ok(SceneJoint {
            def,
            body_a: raw.body_a.get_ref().clone(),
            body_b: raw.body_b.get_ref().clone(),
            line: line_of(self.text, raw.kind.span().start),
        })
    }

    /// The joint's settings, each value checked where its key is.
    fn kind(&self, at: &str, ty: JointType, raw: &RawJoint) -> Result<JointKind> {
        let non_negative = |v: f64| v >= 0.0;
        let opt = |key: &str, v: &Option<Spanned<f64>>, ok: fn(f64) -> bool, rule: &str| {
            v.as_ref().map(|v| self.number(at, key, v, ok, rule)).transpose()
        };
        let limits = |key: &str, v: &Option<Pair>| v.as_ref().map(|v| self.limits(at, key, v)).transpose();
        let motor = raw
            .motor
            .as_ref()
            .map(|m| {
                let m = m.get_ref();
                Ok::<_, IoError>(Motor::new(
                    self.number(at, "motor.target_speed", &m.target_speed, |_| true, "")?,
                    self.number(at, "motor.max_force", &m.max_force, non_negative, ">= 0")?,
                ))
            })
            .transpose()?;
        let spring = raw
            .spring
            .as_ref()
            .map(|s| {
                let s = s.get_ref();
                Ok::<_, IoError>(SpringSettings::new(
                    self.number(at, "spring.hertz", &s.hertz, non_negative, ">= 0")?,
                    self.number_or(at, "spring.damping_ratio", &s.damping_ratio, 0.0, non_negative, ">= 0")?,
                ))
            })
            .transpose()?;
        let target = opt("spring_target", &raw.spring_target, |_| true, "")?.unwrap_or(0.0);
        let friction_torque = || {
            Ok::<_, IoError>(
                opt("friction_torque", &raw.friction_torque, non_negative, ">= 0")?.unwrap_or(0.0),
            )
        };
        Ok(match ty {
            JointType::Ball => JointKind::Ball(BallJoint {
                swing_limit: opt("swing_limit", &raw.swing_limit, non_negative, ">= 0")?,
                twist_limits: limits("twist_limits", &raw.twist_limits)?,
                friction_torque: friction_torque()?,
            }),
            JointType::Hinge => JointKind::Hinge(HingeJoint {
                limits: limits("limits", &raw.limits)?,
                motor,
                spring,
                spring_target_angle: target,
                friction_torque: friction_torque()?,
            }),
            JointType::Slider => JointKind::Slider(SliderJoint {
                limits: limits("limits", &raw.limits)?,
                motor,
                spring,
                spring_target_position: target,
            }),
            JointType::Fixed => JointKind::Fixed(FixedJoint::new()),
            JointType::Distance => {
                let d = DistanceJoint::default();
                let max_length = match &raw.max_length {
                    Some(v) => self.number(at, "max_length", v, non_negative, ">= 0")?,
                    None => d.max_length,
                };
                JointKind::Distance(DistanceJoint {
                    length: opt("length", &raw.length, non_negative, ">= 0")?,
                    min_length: self.number_or(
                        at,
                        "min_length",
                        &raw.min_length,
                        0.0,
                        non_negative,
                        ">= 0",
                    )?,
                    max_length,
                    spring,
                })
            }
        })
    }

    /// `[lower, upper]`, finite and ordered.
    fn limits(&self, at: &str, key: &str, v: &Pair) -> Result<Limits> {
        let [lower, upper] = *v.get_ref();
        if !(lower.is_finite() && upper.is_finite()) {
            return Err(self.error(v.span(), format!("{at}{key} must be finite, got [{lower}, {upper}]")));
        }
        if lower > upper {
            return Err(
                self.error(v.span(), format!("{at}{key}: lower ({lower}) must be <= upper ({upper})"))
            );
        }
        Ok(Limits::new(lower, upper))
    }
}
