//! The solver's threads: every one of the step's threads (step_threads.rs) runs the whole
//! substep loop, each taking pieces of every stage, and a stage ends when its last piece is done
//! (stage_shares.rs; Box2D v3's solver closes its stages the same way).
//!
//! A step has hundreds of stages (each colour of each pass of each substep, colouring.rs); handing
//! each to a thread pool would cost a wake-up per stage, more than a small stage's work. Here the
//! threads stay awake for the step and a stage boundary costs a few atomic operations. No thread
//! has to reach a stage's end: one whose core the machine has taken for a while holds up the
//! others only by a piece it took, and catches up when it runs again.
//!
//! Pieces never change a number: a body stage treats every body on its own, and a colour's
//! constraints share no moving body, and neither do two components of joints
//! (joint_components.rs), so which thread does what is invisible in the result. Stages that are
//! not split (joint trees, small colours, the overflow colour) are one piece, done by one thread
//! while the others wait.

#![allow(unsafe_code)] // `Shared`: threads write distinct elements within a stage.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::dynamics::colouring::ContactColouring;
use crate::dynamics::contact_solver::{ContactConstraint, GroupVelocities, StillBlock, GROUP};
use crate::dynamics::joint::Joint;
use crate::dynamics::joint_components::JointComponents;
use crate::dynamics::solver_body::SolverBody;
use crate::dynamics::stage_shares::{Left, StageShares};
use crate::id::Slot;
use crate::step_threads::StepThreads;
use crate::waiting::Waiting;

/// The panic of a thread released from a stage because another thread panicked.
pub(crate) const RELEASED: &str = "another solver thread panicked";

/// Where a fixed number of threads meet: the solver's stages, which the threads share out in
/// pieces and which end when their last piece is done (stage_shares.rs), and how a thread waits
/// for a stage's end (waiting.rs).
pub(crate) struct ThreadStages {
    threads: usize,
    shares: StageShares,
    /// Set when a thread panics, so the others stop waiting for it.
    poisoned: AtomicBool,
    waiting: Waiting,
}

impl ThreadStages {
    pub fn new(threads: usize) -> Self {
        ThreadStages {
            threads,
            shares: StageShares::new(threads),
            poisoned: AtomicBool::new(false),
            waiting: Waiting::default(),
        }
    }

    pub fn poison(&self) {
        self.poisoned.store(true, Ordering::Release);
        self.waiting.wake_all();
    }

    /// Thread `index`'s part of a stage (`StageShares::take_pieces`): returns once the stage is
    /// done. Everything written in the stage's pieces is then visible to this thread. Panics if
    /// another thread panicked.
    fn stage(&self, index: usize, range: Range<usize>, chunk: usize, f: impl FnMut(Range<usize>)) {
        match self.shares.take_pieces(index, range, chunk, f) {
            Left::Finished => self.waiting.wake_all(),
            Left::Done => {}
            Left::Waiting(stage) => {
                self.waiting
                    .wait_until(|| self.shares.is_done(stage) || self.poisoned.load(Ordering::Acquire));
                if !self.shares.is_done(stage) {
                    std::panic::panic_any(RELEASED);
                }
            }
        }
    }
}

/// The constraints a thread takes at a time of a colour split between the threads
/// (stage_shares.rs): eight groups of four (contact_lanes.rs), so a piece cuts no group apart;
/// a few microseconds of work, against some tens of nanoseconds to take it.
const CONTACT_PIECE: usize = 8 * GROUP;

/// Bodies, blocks of four manifolds and joint components a thread takes at a time.
const BODY_PIECE: usize = 64;
const BLOCK_PIECE: usize = 8;
const COMPONENT_PIECE: usize = 2;

/// One thread's place among the solver's threads.
#[derive(Clone, Copy)]
pub(crate) struct SolverThread<'a> {
    // Private: the shares' disjointness, which the unsafe accesses rest on, comes from each
    // thread having its own index.
    index: usize,
    count: usize,
    /// `None` when there is one thread.
    stages: Option<&'a ThreadStages>,
}

impl<'a> SolverThread<'a> {
    /// The only thread.
    pub const ALONE: SolverThread<'static> = SolverThread { index: 0, count: 1, stages: None };

