//! The world's threads for the length of one step.
//!
//! A step hands work to its threads four times (the narrow phase, the solver's gather, its
//! contact preparation and its substeps), with serial work in between. Each hand-over through
//! the thread pool itself woke sleeping threads: on a two-core virtual machine a sleeping thread
//! took about 75 µs to start, and the calling thread as long to notice the end — about 150 µs a
//! hand-over, with the proxies' update then also threaded 0.75 ms of a 7 ms step of the rain
//! scene.
//!
//! So a step takes the pool's threads once, at its start ([`StepThreads::begin`]): they then wait
//! for work by spinning (yielding their core between checks after a while, and sleeping only
//! after half a millisecond: waiting.rs) instead of going back to sleep in the pool,
//! and the step's own thread posts each piece of work to them ([`StepThreads::run`]) and does its
//! share as thread 0. The threads wake while the step's first serial stages run, and are let go
//! when the step ends (on drop). Every piece of work is finished by all threads before `run`
//! returns, so a piece may borrow from the step.
//!
//! Which thread does what never changes a number: the work handed out is split by the scene
//! (chunks of contacts, shares of bodies, a colour's constraints), never merged in thread order.

#![allow(unsafe_code)] // The posted work is borrowed across threads; see `run`.

use std::any::Any;
use std::cell::UnsafeCell;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use crate::dynamics::solver_threads::{Shared, SolverThread, ThreadStages, RELEASED};
use crate::waiting::Waiting;

/// A piece of work for every thread: called once on each, with its place among them.
type Work<'a> = dyn Fn(SolverThread) + Sync + 'a;

/// What the step's thread and the pool's threads share.
struct Control {
    threads: usize,
    /// Pieces of work posted so far (a thread runs piece `k` once it sees `posted ≥ k`).
    posted: AtomicUsize,
    /// The last piece posted. Written only while no thread runs a piece (see `run`).
    work: UnsafeCell<Option<*const Work<'static>>>,
    /// Pieces finished, summed over the pool's threads.
    finished: AtomicUsize,
    /// Set when the step ends: the pool's threads go back to the pool.
    closing: AtomicBool,
    /// The stages of the work the threads run (solver_threads.rs).
    stages: ThreadStages,
    /// Where the threads wait for `posted`, `finished` and `closing` (woken by each change).
    waiting: Waiting,
    /// The first panic of a pool thread, to pass on from `run`.
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

// SAFETY: `work` is written by the step's thread only while the pool's threads wait for the next
// piece (all have finished the last: `run` waits for that), and read by them only after the
// `posted` increment that follows the write (release/acquire); everything else is atomic or
// locked.
unsafe impl Sync for Control {}
unsafe impl Send for Control {}

/// The pool's threads, taken for one step.
pub(crate) struct StepThreads {
    control: Arc<Control>,
}

impl StepThreads {
    /// Takes all of `pool`'s threads for a step: they wait for work beside the calling thread,
    /// which makes one thread more than the pool has.
    pub fn begin(pool: &rayon::ThreadPool) -> StepThreads {
        let threads = pool.current_num_threads() + 1;
        let control = Arc::new(Control {
            threads,
            posted: AtomicUsize::new(0),
            work: UnsafeCell::new(None),
            finished: AtomicUsize::new(0),
            closing: AtomicBool::new(false),
            stages: ThreadStages::new(threads),
            waiting: Waiting::default(),
            panic: Mutex::new(None),
        });
        for index in 1..threads {
            let control = Arc::clone(&control);
            pool.spawn(move || serve(&control, index));
        }
        StepThreads { control }
    }

    /// Runs `work` on every thread, the calling thread as thread 0, and returns when all have
    /// finished it. A panic on any thread releases the others from their stages and is passed
    /// on once all have stopped.
    pub fn run(&self, work: impl Fn(SolverThread) + Sync) {
        let control = &*self.control;
        let borrowed: &Work<'_> = &work;
        // SAFETY: only the lifetime is erased. The pool's threads call the work only between
        // the `posted` increment below and their `finished` increment, and this function does
        // not return (nor unwind) before every one of them has finished: `work` outlives every
        // use. No thread reads `work` now (all finished the last piece before the last `run`
        // returned), so the write does not race.
        unsafe {
            let erased: *const Work<'static> = std::mem::transmute(borrowed as *const Work<'_>);
            *control.work.get() = Some(erased);
        }
        let number = control.posted.fetch_add(1, Ordering::Release) + 1;
        control.waiting.wake_all();
        let own = catch_unwind(AssertUnwindSafe(|| work(SolverThread::new(0, &control.stages))));
        if own.is_err() {
            control.stages.poison();
        }
        control
            .waiting
            .wait_until(|| control.finished.load(Ordering::Acquire) >= number * (control.threads - 1));
        let theirs = control.panic.lock().map(|mut p| p.take()).unwrap_or(None);
        // Pass on the panic that caused the others (they only stopped waiting for it).
        match (own, theirs) {
            (Err(mine), Some(other)) if mine.downcast_ref::<&str>() == Some(&RELEASED) => {
                resume_unwind(other)
            }
            (Err(mine), _) => resume_unwind(mine),
            (Ok(()), Some(other)) => resume_unwind(other),
            (Ok(()), None) => {}
        }
    }

