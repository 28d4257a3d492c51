//! Bodies: the definition a user fills in (`BodyDef`), the hot per-step state (`BodyState`), and
//! the body itself with its mass properties in the principal frame.
//!
//! Frames and points:
//! - the *body frame* is the frame the user places (`position`, `orientation`) and the shape is
//!   defined in;
//! - the *principal frame* sits at the centre of mass with axes along the principal axes of inertia;
//!   `principal_rotation_local` maps it into the body frame;
//! - `linear_velocity` is the velocity of the centre of mass, `angular_velocity` is in the world frame.

use crate::collision::filter::CollisionFilter;
use crate::collision::ProxyKey;
use crate::dynamics::material::Material;
use crate::mass::{MassProperties, PrincipalFrame};
use crate::math::{hat, DMat3, DQuat, DVec3, Transform};
use crate::shape::Shape;

/// How a body moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum BodyKind {
    /// Moved by forces, impulses and (later) contacts and joints.
    #[default]
    Dynamic,
    /// Never moves; infinite mass.
    Static,
    /// Moves with the velocity the user sets, unaffected by forces; infinite mass.
    Kinematic,
}

impl BodyKind {
    pub fn name(self) -> &'static str {
        match self {
            BodyKind::Dynamic => "dynamic",
            BodyKind::Static => "static",
            BodyKind::Kinematic => "kinematic",
        }
    }
}

/// Everything needed to create a body. Start from `BodyDef::default()` and set what differs.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BodyDef {
    /// A name for messages and recordings (need not be unique, but recordings are clearer if it is).
    pub name: String,
    pub kind: BodyKind,
    /// The body's shape, in the body frame. A dynamic body needs a shape or `mass_properties`.
    pub shape: Option<Shape>,
    /// Density, kg/m³, used with `shape` when neither `mass` nor `mass_properties` is given.
    pub density: f64,
    /// Total mass, kg: when set, the shape's density is whatever gives this mass.
    pub mass: Option<f64>,
    /// Explicit mass properties in the body frame (overrides `shape`, `density` and `mass`).
    pub mass_properties: Option<MassProperties>,
    /// World position of the body frame's origin.
    pub position: DVec3,
    /// Orientation of the body frame (unit quaternion; normalised on creation).
    pub orientation: DQuat,
    /// Velocity of the centre of mass, world frame, m/s.
    pub linear_velocity: DVec3,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: DVec3,
    /// Linear damping rate, 1/s (velocity scaled by 1/(1 + dt·c) each step). Default 0.
    pub linear_damping: f64,
    /// Angular damping rate, 1/s. Default 0.
    pub angular_damping: f64,
    /// Multiplies the world's gravity for this body. Default 1.
    pub gravity_scale: f64,
    /// May this body fall asleep when it comes to rest? Default true.
    pub allow_sleep: bool,
    /// The surface of the body's shape: friction, restitution, rolling and torsional friction.
    pub material: Material,
    /// Which other shapes the body's shape may touch.
    pub filter: CollisionFilter,
    /// A sensor reports overlaps but makes no contact force.
    pub is_sensor: bool,
    /// Sweep this (dynamic) body's motion against static geometry after each step, so it cannot
    /// pass through a wall that its speculative contacts missed (`continuous.rs`). Default false.
    #[serde(default)]
    pub bullet: bool,
}

impl Default for BodyDef {
    fn default() -> Self {
        Self {
            name: String::new(),
            kind: BodyKind::Dynamic,
            shape: None,
            density: 1000.0,
            mass: None,
            mass_properties: None,
            position: DVec3::ZERO,
            orientation: DQuat::IDENTITY,
            linear_velocity: DVec3::ZERO,
            angular_velocity: DVec3::ZERO,
            linear_damping: 0.0,
            angular_damping: 0.0,
            gravity_scale: 1.0,
            allow_sleep: true,
            material: Material::default(),
            filter: CollisionFilter::default(),
            is_sensor: false,
            bullet: false,
        }
    }
}

/// The hot state the integrator and solver work on.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BodyState {
    /// Centre of mass, world frame.
    pub com_world: DVec3,
    /// Orientation of the body frame in the world.
    pub rotation: DQuat,
    /// Velocity of the centre of mass, world frame.
    pub linear_velocity: DVec3,
    /// Angular velocity, world frame.
    pub angular_velocity: DVec3,
}

