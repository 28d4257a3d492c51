//! The solver's threads: every one of the step's threads (step_threads.rs) runs the whole
//! substep loop, each doing its share of every stage, and they meet at a spinning barrier between
//! stages (as Box2D v3's solver does).
//!
//! A step has hundreds of stages (each colour of each pass of each substep, colouring.rs); handing
//! each to a thread pool would cost a wake-up per stage, more than a small stage's work. Here the
//! threads stay awake for the step and a stage boundary costs a barrier — a few hundred
//! nanoseconds.
//!
//! Shares never change a number: a body stage treats every body on its own, and a colour's
//! constraints share no moving body, and neither do two components of joints
//! (joint_components.rs), so which thread does what is invisible in the result. Stages that are
//! not split (joint trees, small colours, the overflow colour) run on the first thread while the
//! others wait.

#![allow(unsafe_code)] // `Shared`: threads write distinct elements between barriers.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use crate::dynamics::colouring::ContactColouring;
use crate::dynamics::contact_solver::{ContactConstraint, GroupVelocities, StillBlock, GROUP};
use crate::dynamics::joint::Joint;
use crate::dynamics::joint_components::JointComponents;
use crate::dynamics::solver_body::SolverBody;
use crate::dynamics::stage_shares::StageShares;
use crate::id::Slot;
use crate::step_threads::StepThreads;
use crate::waiting::Waiting;

/// The panic of a thread released from a barrier because another thread panicked.
pub(crate) const RELEASED: &str = "another solver thread panicked";

/// A barrier for a fixed number of threads that spins before it sleeps (waiting.rs), and the
/// threads' shares of the colour they work on between two waits (stage_shares.rs).
pub(crate) struct SpinBarrier {
    threads: usize,
    shares: StageShares,
    arrived: AtomicUsize,
    generation: AtomicUsize,
    /// Set when a thread panics, so the others stop waiting for it.
    poisoned: AtomicBool,
    waiting: Waiting,
}

impl SpinBarrier {
    pub fn new(threads: usize) -> Self {
        SpinBarrier {
            threads,
            shares: StageShares::new(threads),
            arrived: AtomicUsize::new(0),
            generation: AtomicUsize::new(0),
            poisoned: AtomicBool::new(false),
            waiting: Waiting::default(),
        }
    }

    /// Waits until every thread has arrived. Everything a thread wrote before it arrived is
    /// visible to every thread after the barrier. Panics if another thread panicked.
    pub fn wait(&self) {
        let generation = self.generation.load(Ordering::Acquire);
        if self.arrived.fetch_add(1, Ordering::AcqRel) + 1 == self.threads {
            self.arrived.store(0, Ordering::Relaxed);
            self.generation.fetch_add(1, Ordering::Release);
            self.waiting.wake_all();
            return;
        }
        self.waiting.wait_until(|| {
            self.generation.load(Ordering::Acquire) != generation || self.poisoned.load(Ordering::Acquire)
        });
        if self.generation.load(Ordering::Acquire) == generation {
            std::panic::panic_any(RELEASED);
        }
    }

    pub fn poison(&self) {
        self.poisoned.store(true, Ordering::Release);
        self.waiting.wake_all();
    }
}

/// The constraints a thread takes at a time of a colour split between the threads
/// (stage_shares.rs): eight groups of four (contact_lanes.rs), so a piece cuts no group apart;
/// a few microseconds of work, against some tens of nanoseconds to take it.
const STAGE_CHUNK: usize = 8 * GROUP;

/// One thread's place among the solver's threads.
#[derive(Clone, Copy)]
pub(crate) struct SolverThread<'a> {
    // Private: the shares' disjointness, which the unsafe accesses rest on, comes from each
    // thread having its own index.
    index: usize,
    count: usize,
    /// `None` when there is one thread.
    barrier: Option<&'a SpinBarrier>,
}

impl<'a> SolverThread<'a> {
    /// The only thread.
    pub const ALONE: SolverThread<'static> = SolverThread { index: 0, count: 1, barrier: None };

    pub fn new(index: usize, barrier: &'a SpinBarrier) -> Self {
        SolverThread { index, count: barrier.threads, barrier: Some(barrier) }
    }

    /// The thread that runs the stages that are not split.
    pub fn is_first(&self) -> bool {
        self.index == 0
    }