    pub fn new(index: usize, stages: &'a ThreadStages) -> Self {
        SolverThread { index, count: stages.threads, stages: Some(stages) }
    }

    /// A stage over the items `range`: calls `f` on the pieces of it (cut at multiples of
    /// `chunk`) this thread takes — its own share first, then what is left of the others'
    /// (stage_shares.rs) — and returns once every piece is done, whoever did it. Every thread
    /// must go through the same stages in the same order. A stage of `range` in one piece:
    /// `chunk` of `range.end` or more.
    pub fn stage(&self, range: Range<usize>, chunk: usize, f: impl FnMut(Range<usize>)) {
        match self.stages {
            Some(stages) => stages.stage(self.index, range, chunk, f),
            None => {
                let mut f = f;
                if !range.is_empty() {
                    f(range)
                }
            }
        }
    }

    /// This thread's contiguous share of `range`.
    pub fn share(&self, range: Range<usize>) -> Range<usize> {
        let len = range.len();
        let (count, index) = (self.count, self.index);
        range.start + len * index / count..range.start + len * (index + 1) / count
    }
}

/// What the substeps work on, shared by the solver's threads. Every stage method is a stage
/// (`SolverThread::stage`): it returns once every piece of the stage is done, and within it each
/// thread writes only the pieces it took (of the bodies, of the contacts, of a colour's contacts,
/// which share no dynamic body, of the joints' components) or — in a stage of one piece, the
/// thread that took it — everything; that is what makes the accesses below sound.
pub(crate) struct SolveData<'a, S> {
    bodies: Shared<'a, SolverBody>,
    /// The bodies some constraint acts on (strictly increasing slots): the body stages' work.
    constrained: &'a [u32],
    /// The moving bodies no constraint acts on (strictly increasing slots).
    unconstrained: &'a [u32],
    contacts: Shared<'a, ContactConstraint>,
    /// The rows of the contacts four at a time, `blocks[j]` those at `4j..4j + 4` (empty unless
    /// the contacts go in groups): see `fill_blocks`.
    blocks: Shared<'a, StillBlock>,
    colouring: &'a ContactColouring,
    /// The joint pool's slots, by slot.
    joints: Shared<'a, Slot<Joint>>,
    /// The solved joints by component: a thread's share of them is its own in a joint stage.
    joint_components: &'a JointComponents,
    /// The state the stages that are not split work on (the joint trees).
    serial: Shared<'a, S>,
}

