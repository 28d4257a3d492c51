//! Collision detection: bounding volumes, the broad phase that finds candidate pairs, and queries.
//!
//! Frames: every `Aabb` and `Ray` here is in world coordinates unless its name says `_local`.

pub mod aabb;
pub mod broad_phase;
pub mod dynamic_tree;
pub mod ray;

pub use aabb::{shape_aabb, Aabb};
pub use broad_phase::{BroadPhase, ProxyKey, ProxyKind, ProxyUpdate};
pub use dynamic_tree::{DynamicTree, ProxyId};
pub use ray::{ray_cast_shape, Ray, RayHit};
