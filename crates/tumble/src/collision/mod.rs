//! Collision detection. This part is the convex narrow phase: support functions, GJK distance,
//! EPA penetration, the separating-axis test with face clipping for polyhedra, closed forms for
//! spheres and capsules, contact manifolds, and the shape-pair table that picks among them
//! (`narrow_phase::collide`). See `docs/collision.md` for the derivations.

pub mod clip;
pub mod convex_contact;
pub mod epa;
pub mod feature;
pub mod gjk;
pub mod manifold;
pub mod narrow_phase;
pub mod polytope;
pub mod round;
pub mod sat;
pub mod segment;
pub mod support;

pub use manifold::{ContactPoint, Manifold};
pub use narrow_phase::{collide, PairCache};