    /// Runs `f` on chunks of `chunk` items of `a` and the matching items of `b` (as long as
    /// `a`), each chunk on whichever thread claims it next: the chunks differ in cost, and a
    /// thread that is done with cheap ones takes more. With the chunk's offset in `a`.
    pub fn for_each_chunk<A: Send, B: Send>(
        &self,
        (a, b): (&mut [A], &mut [B]),
        chunk: usize,
        f: impl Fn(usize, &mut [A], &mut [B]) + Sync,
    ) {
        assert_eq!(a.len(), b.len(), "chunks of two slices of one length");
        let chunk = chunk.max(1);
        let len = a.len();
        let (a, b) = (Shared::new(a), Shared::new(b));
        let next = AtomicUsize::new(0);
        self.run(|_| loop {
            let start = next.fetch_add(1, Ordering::Relaxed) * chunk;
            if start >= len {
                break;
            }
            let range = start..(start + chunk).min(len);
            // SAFETY: each chunk is claimed once (the counter), so no two threads touch the same
            // items, and `run` returns only after every thread has stopped.
            let (part_a, part_b) = unsafe { (a.slice(range.clone()), b.slice(range)) };
            f(start, part_a, part_b);
        });
    }
}

/// `f(offset, part)` over `items` in chunks of `chunk` on `threads` (see
/// [`StepThreads::for_each_chunk`]), or over all of them at once on this thread when there are
/// none. `f` must treat each item on its own, so that the split changes no number.
pub(crate) fn for_each_chunk_of<T: Send>(
    threads: Option<&StepThreads>,
    items: &mut [T],
    chunk: usize,
    f: impl Fn(usize, &mut [T]) + Sync,
) {
    match threads {
        Some(threads) => {
            // A second slice of units: `for_each_chunk` pairs each item with one (they take no room).
            let mut units = vec![(); items.len()];
            threads.for_each_chunk((items, &mut units), chunk, |offset, part, _| f(offset, part));
        }
        None => f(0, items),
    }
}

/// New items written per chunk by [`extend_on_threads`] (some hundred kilobytes of contacts or
/// constraints).
const GROW_CHUNK: usize = 256;

/// Appends `make(source)` for each of `sources` to `items`, in order, writing the new places on
/// `threads` when there are many. The first step of a pile of some thousand boxes makes some ten
/// thousand contacts and the solver's arrays for them: tens of megabytes, and each new page faults
/// when first written. On one thread those were the longest serial stretches of large_pyramid's
/// first step on two threads (its set-up 33 ms, of them about 12 writing the arrays; 12-15 ms
/// making the contacts).
pub(crate) fn extend_on_threads<T: Send, S: Sync>(
    items: &mut Vec<T>,
    sources: &[S],
    make: impl Fn(&S) -> T + Sync,
    threads: Option<&StepThreads>,
) {
    let (old, added) = (items.len(), sources.len());
    let Some(threads) = threads.filter(|_| added >= 4 * GROW_CHUNK) else {
        items.extend(sources.iter().map(make));
        return;
    };
    items.reserve(added);
    let new_places = &mut items.spare_capacity_mut()[..added];
    for_each_chunk_of(Some(threads), new_places, GROW_CHUNK, |offset, part| {
        for (place, source) in part.iter_mut().zip(&sources[offset..]) {
            place.write(make(source));
        }
    });
    // SAFETY: `reserve` made room for `old + added` items, and every place in `old..old + added`
    // was written above: `for_each_chunk_of` hands each one to exactly one call and returns when
    // all are done. (A panic in `make` propagates from it before this line: the length stays as
    // it was, and what was written is leaked, never read.)
    unsafe { items.set_len(old + added) };
}

/// `Vec::resize` of `items` to `len` with copies of `value`, the new places written on `threads`
/// when there are many (`extend_on_threads`).
pub(crate) fn resize_on_threads<T: Clone + Send + Sync>(
    items: &mut Vec<T>,
    len: usize,
    value: T,
    threads: Option<&StepThreads>,
) {
    if len <= items.len() {
        items.truncate(len);
        return;
    }
    let places = vec![(); len - items.len()];
    extend_on_threads(items, &places, |_| value.clone(), threads);
}