impl<'a, S: Send> SolveData<'a, S> {
    /// `contacts` must be in the order `colouring` sorted them into; `constrained` and
    /// `unconstrained` list body slots, each strictly increasing (so no slot twice);
    /// `joint_components` lists slots of live joints (each once).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        bodies: &'a mut [SolverBody],
        (constrained, unconstrained): (&'a [u32], &'a [u32]),
        contacts: &'a mut [ContactConstraint],
        blocks: &'a mut [StillBlock],
        colouring: &'a ContactColouring,
        (joints, joint_components): (&'a mut [Slot<Joint>], &'a JointComponents),
        serial: &'a mut S,
    ) -> Self {
        assert!(
            blocks.is_empty() || blocks.len() == contacts.len().div_ceil(GROUP),
            "a block per four contacts"
        );
        for list in [constrained, unconstrained] {
            assert!(list.windows(2).all(|w| w[0] < w[1]), "body lists must be strictly increasing");
            assert!(list.last().is_none_or(|&i| (i as usize) < bodies.len()), "body slot out of range");
        }
        SolveData {
            bodies: Shared::new(bodies),
            constrained,
            unconstrained,
            contacts: Shared::new(contacts),
            blocks: Shared::new(blocks),
            colouring,
            joints: Shared::new(joints),
            joint_components,
            serial: Shared::new(std::slice::from_mut(serial)),
        }
    }

    /// `f` on every solved joint with its two bodies, the joints' components (joint_components.rs)
    /// shared out whole; a body that is not dynamic as a private copy, as for the contacts.
    pub fn joints_with_bodies(
        &self,
        thread: SolverThread,
        f: impl Fn(&mut Joint, &mut SolverBody, &mut SolverBody),
    ) {
        let components = 0..self.joint_components.count();
        thread.stage(components, COMPONENT_PIECE, |piece| {
            for &slot in self.joint_components.slots(piece) {
                // SAFETY: each joint slot appears once in the components, and the components this
                // thread took are its own until the stage ends.
                let joint = unsafe { &mut self.joints.slice(slot as usize..slot as usize + 1)[0] };
                let joint = joint.value_mut().expect("solved joints are live");
                // SAFETY: the dynamic bodies of a component are its own (no other component's
                // joint has one), so this thread's until the stage ends; `with_pair` copies the
                // others.
                unsafe {
                    self.bodies.with_pair(joint.body_a.index(), joint.body_b.index(), |a, b| f(joint, a, b))
                };
            }
        });
    }

    /// `f` on every constrained body, shared out in pieces.
    pub fn bodies(&self, thread: SolverThread, f: impl Fn(&mut SolverBody)) {
        self.each_body(thread, self.constrained, f);
    }

    /// `f` on the unconstrained bodies in groups of up to `N` (in slot order; the last group's
    /// missing bodies are `None`), shared out in pieces.
    pub fn unconstrained_bodies<const N: usize>(
        &self,
        thread: SolverThread,
        f: impl Fn(&mut [Option<&mut SolverBody>; N]),
    ) {
        let slots = self.unconstrained;
        // Pieces of whole groups, so the groups are those of one walk over all the slots.
        thread.stage(0..slots.len(), BODY_PIECE.next_multiple_of(N), |piece| {
            for group in slots[piece].chunks(N) {
                let mut bodies = std::array::from_fn(|k| {
                    // SAFETY: the slots are distinct (checked in `new`) and in range, and the
                    // pieces this thread took are its own until the stage ends.
                    group
                        .get(k)
                        .map(|&slot| unsafe { &mut self.bodies.slice(slot as usize..slot as usize + 1)[0] })
                });
                f(&mut bodies);
            }
        });
    }

    fn each_body(&self, thread: SolverThread, slots: &[u32], f: impl Fn(&mut SolverBody)) {
        thread.stage(0..slots.len(), BODY_PIECE, |piece| {
            for &slot in &slots[piece] {
                // SAFETY: the slots are distinct (checked in `new`) and in range, and the pieces
                // this thread took are its own until the stage ends.
                f(unsafe { &mut self.bodies.slice(slot as usize..slot as usize + 1)[0] });
            }
        });
    }

    /// `f` on every contact on its own (no bodies), shared out in pieces.
    pub fn contacts(&self, thread: SolverThread, f: impl Fn(&mut ContactConstraint)) {
        thread.stage(0..self.contacts.len, CONTACT_PIECE, |piece| {
            // SAFETY: a piece this thread took, until the stage ends.
            unsafe { self.contacts.slice(piece) }.iter_mut().for_each(&f);
        });
    }

    /// `f` on every contact with its two bodies, colour by colour (colouring.rs): a large colour
    /// shared between the threads in pieces (`each_stage`), small ones and the overflow each on
    /// one thread.
    pub fn contacts_with_bodies(
        &self,
        thread: SolverThread,
        f: impl Fn(&mut ContactConstraint, &mut SolverBody, &mut SolverBody),
    ) {
        let solve = |part: Range<usize>| {
            // SAFETY: a piece of one colour this thread took (or a serial run, on this thread
            // alone), until the stage ends; a colour's contacts share no dynamic body, and
            // `with_pair` copies the others.
            for c in unsafe { self.contacts.slice(part) } {
                unsafe { self.bodies.with_pair(c.body_a, c.body_b, |a, b| f(c, a, b)) };
            }
        };
        self.each_stage(thread, solve);
    }

    /// The blocks of rows of the contacts (`StillBlock`), shared out in pieces, once the
    /// contacts are prepared; nothing if there are no blocks.
    pub fn fill_blocks(&self, thread: SolverThread) {
        self.each_block(thread, |block, contacts| block.fill(contacts));
    }

    /// The state the groups hold back into the contacts (`StillBlock::give_back_state`), each
    /// piece at a time, for the stages that read the contacts themselves.
    pub fn give_back_block_states(&self, thread: SolverThread) {
        self.each_block(thread, |block, contacts| block.give_back_state(contacts));
    }

    /// `ContactConstraint::update_steady_load` of every contact, in pieces: a group's
    /// in its block where the block holds their state (`StillBlock::update_steady_loads`, the
    /// same arithmetic in lanes), so the state stays there for the next substep's passes.
    pub fn update_steady_loads(&self, thread: SolverThread, steady_load_time: f64, h: f64) {
        if self.blocks.len == 0 {
            return self.contacts(thread, |c| c.update_steady_load(steady_load_time, h));
        }
        self.each_block(thread, |block, contacts| {
            if block.holds_state() {
                block.update_steady_loads(steady_load_time, h);
            } else {
                contacts.iter_mut().for_each(|c| c.update_steady_load(steady_load_time, h));
            }
        });
    }

    /// `f` on every block with its (up to four) contacts, shared out in pieces.
    fn each_block(&self, thread: SolverThread, f: impl Fn(&mut StillBlock, &mut [ContactConstraint])) {
        thread.stage(0..self.blocks.len, BLOCK_PIECE, |piece| {
            // SAFETY: a piece of the blocks this thread took, and their contacts, until the stage
            // ends.
            let (blocks, contacts) = unsafe {
                let first = piece.start * GROUP;
                let contacts = self.contacts.slice(first..(piece.end * GROUP).min(self.contacts.len));
                (self.blocks.slice(piece), contacts)
            };
            for (block, contacts) in blocks.iter_mut().zip(contacts.chunks_mut(GROUP)) {
                f(block, contacts);
            }
        });
    }

    /// As `contacts_with_bodies`, but where there are blocks (`fill_blocks`), the four
    /// constraints of a block that lies within one colour and a piece this thread took go to `group`
    /// (with the block and their bodies, `[a₀, b₀, a₁, b₁, …]`), which returns the bodies' new
    /// velocities, or `None` to have `f` take them one by one. The rest of a colour, and the
    /// overflow, go to `f`. `group` must give each constraint what `f` gives it alone.
    pub fn contacts_in_groups(
        &self,
        thread: SolverThread,
        f: impl Fn(&mut ContactConstraint, &mut SolverBody, &mut SolverBody),
        group: impl Fn(
            &mut [ContactConstraint],
            &mut StillBlock,
            &[&SolverBody; 2 * GROUP],
        ) -> Option<GroupVelocities>,
    ) {
        if self.blocks.len == 0 {
            return self.contacts_with_bodies(thread, f);
        }
        let solve = |piece: Range<usize>| {
            let mut start = piece.start;
            while start < piece.end {
                let colour_end = self.colouring.colour_end(start);
                let end = colour_end.map_or(piece.end, |end| end.min(piece.end));
                // SAFETY: as in `contacts_with_bodies`: a piece of one colour this thread took
                // (or a serial run, on this thread alone), until the stage ends.
                let part = unsafe { self.contacts.slice(start..end) };
                // The whole blocks within the colour, `first_block..end_block`, in groups; the
                // places before and after them one by one.
                let (first_block, end_block) = match colour_end {
                    Some(_) => (start.div_ceil(GROUP), end / GROUP),
                    None => (0, 0),
                };
                let alone_one = |c: &mut ContactConstraint| {
                    // SAFETY: as in `contacts_with_bodies`.
                    unsafe { self.bodies.with_pair(c.body_a, c.body_b, |a, b| f(c, a, b)) };
                };
                if first_block < end_block {
                    let (head, rest) = part.split_at_mut(first_block * GROUP - start);
                    let (grouped, tail) = rest.split_at_mut((end_block - first_block) * GROUP);
                    head.iter_mut().for_each(alone_one);
                    // SAFETY: this thread's blocks (those of its contacts) until the stage ends.
                    let blocks = unsafe { self.blocks.slice(first_block..end_block) };
                    for (contacts, block) in grouped.chunks_exact_mut(GROUP).zip(blocks.iter_mut()) {
                        // SAFETY: the constraints are of one colour, so their dynamic bodies are
                        // distinct and this thread's until the stage ends.
                        let took = unsafe {
                            let slots = std::array::from_fn(|j| {
                                let c = &contacts[j / 2];
                                if j % 2 == 0 {
                                    c.body_a
                                } else {
                                    c.body_b
                                }
                            });
                            self.bodies.with_group(slots, |bodies| group(contacts, block, bodies))
                        };
                        if !took {
                            contacts.iter_mut().for_each(alone_one);
                        }
                    }
                    tail.iter_mut().for_each(alone_one);
                } else {
                    part.iter_mut().for_each(alone_one);
                }
                start = end;
            }
        };
        self.each_stage(thread, solve);
    }

    /// `solve` on the colours' constraints in colour order, a stage at a time: a colour that is
    /// split between the threads in pieces (`SolverThread::stage`), a serial run (small colours,
    /// the overflow) in one piece, to whichever thread takes it.
    fn each_stage(&self, thread: SolverThread, mut solve: impl FnMut(Range<usize>)) {
        for (run, split) in self.colouring.stages() {
            let chunk = if *split { CONTACT_PIECE } else { run.end };
            thread.stage(run.clone(), chunk, &mut solve);
        }
    }

    /// `f` on one thread (whichever takes the stage's one piece) with the serial state, the
    /// joints' slots and all bodies; the others wait.
    pub fn serial(
        &self,
        thread: SolverThread,
        f: impl FnOnce(&mut S, &mut [Slot<Joint>], &mut [SolverBody]),
    ) {
        let mut f = Some(f);
        thread.stage(0..1, 1, |_| {
            let f = f.take().expect("a stage's piece is taken once");
            // SAFETY: the one thread that took the stage's one piece, until the stage ends.
            unsafe { f(&mut self.serial.all()[0], self.joints.all(), self.bodies.all()) };
        });
    }
}

