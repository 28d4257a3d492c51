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
//! When the step has threads, the constraints within a colour are ordered by their lower moving
//! body's slot. The order within a colour changes no number (its constraints share no moving
//! body), but it decides which thread touches which body: in input order a thread's share of one
//! colour and its share of the next had bodies in common only by chance, and about half the
//! bodies a thread worked on were last written by the other thread's core, whose cache lines then
//! crossed between the cores at almost every colour. Ordered by body, each thread keeps working on
//! about the same bodies from colour to colour: the 2,000-ball rain ran 11% faster on two threads
//! at 3 substeps and 16% at 8. On one thread the sort only cost (1%), and input order stays.
//! (The overflow keeps input order: its constraints do share bodies, and are solved one after the
//! other.)
//!
//! Within a colour a body that does not move may appear in many constraints at once; each works on
//! a private copy of it (solver_threads.rs, `with_pair`).

use std::ops::Range;

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
    /// Each colour's run (not the overflow's), in order; see `colour_end`.
    colour_runs: Vec<Range<usize>>,
    /// Per constraint, in input order: its place in colour order.
    slot_of: Vec<usize>,
    /// Per constraint, in input order: the slot of its lower moving body (the order within a
    /// colour).
    body_of: Vec<u32>,
    /// Scratch of the counting sort by `body_of`: per body slot, where its constraints start.
    body_starts: Vec<u32>,
    /// The constraints (inputs) in order of `body_of`, input order among equals.
    by_body: Vec<u32>,
}