/// A rigid body. Read it through `World::body`; change it through the `World` methods, which
/// validate what they are given.
///
/// Laid out in declaration order (`repr(C)`), the fields every step reads for every body first:
/// the step makes several passes over all bodies (the overflow check, gather, write-back, proxies,
/// sleep), and with the flags and the state in the first cache lines each pass touches two or
/// three lines of a body instead of most of its ~600 bytes.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[repr(C)]
pub struct Body {
    pub(crate) kind: BodyKind,
    /// Taken out of the simulation because its state became non-finite (`non_finite.rs`).
    pub(crate) isolated: bool,
    /// Swept against static geometry after each step (`continuous.rs`).
    pub(crate) bullet: bool,
    pub(crate) allow_sleep: bool,
    pub(crate) is_sensor: bool,
    /// `Some(island)` while asleep: the island (named by its lowest body slot) it sleeps with.
    pub(crate) sleeping_island: Option<u32>,
    /// How long the body has been slower than the sleep thresholds, s.
    pub(crate) sleep_time: f64,
    pub(crate) state: BodyState,
    pub(crate) force_world: DVec3,
    pub(crate) torque_world: DVec3,
    /// 1/m, or 0 for static and kinematic bodies.
    pub(crate) inverse_mass: f64,
    /// Principal moments of inertia about the centre of mass (ascending).
    pub(crate) inertia_principal: DVec3,
    /// Rotation taking principal-frame coordinates to body-frame coordinates.
    pub(crate) principal_rotation_local: DQuat,
    pub(crate) linear_damping: f64,
    pub(crate) angular_damping: f64,
    pub(crate) gravity_scale: f64,
    /// Centre of mass in the body frame.
    pub(crate) com_local: DVec3,
    /// Broad-phase proxies of the body's leaf shapes (one per compound child).
    pub(crate) proxies: Vec<ProxyKey>,
    pub(crate) shape: Option<Shape>,
    /// Mass properties in the body frame (as computed or given).
    pub(crate) mass_properties: MassProperties,
    pub(crate) material: Material,
    pub(crate) filter: CollisionFilter,
    pub(crate) name: String,
}

