//! # Tumble
//!
//! A 3D rigid-body dynamics engine: mass properties, Newton–Euler motion with exact free rotation,
//! and (in later modules) collisions, contacts and joints solved together.
//!
//! Conventions: f64, SI units, right-handed with **Z up**, quaternions as (x, y, z, w).

pub mod body;
pub mod collision;
pub mod continuous;
pub mod dynamics;
pub mod events;
pub mod id;
pub mod integrate;
mod lanes;
pub mod mass;
pub mod math;
pub mod non_finite;
mod prefetch;
pub mod profile;
pub mod query;
pub mod scenes;
pub mod shape;
mod sin_cos;
pub mod snapshot;
mod state_hash;
mod step;
mod step_threads;
mod waiting;
pub mod world;

pub use body::{Body, BodyDef, BodyKind, BodyState};
pub use collision::{Aabb, CollisionFilter};
pub use dynamics::joint::{
    BallJoint, DistanceJoint, FixedJoint, HingeJoint, Joint, JointDef, JointKind, Limits, Motor, SliderJoint,
    SpringSettings,
};
pub use dynamics::solver::SolverSettings;
pub use dynamics::{Material, SleepSettings};
pub use events::BodyPair;
pub use id::{BodyId, JointId};
pub use mass::{MassError, MassProperties, PrincipalFrame};
pub use math::{DMat3, DQuat, DVec3, Transform};
pub use non_finite::NonFiniteBody;
pub use query::{QueryError, QueryFilter, RayCastHit};
pub use shape::{
    Capsule, Compound, CompoundChild, Cone, ConvexHull, Cuboid, Cylinder, HeightField, HullError, Plane,
    Shape, ShapeError, Sphere, TriMesh,
};
pub use snapshot::SnapshotError;
pub use world::{World, WorldDef, WorldError};
