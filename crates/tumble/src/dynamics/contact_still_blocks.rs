//! The blocks of still manifolds' groups (contact_lanes.rs): four consecutive manifolds of one
//! colour with their step-constant rows in lanes, written once a step, and their state while they
//! go as a group; and the groups' entry points for the solver's stages. docs/solver.md, "Blocks:
//! the groups' rows and state side by side".

use super::{
    block_group, gather_rows, gather_state, scatter_state, select_state, solve_pass, velocities,
    warm_start_pass, BodyLanes, GroupVelocities, StillRows, StillState, GROUP,
};
use crate::dynamics::contact_block::{RowSet, ALL_ROWS, MAX_POINTS};
use crate::dynamics::contact_solver::ContactConstraint;
use crate::dynamics::solver::StepContext;
use crate::dynamics::solver_body::{still_pair, SolverBody};
use crate::lanes::Lane;
use wide::f64x4;

/// Four manifolds of one colour side by side (places `4j..4j + 4` in colour order) for a step's
/// groups: their rows, written once a step, and — from the first pass that takes them as a group
/// until they go alone or the step's stages that read the manifolds (`give_back_state`) — their
/// state. A group's passes then load both whole instead of gathering some hundred numbers from
/// four manifolds and scattering what changed back each time, and read the rows in place rather
/// than from a copy in the lane state.
#[derive(Clone, Copy)]
pub(crate) struct StillBlock {
    rows: StillRows<f64x4>,
    point_counts: [usize; GROUP],
    /// Every manifold fits the lanes (`fits_lanes`).
    fits_lanes: bool,
    /// The manifolds' state is here, not in the manifolds.
    state_here: bool,
    state: StillState<f64x4>,
    /// The rows each manifold's block last left free (`ContactConstraint::free_rows`).
    free_rows: [RowSet; GROUP],
}

impl Default for StillBlock {
    fn default() -> Self {
        let empty = |_| &ContactConstraint::EMPTY;
        let rows = gather_rows(empty);
        StillBlock {
            point_counts: [0; GROUP],
            fits_lanes: false,
            state_here: false,
            state: gather_state(&rows.live, empty),
            free_rows: [ALL_ROWS; GROUP],
            rows,
        }
    }
}

impl StillBlock {
    /// This block made the block of up to four manifolds (no group takes one of fewer); their
    /// state stays with them. The rows are written only where the group can be taken at all
    /// (`fits_lanes`): a rain of spheres has none, and writing them cost it a tenth of its
    /// speed on two threads.
    pub(crate) fn fill(&mut self, contacts: &[ContactConstraint]) {
        self.fits_lanes = contacts.len() == GROUP && contacts.iter().all(ContactConstraint::fits_lanes);
        self.state_here = false;
        if self.fits_lanes {
            self.rows = gather_rows(|k| &contacts[k]);
            self.point_counts = std::array::from_fn(|k| contacts[k].point_count);
        }
    }

    /// Whether the four manifolds can go as a group now: each fits the lanes and its bodies are a
    /// still pair (`still_pair`).
    #[inline]
    fn is_still(&self, bodies: &[&SolverBody; 2 * GROUP]) -> bool {
        self.fits_lanes && bodies.chunks_exact(2).all(|pair| still_pair(pair[0], pair[1]))
    }

    /// The state of `contacts` (the block's four) into the block, unless it is here.
    #[inline]
    fn take_state(&mut self, contacts: &[ContactConstraint]) {
        if !self.state_here {
            self.state = gather_state(&self.rows.live, |k| &contacts[k]);
            self.free_rows = std::array::from_fn(|k| contacts[k].free_rows);
            self.state_here = true;
        }
    }

    /// The state back into `contacts` (the block's four), if it is here.
    #[inline]
    pub(crate) fn give_back_state(&mut self, contacts: &mut [ContactConstraint]) {
        if self.state_here {
            for (k, contact) in contacts.iter_mut().enumerate().take(GROUP) {
                scatter_state(&self.state, k, contact, true);
                contact.free_rows = self.free_rows[k];
            }
            self.state_here = false;
        }
    }

    /// Whether the four manifolds' state is here (taken by a pass as a group), not in them.
    #[inline]
    pub(crate) fn holds_state(&self) -> bool {
        self.state_here
    }

    /// `ContactConstraint::update_steady_load` of the four manifolds, whose state must be here.
    pub(crate) fn update_steady_loads(&mut self, steady_load_time: f64, h: f64) {
        debug_assert!(self.state_here);
        type L = f64x4;
        let (lower, upper) = (L::splat(0.2 * steady_load_time), L::splat(steady_load_time));
        let (h, one) = (L::splat(h), L::splat(1.0));
        let m = &mut self.state;
        for i in 0..MAX_POINTS {
            let live = self.rows.live[i];
            // `opaque`: a blend and a store, not a masked store (lanes.rs).
            let (steady, age) = (m.steady_normal[i].opaque(), m.steady_age[i].opaque());
            let rate = Lane::min(h / age.clamp(lower, upper), one);
            m.steady_normal[i] = L::select(live, steady + rate * (m.normal_impulse[i] - steady), steady);
            m.steady_age[i] = L::select(live, age + h, age);
        }
    }
}

impl StillBlock {
    /// The group's bodies in lanes, with the manifolds' state in the block, when all four are
    /// still; else `None`, with the state back in the manifolds (each then goes alone).
    #[inline(always)]
    fn take_group(
        &mut self,
        contacts: &mut [ContactConstraint],
        bodies: &[&SolverBody; 2 * GROUP],
    ) -> Option<(BodyLanes<f64x4>, BodyLanes<f64x4>)> {
        if !self.is_still(bodies) {
            self.give_back_state(contacts);
            return None;
        }
        self.take_state(contacts);
        Some((BodyLanes::gather(|k| bodies[2 * k]), BodyLanes::gather(|k| bodies[2 * k + 1])))
    }
}

/// Stage "warm start" of four still manifolds of one colour at once (`block`: theirs; `bodies`:
/// each one's a and b), or `None` when they are not all still (then each goes alone, with its
/// state back).
pub(crate) fn warm_start_group(
    contacts: &mut [ContactConstraint],
    block: &mut StillBlock,
    bodies: &[&SolverBody; 2 * GROUP],
) -> Option<GroupVelocities> {
    let (mut a, mut b) = block.take_group(contacts, bodies)?;
    warm_start_pass(&block.rows, &block.state, &mut a, &mut b);
    Some(velocities(&a, &b))
}

/// Stage "solve"/"relax" of four still manifolds of one colour at once, or `None` when they are
/// not all still (as `warm_start_group`). A lane whose block does not take every row free in the
/// first try (or has one point) solves its block alone, as the one-manifold path does.
pub(crate) fn solve_group(
    contacts: &mut [ContactConstraint],
    block: &mut StillBlock,
    bodies: &[&SolverBody; 2 * GROUP],
    ctx: &StepContext,
    use_bias: bool,
) -> Option<GroupVelocities> {
    let (mut a, mut b) = block.take_group(contacts, bodies)?;
    let StillBlock { rows, point_counts, state, free_rows, .. } = block;
    let before = *state;
    let active = solve_pass(rows, state, &mut a, &mut b, ctx, use_bias, |inputs, active| {
        block_group(contacts, free_rows, point_counts, &rows.live, inputs, active, use_bias)
    });
    // An idle lane's state is as it was (the one-manifold path leaves an idle manifold alone).
    // A resting group's lanes are all active: then there is nothing to select.
    if !active.all() {
        *state = select_state(active, state, &before);
    }
    Some(velocities(&a, &b))
}
