//! Collision detection: bounding volumes and the broad phase that finds candidate pairs; the
//! convex narrow phase (support functions, GJK distance, EPA penetration, the separating-axis test
//! with face clipping for polyhedra, closed forms for spheres and capsules, contact manifolds and
//! the shape-pair table `narrow_phase::collide`); static geometry (planes, height fields and
//! triangle meshes with their BVH and the internal-edge rule); the contact manager that keeps contacts between
//! steps; ray casts and filtering; the time of impact of a swept convex shape (for bullets,
//! `continuous.rs`). See `docs/collision.md` for the derivations.
//!
//! Frames: every `Aabb` and `Ray` here is in world coordinates unless its name says `_local`.

pub mod aabb;
pub mod broad_phase;
pub mod clip;
pub(crate) mod contact_manager;
pub(crate) mod contact_store;
pub mod convex_contact;
pub mod dynamic_tree;
pub mod epa;
pub mod feature;
pub mod filter;
pub mod gjk;
pub mod manifold;
pub mod manifold_reuse;
pub mod mesh_bvh;
pub mod mesh_contact;
pub mod narrow_phase;
pub mod plane_contact;
pub mod polytope;
pub mod ray;
pub mod round;
pub mod sat;
pub mod sat_apart;
pub mod segment;
pub mod static_pairs;
pub mod support;
pub mod time_of_impact;
pub mod triangle;

pub use aabb::{shape_aabb, Aabb};
pub use broad_phase::{BroadPhase, ProxyKey, ProxyKind, ProxyUpdate};
pub use dynamic_tree::{DynamicTree, ProxyId};
pub use filter::CollisionFilter;
pub use manifold::{ContactPoint, Manifold};
pub use narrow_phase::{collide, PairCache};
pub use ray::{ray_cast_shape, Ray, RayHit};
