//! Graph colouring of the contact constraints: constraints of one colour share no moving body, so
//! a colour can be solved in any order, on any number of threads, with the same result.
//!
//! Each constraint takes the lowest colour that neither of its moving bodies has yet (bodies that
//! do not move — static, kinematic, asleep — never limit the colouring: the constraints only read
//! them). Constraints are visited in the contact manager's order, so the colouring depends on the
//! scene alone, never on the thread count. A constraint for which all [`COLOUR_COUNT`] colours
//! are taken (a body touching very many others) goes to the overflow, solved last, one after
//! the other.
//!
//! The solver then sweeps the constraints colour by colour (a Gauss–Seidel sweep in colour order,
//! as in Box2D v3's solver). The constraints are prepared straight into that order, so a colour is
//! one contiguous run that splits into shares for the threads.
//!
//! Within a colour a body that does not move may appear in many constraints at once; each works on
//! a private copy of it (solver_threads.rs, `with_pair`).

use std::ops::Range;

use crate::dynamics::solver_body::SolverBody;

/// Colours before the overflow. Bodies in a box pyramid touch at most about a dozen others.
const COLOUR_COUNT: usize = 32;

/// A colour's constraints are split between threads only when there are at least this many: below
/// that the hand-over costs more than it saves.
const PARALLEL_MIN_CONSTRAINTS: usize = 64;

/// The colouring of one step's contact constraints, and the scratch it is built with (kept between
/// steps, so a steady-state step does not allocate).
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactColouring {
    /// Per body slot: a bit per colour already used by one of its constraints.
    body_colours: Vec<u64>,
    /// Per constraint, in input order: its colour (`COLOUR_COUNT` = overflow).
    colour_of: Vec<u8>,
    /// See `stages`.
    stages: Vec<(Range<usize>, bool)>,
    /// Per constraint, in input order: its place in colour order.
    slot_of: Vec<usize>,
}

impl ContactColouring {
    /// Colours the constraints between the body pairs `pairs` (in input order) and returns how
    /// many there are; `slot` then gives each one's place in colour order (input order within a
    /// colour).
    pub fn colour(&mut self, pairs: impl Iterator<Item = (usize, usize)>, bodies: &[SolverBody]) -> usize {
        self.body_colours.clear();
        self.body_colours.resize(bodies.len(), 0);
        self.colour_of.clear();
        let mut counts = [0usize; COLOUR_COUNT + 1];
        for (body_a, body_b) in pairs {
            let moving = |i: usize| bodies[i].is_dynamic();
            let mut used = 0u64;
            for i in [body_a, body_b] {
                if moving(i) {
                    used |= self.body_colours[i];
                }
            }
            let colour = (used.trailing_ones() as usize).min(COLOUR_COUNT);
            if colour < COLOUR_COUNT {
                for i in [body_a, body_b] {
                    if moving(i) {
                        self.body_colours[i] |= 1 << colour;
                    }
                }
            }
            self.colour_of.push(colour as u8);
            counts[colour] += 1;
        }

        // Counting sort: each colour's run (then the overflow's) starts where the previous one ends.
        let mut start = 0;
        let runs: [Range<usize>; COLOUR_COUNT + 1] = std::array::from_fn(|colour| {
            start += counts[colour];
            start - counts[colour]..start
        });
        let mut next: [usize; COLOUR_COUNT + 1] = std::array::from_fn(|colour| runs[colour].start);
        self.slot_of.clear();
        for &colour in &self.colour_of {
            let slot = &mut next[usize::from(colour)];
            self.slot_of.push(*slot);
            *slot += 1;
        }

        self.stages.clear();
        for (colour, run) in runs.iter().enumerate() {
            let split = colour < COLOUR_COUNT && run.len() >= PARALLEL_MIN_CONSTRAINTS;
            match self.stages.last_mut() {
                _ if run.is_empty() => {}
                Some((serial, false)) if !split => serial.end = run.end,
                _ => self.stages.push((run.clone(), split)),
            }
        }
        self.slot_of.len()
    }

    /// The place in colour order of the constraint `input` (in input order). A permutation of
    /// `0..count`.
    pub fn slot(&self, input: usize) -> usize {
        self.slot_of[input]
    }

    /// The solver's stages over the constraints in colour order: a colour with enough constraints
    /// to split between threads (`true`), or a run of consecutive colours too small for that, or
    /// the overflow, done by one thread (`false`).
    pub fn stages(&self) -> &[(Range<usize>, bool)] {
        &self.stages
    }
}