    /// Waits for the other threads at the end of a stage.
    pub fn sync(&self) {
        if let Some(barrier) = self.barrier {
            barrier.wait();
        }
    }

    /// Calls `f` on the pieces of `range` (cut at multiples of `chunk`) this thread takes of a
    /// shared stage: its own share first, then what is left of the others' (stage_shares.rs).
    /// Every thread must call it for the stage, and the stage end at a barrier.
    pub fn take_chunks(&self, range: Range<usize>, chunk: usize, f: impl FnMut(Range<usize>)) {
        match self.barrier {
            Some(barrier) => barrier.shares.take_chunks(self.index, range, chunk, f),
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

/// What the substeps work on, shared by the solver's threads. Every stage method ends at a
/// barrier, and between barriers each thread writes only its share (of the bodies, of the
/// contacts, or of a colour's contacts, which share no dynamic body) or — the first thread alone —
/// everything; that is what makes the accesses below sound.
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

    /// `f` on every solved joint with its two bodies, each thread its share of the joints'
    /// components (joint_components.rs); a body that is not dynamic as a private copy, as for
    /// the contacts.
    pub fn joints_with_bodies(
        &self,
        thread: SolverThread,
        f: impl Fn(&mut Joint, &mut SolverBody, &mut SolverBody),
    ) {
        for &slot in self.joint_components.share(thread) {
            // SAFETY: each joint slot appears once in the components, and this thread's share of
            // them is its own until the barrier.
            let joint = unsafe { &mut self.joints.slice(slot as usize..slot as usize + 1)[0] };
            let joint = joint.value_mut().expect("solved joints are live");
            // SAFETY: the dynamic bodies of a component are its own (no other component's joint
            // has one), so this thread's until the barrier; `with_pair` copies the others.
            unsafe {
                self.bodies.with_pair(joint.body_a.index(), joint.body_b.index(), |a, b| f(joint, a, b))
            };
        }
        thread.sync();
    }

    /// `f` on every constrained body, each thread its share.
    pub fn bodies(&self, thread: SolverThread, f: impl Fn(&mut SolverBody)) {
        self.each_body(thread, self.constrained, f);
    }

    /// `f` on the unconstrained bodies in groups of up to `N` (in slot order; the last group's
    /// missing bodies are `None`), each thread its share.
    pub fn unconstrained_bodies<const N: usize>(
        &self,
        thread: SolverThread,
        f: impl Fn(&mut [Option<&mut SolverBody>; N]),
    ) {
        let slots = self.unconstrained;
        for group in slots[thread.share(0..slots.len())].chunks(N) {
            let mut bodies = std::array::from_fn(|k| {
                // SAFETY: the slots are distinct (checked in `new`) and in range, and this
                // thread's share of them is its own until the barrier.
                group
                    .get(k)
                    .map(|&slot| unsafe { &mut self.bodies.slice(slot as usize..slot as usize + 1)[0] })
            });
            f(&mut bodies);
        }
        thread.sync();
    }

    fn each_body(&self, thread: SolverThread, slots: &[u32], f: impl Fn(&mut SolverBody)) {
        for &slot in &slots[thread.share(0..slots.len())] {
            // SAFETY: the slots are distinct (checked in `new`) and in range, and this thread's
            // share of them is its own until the barrier.
            f(unsafe { &mut self.bodies.slice(slot as usize..slot as usize + 1)[0] });
        }
        thread.sync();
    }

    /// `f` on every contact on its own (no bodies), each thread its share.
    pub fn contacts(&self, thread: SolverThread, f: impl Fn(&mut ContactConstraint)) {
        // SAFETY: this thread's share, until the barrier.
        unsafe { self.contacts.slice(thread.share(0..self.contacts.len)) }.iter_mut().for_each(f);
        thread.sync();
    }

    /// `f` on every contact with its two bodies, colour by colour (colouring.rs): a large colour
    /// shared between the threads in pieces (`each_stage`), small ones and the overflow on the
    /// first thread.
    pub fn contacts_with_bodies(
        &self,
        thread: SolverThread,
        f: impl Fn(&mut ContactConstraint, &mut SolverBody, &mut SolverBody),
    ) {
        let solve = |part: Range<usize>| {
            // SAFETY: a piece of one colour this thread took (or a serial run on the first thread
            // alone), until the barrier; a colour's contacts share no dynamic body, and
            // `with_pair` copies the others.
            for c in unsafe { self.contacts.slice(part) } {
                unsafe { self.bodies.with_pair(c.body_a, c.body_b, |a, b| f(c, a, b)) };
            }
        };
        self.each_stage(thread, solve);
    }

    /// The blocks of rows of the contacts (`StillBlock`), each thread its share, once the
    /// contacts are prepared; nothing if there are no blocks.
    pub fn fill_blocks(&self, thread: SolverThread) {
        self.each_block(thread, |block, contacts| block.fill(contacts));
    }

    /// The state the groups hold back into the contacts (`StillBlock::give_back_state`), each
    /// thread its share, for the stages that read the contacts themselves.
    pub fn give_back_block_states(&self, thread: SolverThread) {
        self.each_block(thread, |block, contacts| block.give_back_state(contacts));
    }

    /// `ContactConstraint::update_steady_load` of every contact, each thread its share: a group's
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

    /// `f` on every block with its (up to four) contacts, each thread its share.
    fn each_block(&self, thread: SolverThread, f: impl Fn(&mut StillBlock, &mut [ContactConstraint])) {
        if self.blocks.len == 0 {
            return;
        }
        let mine = thread.share(0..self.blocks.len);
        // SAFETY: this thread's share of the blocks and of their contacts, until the barrier.
        let (blocks, contacts) = unsafe {
            let first = mine.start * GROUP;
            let contacts = self.contacts.slice(first..(mine.end * GROUP).min(self.contacts.len));
            (self.blocks.slice(mine), contacts)
        };
        for (block, contacts) in blocks.iter_mut().zip(contacts.chunks_mut(GROUP)) {
            f(block, contacts);
        }
        thread.sync();
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
                // (or a serial run on the first thread alone), until the barrier.
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
                    // SAFETY: this thread's blocks (those of its contacts) until the barrier.
                    let blocks = unsafe { self.blocks.slice(first_block..end_block) };
                    for (contacts, block) in grouped.chunks_exact_mut(GROUP).zip(blocks.iter_mut()) {
                        // SAFETY: the constraints are of one colour, so their dynamic bodies are
                        // distinct and this thread's until the barrier.
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

    /// `solve` on the colours' constraints in colour order, a stage at a time: the pieces this
    /// thread takes of a colour that is split between the threads (`SolverThread::take_chunks`),
    /// a serial run on the first thread alone; each stage ends at a barrier.
    fn each_stage(&self, thread: SolverThread, mut solve: impl FnMut(Range<usize>)) {
        for (run, split) in self.colouring.stages() {
            match (split, thread.is_first()) {
                (true, _) => thread.take_chunks(run.clone(), STAGE_CHUNK, &mut solve),
                (false, true) => solve(run.clone()),
                (false, false) => {}
            }
            thread.sync();
        }
    }

    /// `f` on the first thread with the serial state, the joints' slots and all bodies; the
    /// others wait.
    pub fn serial(
        &self,
        thread: SolverThread,
        f: impl FnOnce(&mut S, &mut [Slot<Joint>], &mut [SolverBody]),
    ) {
        if thread.is_first() {
            // SAFETY: the first thread alone, until the barrier.
            unsafe { f(&mut self.serial.all()[0], self.joints.all(), self.bodies.all()) };
        }
        thread.sync();
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
/// the next barrier (or, in `StepThreads::for_each_chunk`, until the work is done).
pub(crate) struct Shared<'a, T> {
    ptr: *mut T,
    len: usize,
    _slice: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: access goes through the unsafe methods, whose contracts keep threads to distinct
// elements between barriers (and the barrier orders the writes).
unsafe impl<T: Send> Send for Shared<'_, T> {}
unsafe impl<T: Send> Sync for Shared<'_, T> {}

impl<'a, T> Shared<'a, T> {
    pub(crate) fn new(slice: &'a mut [T]) -> Self {
        Shared { ptr: slice.as_mut_ptr(), len: slice.len(), _slice: std::marker::PhantomData }
    }

    /// The elements in `range`.
    ///
    /// # Safety
    /// No other thread may use them until the next barrier, and this thread holds no other
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
    /// As for `slice`: no other thread uses any element until the next barrier.
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
    /// No other thread may use a dynamic body `i` or `j` until the next barrier.
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
    /// the next barrier.
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
