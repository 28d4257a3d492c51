//! A joint's limit rows written out as plain Jacobians, for the joint tree
//! (`dynamics/joint_tree/`), which takes a limit row into its joint's block while the limit
//! pushes (an active set), so a figure with limits is solved exactly as a whole.
//!
//! The rows are the limit parts' own (`ball.rs`, `hinge.rs`, `slider.rs`): the same Jacobians,
//! the same `C ≥ 0` (`C` the distance to the limit, negative past it), the same accumulated
//! impulses (`λ ≥ 0`, pushing). Their order is fixed per kind, and names the part a row's
//! impulse goes to (`Joint::add_limit_impulse`):
//!
//! | kind | rows |
//! |---|---|
//! | ball | swing, twist lower, twist upper |
//! | hinge | lower, upper |
//! | slider | lower, upper |
//!
//! Of a pair of sides only one may push (`eligible`): the nearer, or in a velocity solve the one
//! nearer at the end of the substep at the current speed (`choose_approached_sides`). A joint's
//! block then stays within six rows (a hinge's five and one limit), and both sides of a range
//! can only be reached at once by a joint that moves across the whole range in one substep.

use super::equality::RowJacobian;
use crate::math::DVec3;

/// Most limit rows of any joint (a ball joint's swing and two twist sides).
pub(crate) const MAX_LIMIT_ROWS: usize = 3;

/// One limit row now.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct LimitRow {
    pub jacobian: RowJacobian,
    /// `C`: the distance to the limit (rad or m), negative past it.
    pub error: f64,
    /// The part's accumulated impulse (≥ 0).
    pub impulse: f64,
    /// Whether the row may push this pass: it has an axis now (a swing row has none while the
    /// two joint axes are aligned) and is the nearer side of its pair.
    pub eligible: bool,
}

/// A joint's limit rows now, in the kind's order (see the module comment).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct LimitRows {
    pub len: usize,
    pub rows: [LimitRow; MAX_LIMIT_ROWS],
    /// The first rows of the pairs of sides (`choose_nearer_side`).
    pairs: [usize; 2],
    pair_count: usize,
}

impl LimitRows {
    /// A purely angular row about `axis` (hinge and twist sides, the swing cone): `Ċ = axis·(ω_b − ω_a)`.
    pub fn push_angular(&mut self, axis: Option<DVec3>, error: f64, impulse: f64) {
        let jacobian = axis.map_or(RowJacobian::default(), |axis| RowJacobian {
            angular_a: axis,
            angular_b: axis,
            ..RowJacobian::default()
        });
        self.push(LimitRow { jacobian, error, impulse, eligible: axis.is_some() });
    }

    /// No rows (the arrays are left as they are).
    pub fn clear(&mut self) {
        (self.len, self.pair_count) = (0, 0);
    }

    pub fn push(&mut self, row: LimitRow) {
        self.rows[self.len] = row;
        self.len += 1;
    }

    /// Rows `k` and `k + 1` are the two sides of one range: leaves the farther out of this pass.
    pub fn choose_nearer_side(&mut self, k: usize) {
        self.pairs[self.pair_count] = k;
        self.pair_count += 1;
        self.choose_side(k, self.rows[k].error, self.rows[k + 1].error);
    }

    /// For a velocity solve: of each pair of sides, leaves out the one farther at the end of a
    /// substep of length `h` at the rows' velocities now (`velocity`), so that a joint swinging
    /// hard across a narrow range meets the side it is heading for.
    pub fn choose_approached_sides(&mut self, h: f64, velocity: impl Fn(&RowJacobian) -> f64) {
        for p in 0..self.pair_count {
            let k = self.pairs[p];
            if !(self.rows[k].eligible || self.rows[k + 1].eligible) {
                continue; // no axis now
            }
            let ahead = |row: &LimitRow| row.error + h * velocity(&row.jacobian);
            self.choose_side(k, ahead(&self.rows[k]), ahead(&self.rows[k + 1]));
        }
    }

    fn choose_side(&mut self, k: usize, lower: f64, upper: f64) {
        (self.rows[k].eligible, self.rows[k + 1].eligible) = (lower <= upper, lower > upper);
    }
}