impl ContactColouring {
    /// Colours the constraints between the body pairs `pairs` (in input order) of the
    /// `body_count` body slots, each body with whether it moves (is dynamic), and returns how many
    /// there are; `slot` then gives each one's place in colour order (input order within a
    /// colour).
    /// With `by_body`, the constraints within a colour are ordered by body instead (see the
    /// module docs); the solver's result is the same either way.
    pub fn colour(
        &mut self,
        pairs: impl Iterator<Item = ((usize, bool), (usize, bool))>,
        body_count: usize,
        by_body: bool,
    ) -> usize {
        self.body_colours.clear();
        self.body_colours.resize(body_count, 0);
        self.colour_of.clear();
        self.body_of.clear();
        let mut counts = [0usize; COLOUR_COUNT + 1];
        for ((body_a, moving_a), (body_b, moving_b)) in pairs {
            let lower = match (moving_a, moving_b) {
                (true, true) => body_a.min(body_b),
                (true, false) => body_a,
                (false, true) => body_b,
                // Takes part with no moving body only in tests; any place will do.
                (false, false) => 0,
            };
            if by_body {
                self.body_of.push(lower as u32);
            }
            let mut used = 0u64;
            for (i, moving) in [(body_a, moving_a), (body_b, moving_b)] {
                if moving {
                    used |= self.body_colours[i];
                }
            }
            let colour = (used.trailing_ones() as usize).min(COLOUR_COUNT);
            if colour < COLOUR_COUNT {
                for (i, moving) in [(body_a, moving_a), (body_b, moving_b)] {
                    if moving {
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
        if by_body {
            self.sort_by_body(body_count);
            self.slot_of.resize(self.colour_of.len(), 0);
            // The colours in body order (see the module docs), then the overflow in input order.
            for &input in &self.by_body {
                let colour = usize::from(self.colour_of[input as usize]);
                if colour < COLOUR_COUNT {
                    self.slot_of[input as usize] = next[colour];
                    next[colour] += 1;
                }
            }
            for (input, &colour) in self.colour_of.iter().enumerate() {
                if usize::from(colour) == COLOUR_COUNT {
                    self.slot_of[input] = next[COLOUR_COUNT];
                    next[COLOUR_COUNT] += 1;
                }
            }
        } else {
            for &colour in &self.colour_of {
                let slot = &mut next[usize::from(colour)];
                self.slot_of.push(*slot);
                *slot += 1;
            }
        }

        self.colour_runs.clear();
        self.colour_runs.extend(runs[..COLOUR_COUNT].iter().filter(|run| !run.is_empty()).cloned());
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

    /// `by_body`: the inputs in order of `body_of` (a counting sort over the `body_count` slots;
    /// stable, so input order among the constraints of one body).
    fn sort_by_body(&mut self, body_count: usize) {
        self.body_starts.clear();
        self.body_starts.resize(body_count + 1, 0);
        for &body in &self.body_of {
            self.body_starts[body as usize + 1] += 1;
        }
        for i in 1..self.body_starts.len() {
            self.body_starts[i] += self.body_starts[i - 1];
        }
        self.by_body.clear();
        self.by_body.resize(self.body_of.len(), 0);
        for (input, &body) in self.body_of.iter().enumerate() {
            let start = &mut self.body_starts[body as usize];
            self.by_body[*start as usize] = input as u32;
            *start += 1;
        }
    }

    /// The place in colour order of the constraint `input` (in input order). A permutation of
    /// `0..count`.
    pub fn slot(&self, input: usize) -> usize {
        self.slot_of[input]
    }

    /// Where the colour of the constraint at `place` (in colour order) ends, or `None` in the
    /// overflow. Within one colour no two constraints share a moving body, so any of them can be
    /// solved side by side (contact_lanes.rs).
    pub fn colour_end(&self, place: usize) -> Option<usize> {
        let i = self.colour_runs.partition_point(|run| run.end <= place);
        self.colour_runs.get(i).filter(|run| run.contains(&place)).map(|run| run.end)
    }

    /// The solver's stages over the constraints in colour order: a colour with enough constraints
    /// to split between threads (`true`), or a run of consecutive colours too small for that, or
    /// the overflow, done by one thread (`false`).
    pub fn stages(&self) -> &[(Range<usize>, bool)] {
        &self.stages
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::solver_body::SolverBody;
    use crate::math::{DQuat, DVec3};

    /// Ordered by body, the colours are the same and each colour's run goes by lower moving body;
    /// only the places within a colour differ from input order.
    #[test]
    fn ordering_by_body_keeps_the_colours_and_sorts_each_colour() {
        // Body 0 is the ground (fixed); 1..=12 move. A chain of pairs plus each body on the
        // ground, given in a scrambled order.
        let mut bodies = vec![SolverBody::FIXED];
        bodies.extend((1..=12).map(|_| SolverBody::dynamic_for_test(1.0, DVec3::ONE, DQuat::IDENTITY)));
        let mut pairs: Vec<(usize, usize)> = (1..12).map(|i| (i + 1, i)).collect();
        pairs.extend((1..=12).map(|i| (0, i)));
        pairs.reverse();
        pairs.swap(3, 17);
        let (mut by_input, mut by_body) = (ContactColouring::default(), ContactColouring::default());
        let with_motion =
            || pairs.iter().map(|&(a, b)| ((a, bodies[a].is_dynamic()), (b, bodies[b].is_dynamic())));
        assert_eq!(by_input.colour(with_motion(), bodies.len(), false), pairs.len());
        assert_eq!(by_body.colour(with_motion(), bodies.len(), true), pairs.len());
        assert_eq!(by_input.colour_of, by_body.colour_of);
        assert_eq!(by_input.stages, by_body.stages);
        let lower = |(a, b): (usize, usize)| if a == 0 { b } else { a.min(b) };
        let mut order = vec![usize::MAX; pairs.len()];
        for input in 0..pairs.len() {
            order[by_body.slot(input)] = input;
        }
        assert!(order.iter().all(|&input| input != usize::MAX), "slots are a permutation");
        for w in order.windows(2) {
            let (c0, c1) = (by_body.colour_of[w[0]], by_body.colour_of[w[1]]);
            assert!(c0 <= c1, "colours in order");
            if c0 == c1 {
                assert!(lower(pairs[w[0]]) <= lower(pairs[w[1]]), "a colour by body: {:?}", (w, pairs));
            }
        }
        // In input order, input order within each colour.
        for input in 1..pairs.len() {
            for earlier in 0..input {
                if by_input.colour_of[earlier] == by_input.colour_of[input] {
                    assert!(by_input.slot(earlier) < by_input.slot(input));
                }
            }
        }
    }
}