impl Body {
    pub(crate) fn new(def: &BodyDef, mass_properties: MassProperties, principal: PrincipalFrame) -> Body {
        let rotation = def.orientation.normalize();
        let com_local = mass_properties.center_of_mass;
        let dynamic = def.kind == BodyKind::Dynamic;
        Body {
            name: def.name.clone(),
            kind: def.kind,
            shape: def.shape.clone(),
            mass_properties,
            inverse_mass: if dynamic { 1.0 / mass_properties.mass } else { 0.0 },
            com_local,
            inertia_principal: principal.moments,
            principal_rotation_local: DQuat::from_mat3(&principal.axes).normalize(),
            state: BodyState {
                com_world: def.position + rotation * com_local,
                rotation,
                linear_velocity: if def.kind == BodyKind::Static { DVec3::ZERO } else { def.linear_velocity },
                angular_velocity: if def.kind == BodyKind::Static {
                    DVec3::ZERO
                } else {
                    def.angular_velocity
                },
            },
            force_world: DVec3::ZERO,
            torque_world: DVec3::ZERO,
            linear_damping: def.linear_damping,
            angular_damping: def.angular_damping,
            gravity_scale: def.gravity_scale,
            allow_sleep: def.allow_sleep,
            material: def.material,
            filter: def.filter,
            is_sensor: def.is_sensor,
            bullet: def.bullet,
            proxies: Vec::new(),
            sleep_time: 0.0,
            sleeping_island: None,
            isolated: false,
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn kind(&self) -> BodyKind {
        self.kind
    }

    pub fn shape(&self) -> Option<&Shape> {
        self.shape.as_ref()
    }

    /// The hot state: centre of mass, rotation, velocities.
    pub fn state(&self) -> &BodyState {
        &self.state
    }

    /// World position of the body frame's origin.
    pub fn position(&self) -> DVec3 {
        self.state.com_world - self.state.rotation * self.com_local
    }

    /// Orientation of the body frame.
    pub fn orientation(&self) -> DQuat {
        self.state.rotation
    }

    /// The body frame's pose in the world.
    pub fn transform(&self) -> Transform {
        Transform::new(self.position(), self.state.rotation)
    }

    pub fn com_world(&self) -> DVec3 {
        self.state.com_world
    }

    /// Centre of mass in the body frame.
    pub fn com_local(&self) -> DVec3 {
        self.com_local
    }

    pub fn linear_velocity(&self) -> DVec3 {
        self.state.linear_velocity
    }

    pub fn angular_velocity(&self) -> DVec3 {
        self.state.angular_velocity
    }

    /// Mass properties in the body frame.
    pub fn mass_properties(&self) -> &MassProperties {
        &self.mass_properties
    }

    pub fn mass(&self) -> f64 {
        self.mass_properties.mass
    }

    /// 1/m; 0 for static and kinematic bodies.
    pub fn inverse_mass(&self) -> f64 {
        self.inverse_mass
    }

    /// Principal moments of inertia (ascending), kg·m².
    pub fn inertia_principal(&self) -> DVec3 {
        self.inertia_principal
    }

    /// Orientation of the principal frame in the world.
    pub fn principal_rotation_world(&self) -> DQuat {
        self.state.rotation * self.principal_rotation_local
    }

    /// Inertia tensor about the centre of mass in world axes, `R diag(I) Rᵀ`.
    pub fn inertia_world(&self) -> DMat3 {
        let r = DMat3::from_quat(self.principal_rotation_world());
        r * DMat3::from_diagonal(self.inertia_principal) * r.transpose()
    }

    /// Inverse world inertia `R diag(1/I) Rᵀ`; zero for static and kinematic bodies.
    pub fn inverse_inertia_world(&self) -> DMat3 {
        if self.kind != BodyKind::Dynamic {
            return DMat3::ZERO;
        }
        let r = DMat3::from_quat(self.principal_rotation_world());
        r * DMat3::from_diagonal(self.inertia_principal.recip()) * r.transpose()
    }

    /// Accumulated force (world frame) since the last step.
    pub fn force(&self) -> DVec3 {
        self.force_world
    }

    /// Accumulated torque about the centre of mass (world frame) since the last step.
    pub fn torque(&self) -> DVec3 {
        self.torque_world
    }

    pub fn linear_damping(&self) -> f64 {
        self.linear_damping
    }

    pub fn angular_damping(&self) -> f64 {
        self.angular_damping
    }

    pub fn gravity_scale(&self) -> f64 {
        self.gravity_scale
    }

    /// The surface material of the body's shape.
    pub fn material(&self) -> &Material {
        &self.material
    }

    pub fn filter(&self) -> &CollisionFilter {
        &self.filter
    }

    pub fn is_sensor(&self) -> bool {
        self.is_sensor
    }

    /// True when the body is a bullet: a dynamic bullet's motion is swept against static geometry
    /// after each step (`World::set_bullet`).
    pub fn is_bullet(&self) -> bool {
        self.bullet
    }

    /// False while the body sleeps (it is then not simulated until something wakes it).
    pub fn is_awake(&self) -> bool {
        self.sleeping_island.is_none()
    }

    /// True once the step took the body out of the simulation because its state became
    /// non-finite: it stands still where it last was finite and touches nothing
    /// (`World::isolated_bodies`).
    pub fn is_isolated(&self) -> bool {
        self.isolated
    }

    /// Velocity of the material point now at `point_world`: `v + ω × r`, r from the centre of mass.
    pub fn point_velocity(&self, point_world: DVec3) -> DVec3 {
        let r = point_world - self.state.com_world;
        self.state.linear_velocity + self.state.angular_velocity.cross(r)
    }

    /// Angular acceleration from the accumulated torque and the gyroscopic term:
    /// `ω̇ = I⁻¹ (τ − ω × I ω)` (Euler's equations in the world frame).
    pub fn angular_acceleration(&self) -> DVec3 {
        if self.kind != BodyKind::Dynamic {
            return DVec3::ZERO;
        }
        let w = self.state.angular_velocity;
        let l = self.inertia_world() * w;
        self.inverse_inertia_world() * (self.torque_world - w.cross(l))
    }

    /// Acceleration of the centre of mass from the accumulated force and `gravity` (the world's).
    pub fn linear_acceleration(&self, gravity: DVec3) -> DVec3 {
        if self.kind != BodyKind::Dynamic {
            return DVec3::ZERO;
        }
        gravity * self.gravity_scale + self.force_world * self.inverse_mass
    }

    /// Acceleration of the material point now at `point_world`:
    /// `a = a_cm + ω̇ × r + ω × (ω × r)`.
    pub fn point_acceleration(&self, point_world: DVec3, gravity: DVec3) -> DVec3 {
        let r = point_world - self.state.com_world;
        let w = self.state.angular_velocity;
        self.linear_acceleration(gravity) + self.angular_acceleration().cross(r) + w.cross(w.cross(r))
    }

    /// The point inverse mass matrix `K(r₁, r₂) = (1/m)·1 − r̂₂ I⁻¹ r̂₁`: an impulse `j` applied at
    /// offset `r1` (from the centre of mass, world frame) changes the velocity of the point at offset
    /// `r2` by `K j`. Zero for static and kinematic bodies.
    pub fn inverse_mass_matrix(&self, r1: DVec3, r2: DVec3) -> DMat3 {
        DMat3::from_diagonal(DVec3::splat(self.inverse_mass))
            - hat(r2) * self.inverse_inertia_world() * hat(r1)
    }

    /// `½ m v² + ½ ω·Iω`; zero for static bodies, and for kinematic bodies (infinite mass has no
    /// meaningful energy, so they are left out of totals).
    pub fn kinetic_energy(&self) -> f64 {
        if self.kind != BodyKind::Dynamic {
            return 0.0;
        }
        let v = self.state.linear_velocity;
        let w = self.state.angular_velocity;
        0.5 * self.mass() * v.length_squared() + 0.5 * w.dot(self.inertia_world() * w)
    }

    /// `m v`; zero for non-dynamic bodies.
    pub fn linear_momentum(&self) -> DVec3 {
        if self.kind != BodyKind::Dynamic {
            return DVec3::ZERO;
        }
        self.mass() * self.state.linear_velocity
    }

    /// Angular momentum about the centre of mass, `I ω`, world frame.
    pub fn angular_momentum_about_com(&self) -> DVec3 {
        if self.kind != BodyKind::Dynamic {
            return DVec3::ZERO;
        }
        self.inertia_world() * self.state.angular_velocity
    }

    /// Angular momentum about a fixed world point: `(x − o) × m v + I ω`.
    pub fn angular_momentum_about(&self, origin_world: DVec3) -> DVec3 {
        (self.state.com_world - origin_world).cross(self.linear_momentum())
            + self.angular_momentum_about_com()
    }
}