impl Drop for StepThreads {
    fn drop(&mut self) {
        self.control.closing.store(true, Ordering::Release);
        self.control.waiting.wake_all();
    }
}

/// A pool thread's part: run each piece of work as it is posted, until the step ends.
fn serve(control: &Control, index: usize) {
    let mut done = 0;
    loop {
        control.waiting.wait_until(|| {
            control.posted.load(Ordering::Acquire) != done || control.closing.load(Ordering::Acquire)
        });
        if control.posted.load(Ordering::Acquire) == done {
            return; // closing
        }
        done += 1;
        // SAFETY: see `run`: the piece is alive and not rewritten until this thread has
        // counted itself finished.
        let work = unsafe { &*(*control.work.get()).expect("work is posted before it is counted") };
        if let Err(panic) = catch_unwind(AssertUnwindSafe(|| work(SolverThread::new(index, &control.stages))))
        {
            control.stages.poison();
            if panic.downcast_ref::<&str>() != Some(&RELEASED) {
                if let Ok(mut first) = control.panic.lock() {
                    first.get_or_insert(panic);
                }
            }
        }
        control.finished.fetch_add(1, Ordering::Release);
        control.waiting.wake_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool")
    }

    #[test]
    fn every_chunk_is_done_once_whatever_the_threads() {
        let pool = pool(2);
        let threads = StepThreads::begin(&pool);
        for round in 0..50 {
            let mut items: Vec<usize> = vec![0; 1000 + round];
            let mut marks = vec![0u32; items.len()];
            threads.for_each_chunk((&mut items, &mut marks), 7, |offset, part, marks| {
                for (i, (item, mark)) in part.iter_mut().zip(marks).enumerate() {
                    *item = offset + i;
                    *mark += 1;
                }
            });
            assert!(items.iter().enumerate().all(|(i, &v)| v == i));
            assert!(marks.iter().all(|&m| m == 1));
        }
    }

    /// Grown on threads, a vector holds what it holds grown on one: the old items, then the new
    /// ones in order (shrinking, growing by a few, and growing by many, from empty and not).
    #[test]
    fn growing_on_threads_gives_what_growing_on_one_gives() {
        let pool = pool(2);
        let threads = StepThreads::begin(&pool);
        let (mut alone, mut shared): (Vec<u64>, Vec<u64>) = (Vec::new(), Vec::new());
        for (round, len) in [5000, 3, 40, 7000, 6999, 20000].into_iter().enumerate() {
            alone.resize(len, round as u64);
            resize_on_threads(&mut shared, len, round as u64, Some(&threads));
            assert_eq!(alone, shared, "resize to {len}");
            let sources: Vec<u64> = (0..len as u64 / 3).collect();
            alone.extend(sources.iter().map(|s| s * 7 + 1));
            extend_on_threads(&mut shared, &sources, |s| s * 7 + 1, Some(&threads));
            assert_eq!(alone, shared, "extend by {}", sources.len());
        }
    }

    #[test]
    fn a_stage_ends_when_every_piece_is_done_and_the_pieces_cover_the_range() {
        let pool = pool(1);
        let threads = StepThreads::begin(&pool);
        let counts: Vec<AtomicUsize> = (0..100).map(|_| AtomicUsize::new(0)).collect();
        let done = AtomicUsize::new(0);
        threads.run(|thread| {
            thread.stage(3..100, 8, |piece| {
                for i in piece {
                    counts[i].fetch_add(1, Ordering::Relaxed);
                    done.fetch_add(1, Ordering::Relaxed);
                }
            });
            // Every thread sees every piece of the stage done.
            assert_eq!(done.load(Ordering::Relaxed), 97);
        });
        assert!(counts[..3].iter().all(|c| c.load(Ordering::Relaxed) == 0));
        assert!(counts[3..].iter().all(|c| c.load(Ordering::Relaxed) == 1));
    }

    #[test]
    fn a_panic_in_a_stage_is_passed_on_and_the_next_step_works() {
        let pool = pool(1);
        let result = catch_unwind(AssertUnwindSafe(|| {
            let threads = StepThreads::begin(&pool);
            threads.run(|thread| {
                // Whichever thread takes the second piece fails; the other waits for the stage.
                thread.stage(0..2, 1, |piece| {
                    if piece.start == 1 {
                        panic!("a piece fails");
                    }
                });
                thread.stage(0..2, 1, |_| {});
            });
        }));
        let payload = result.expect_err("the panic is passed on");
        assert_eq!(payload.downcast_ref::<&str>(), Some(&"a piece fails"));
        let threads = StepThreads::begin(&pool);
        let sum = AtomicUsize::new(0);
        threads.run(|thread| {
            sum.fetch_add(thread.share(0..10).len(), Ordering::Relaxed);
        });
        assert_eq!(sum.load(Ordering::Relaxed), 10);
    }
}
