//! Dynamics: the soft-step constraint solver (Catto's Solver2D / Box2D v3 design, in 3D), the
//! joints built from reusable constraint parts, and the solver's per-body working state.
//!
//! See `docs/solver.md` for the derivation of the soft constraints and the stage order.

pub(crate) mod colouring;
pub mod contact;
pub(crate) mod contact_block;
pub(crate) mod contact_friction;
pub(crate) mod contact_solver;
pub(crate) mod island;
pub mod joint;
pub(crate) mod joint_components;
pub(crate) mod joint_tree;
pub mod lcp;
pub mod material;
pub(crate) mod softness;
pub mod solver;
pub(crate) mod solver_body;
pub(crate) mod solver_threads;
pub(crate) mod stage_shares;

pub use contact_solver::{ContactImpulse, ContactMaterial};
pub use island::SleepSettings;
pub use material::Material;
pub use softness::Softness;
