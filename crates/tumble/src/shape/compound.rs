//! Several shapes with local poses, rigidly joined on one body.

use super::Shape;
use crate::mass::MassError;
use crate::math::Transform;

/// One part of a compound: a shape placed at `pose` in the compound's frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CompoundChild {
    pub pose: Transform,
    pub shape: Shape,
}

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Compound {
    children: Vec<CompoundChild>,
}

impl Compound {
    /// A compound of at least one part.
    pub fn new(children: Vec<CompoundChild>) -> Result<Self, MassError> {
        if children.is_empty() {
            return Err(MassError::EmptyCompound);
        }
        Ok(Self { children })
    }

    pub fn children(&self) -> &[CompoundChild] {
        &self.children
    }
}
