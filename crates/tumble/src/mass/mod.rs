//! Mass properties: mass, centre of mass, inertia tensor about the centre of mass, principal
//! moments and axes — for primitives, closed triangle meshes (Mirtich–Eberly) and compounds.
//!
//! Frames: every quantity is expressed in the frame the shape is defined in (the body frame for a
//! body's shape). The inertia tensor is always taken about the centre of mass.

use crate::math::{DMat3, DVec3};

mod eigen;
mod mesh;
mod primitives;
mod volume_integrals;

pub use eigen::symmetric_eigen;
pub use mesh::{validate_closed_mesh, validate_mesh_surface};

/// What went wrong computing mass properties. Every variant says what and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize, serde::Deserialize)]
pub enum MassError {
    #[error("{what} must be finite and > 0, got {value}")]
    NotPositive { what: &'static str, value: f64 },
    #[error("mesh vertex {index} is not finite: ({x}, {y}, {z})")]
    NonFiniteVertex { index: usize, x: f64, y: f64, z: f64 },
    #[error("mesh has no triangles")]
    EmptyMesh,
    #[error("mesh triangle {triangle} refers to vertex {vertex}, but there are only {count} vertices")]
    IndexOutOfRange { triangle: usize, vertex: u32, count: usize },
    #[error("mesh triangle {triangle} is degenerate (repeated vertex or zero area)")]
    DegenerateTriangle { triangle: usize },
    #[error("mesh is open: edge ({a}, {b}) belongs to {count} triangle(s), a closed mesh needs exactly 2")]
    OpenMesh { a: u32, b: u32, count: usize },
    #[error("mesh winding is inconsistent: edge ({a}, {b}) is used in the same direction by triangles {t1} and {t2}")]
    InconsistentWinding { a: u32, b: u32, t1: usize, t2: usize },
    #[error("mesh is inside out (signed volume {volume} < 0): its triangles wind clockwise seen from outside; reverse each triangle's vertex order")]
    InvertedMesh { volume: f64 },
    #[error("mesh encloses no volume (signed volume {volume})")]
    ZeroVolume { volume: f64 },
    #[error("compound has no parts")]
    EmptyCompound,
    #[error("{what} has no mass properties: it is static-only geometry; use it on a static body")]
    StaticOnly { what: &'static str },
}

/// Mass properties of a solid in its own frame.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MassProperties {
    /// Geometric volume, m³.
    pub volume: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass in the shape's frame, m.
    pub center_of_mass: DVec3,
    /// Inertia tensor about the centre of mass, in the shape's axes, kg·m².
    pub inertia: DMat3,
}

/// Principal moments (ascending) and principal axes: `inertia = axes · diag(moments) · axesᵀ`,
/// with `axes` a rotation (orthonormal columns, det +1).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PrincipalFrame {
    pub moments: DVec3,
    pub axes: DMat3,
}