/// The contact constraints in colour order, filled by the solver's threads from the contacts in
/// input order (each thread its share of the inputs, each input to its own slot).
pub(crate) struct ColouredContacts<'a> {
    contacts: Shared<'a, ContactConstraint>,
    colouring: &'a ContactColouring,
}

impl<'a> ColouredContacts<'a> {
    /// `contacts` must be as long as `colouring` has constraints.
    pub fn new(contacts: &'a mut [ContactConstraint], colouring: &'a ContactColouring) -> Self {
        ColouredContacts { contacts: Shared::new(contacts), colouring }
    }

    /// Asks for the place of the constraint of input `input` ahead of its writing (`prefetch.rs`);
    /// nothing is read.
    #[inline(always)]
    pub fn prefetch_slot(&self, input: usize) {
        if input < self.contacts.len {
            let slot = self.colouring.slot(input);
            crate::prefetch::prefetch_at(self.contacts.ptr.wrapping_add(slot).cast_const());
        }
    }

    /// Calls `f` on the place (in colour order) of the constraint of input `input`, which must be
    /// in `thread`'s share of the inputs.
    pub fn with_slot(&self, thread: SolverThread, input: usize, f: impl FnOnce(&mut ContactConstraint)) {
        assert!(thread.share(0..self.contacts.len).contains(&input), "input outside this thread's share");
        let slot = self.colouring.slot(input);
        // SAFETY: the shares of the threads are disjoint, and `slot` is a permutation, so no other
        // thread writes this slot (nor reads it until the threads have finished).
        f(unsafe { &mut self.contacts.slice(slot..slot + 1)[0] });
    }
}

