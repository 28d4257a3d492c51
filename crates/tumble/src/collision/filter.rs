//! Collision filtering: which shapes may touch.

/// Group/mask filtering: shapes `a` and `b` collide when `a.group & b.mask != 0` and
/// `b.group & a.mask != 0`. The default (group 1, mask all) collides with everything.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct CollisionFilter {
    /// The categories this shape belongs to (bits).
    pub group: u32,
    /// The categories this shape collides with (bits).
    pub mask: u32,
}

impl Default for CollisionFilter {
    fn default() -> Self {
        CollisionFilter { group: 1, mask: u32::MAX }
    }
}

impl CollisionFilter {
    /// Both sides must accept the other.
    pub fn accepts(&self, other: &CollisionFilter) -> bool {
        (self.group & other.mask) != 0 && (other.group & self.mask) != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filtering_is_symmetric() {
        let debris = CollisionFilter { group: 0b10, mask: 0b01 };
        let ground = CollisionFilter { group: 0b01, mask: u32::MAX };
        assert!(debris.accepts(&ground) && ground.accepts(&debris));
        assert!(!debris.accepts(&debris), "debris ignores debris");
    }
}