/// A slice the step's threads share, each writing only elements no other thread touches until
/// the stage ends (or, in `StepThreads::for_each_chunk`, until the work is done).
pub(crate) struct Shared<'a, T> {
    ptr: *mut T,
    len: usize,
    _slice: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: access goes through the unsafe methods, whose contracts keep threads to distinct
// elements within a stage (and the stage's end orders the writes).
unsafe impl<T: Send> Send for Shared<'_, T> {}
unsafe impl<T: Send> Sync for Shared<'_, T> {}

impl<'a, T> Shared<'a, T> {
    pub(crate) fn new(slice: &'a mut [T]) -> Self {
        Shared { ptr: slice.as_mut_ptr(), len: slice.len(), _slice: std::marker::PhantomData }
    }

    /// The elements in `range`.
    ///
    /// # Safety
    /// No other thread may use them until the stage ends, and this thread holds no other
    /// reference to them.
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn slice(&self, range: Range<usize>) -> &mut [T] {
        assert!(range.start <= range.end && range.end <= self.len, "share out of bounds");
        // SAFETY: in bounds (checked); exclusive by the caller's contract.
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(range.start), range.len()) }
    }

    /// The whole slice.
    ///
    /// # Safety
    /// As for `slice`: no other thread uses any element until the stage ends.
    #[allow(clippy::mut_from_ref)]
    unsafe fn all(&self) -> &mut [T] {
        // SAFETY: the caller's contract.
        unsafe { self.slice(0..self.len) }
    }
}

impl Shared<'_, SolverBody> {
    /// Calls `f` with bodies `i` and `j`: a dynamic body in place, any other (static, kinematic,
    /// asleep: its impulses are all zero) as a private copy whose changes are dropped — many
    /// constraints of one colour may read it at once, and none may write it. The serial path
    /// works the same way, so both give the same numbers (and a non-finite impulse cannot reach
    /// the ground).
    ///
    /// # Safety
    /// No other thread may use a dynamic body `i` or `j` until the stage ends.
    unsafe fn with_pair<R>(
        &self,
        i: usize,
        j: usize,
        f: impl FnOnce(&mut SolverBody, &mut SolverBody) -> R,
    ) -> R {
        assert!(i < self.len && j < self.len && i != j, "a constraint needs two different bodies");
        // SAFETY: in bounds (checked above); `i != j`, so the references do not alias; a dynamic
        // body is this thread's alone (the caller's contract); a body that does not move is only
        // read, and no thread writes it.
        unsafe {
            let (pi, pj) = (self.ptr.add(i), self.ptr.add(j));
            let (mut copy_i, mut copy_j);
            let a = if (*pi).is_dynamic() {
                &mut *pi
            } else {
                copy_i = *pi;
                &mut copy_i
            };
            let b = if (*pj).is_dynamic() {
                &mut *pj
            } else {
                copy_j = *pj;
                &mut copy_j
            };
            f(a, b)
        }
    }
}

impl Shared<'_, SolverBody> {
    /// Calls `group` with the bodies at `slots` (four constraints' `[a₀, b₀, a₁, b₁, …]`) and,
    /// when it returns velocities, writes them into the dynamic ones (the others, which do not
    /// move, are only read). Returns whether `group` took the constraints.
    ///
    /// # Safety
    /// The dynamic bodies must be distinct, and no other thread may use them until
    /// the stage ends.
    unsafe fn with_group(
        &self,
        slots: [usize; 2 * GROUP],
        group: impl FnOnce(&[&SolverBody; 2 * GROUP]) -> Option<GroupVelocities>,
    ) -> bool {
        assert!(slots.iter().all(|&slot| slot < self.len), "body slot out of range");
        // SAFETY: in bounds (checked); only read here, and written below once these references
        // are no longer used.
        let bodies: [&SolverBody; 2 * GROUP] = std::array::from_fn(|j| unsafe { &*self.ptr.add(slots[j]) });
        let dynamic: [bool; 2 * GROUP] = std::array::from_fn(|j| bodies[j].is_dynamic());
        let Some(velocities) = group(&bodies) else { return false };
        for (j, &slot) in slots.iter().enumerate() {
            if dynamic[j] {
                // SAFETY: a dynamic body is this thread's alone (the caller's contract), and
                // appears once among the slots.
                let body = unsafe { &mut *self.ptr.add(slot) };
                (body.v, body.w) = velocities[j];
            }
        }
        true
    }
}

/// Runs `work` on every one of the step's `threads` (or on this thread alone), each with its
/// `SolverThread`.
pub(crate) fn run_on_threads(threads: Option<&StepThreads>, work: impl Fn(SolverThread) + Sync) {
    match threads {
        Some(threads) => threads.run(work),
        None => work(SolverThread::ALONE),
    }
}
