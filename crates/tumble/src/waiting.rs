//! How the step's threads wait for each other: spin, then yield the core, then sleep.
//!
//! Within a step the threads meet hundreds of times (at the end of every stage, every colour,
//! `dynamics/solver_threads.rs`), and most waits last microseconds: a sleeping thread took about
//! 75 µs to wake on the two-core virtual machine of the benchmarks, so a waiting thread spins
//! first, then yields its core between checks. But on a machine busy with other work a thread
//! the others wait for may have lost its core, and then spinning and yielding only keeps the core
//! from it: with one other busy process on two cores, the rain ran 2.4 times and the ragdolls 3.5
//! times slower on two threads than on one. So after [`WAIT_BEFORE_SLEEP`] a waiting thread
//! sleeps until the awaited thread wakes it, and the core is free for that thread. With the busy
//! process, two threads then ran the rain 2.4 times and the ragdolls 2.2 times as fast as before
//! (median of five alternating rounds), about as fast as one thread; on free cores the two builds
//! could not be told apart (1.00 and 1.02 over seven rounds).

use std::sync::atomic::{fence, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::{Duration, Instant};

/// Spins before a waiting thread starts yielding its core.
const SPINS_BEFORE_YIELD: u32 = 200;

/// How long a waiting thread spins and yields before it sleeps: longer than the waits of a step
/// on free cores (a stage's imbalance, a serial stage between the threaded ones), shorter than
/// the scheduler's time slice, for which a thread that lost its core waits.
pub(crate) const WAIT_BEFORE_SLEEP: Duration = Duration::from_micros(500);

/// A place where threads wait for a condition another thread makes true, and sleep if the wait
/// is long. The thread that makes it true calls [`Waiting::wake_all`] right after.
#[derive(Default)]
pub(crate) struct Waiting {
    /// Threads asleep or about to sleep.
    sleepers: AtomicUsize,
    lock: Mutex<()>,
    wake: Condvar,
}

impl Waiting {
    /// Returns once `done()` is true: spinning, then yielding the core, then (after
    /// [`WAIT_BEFORE_SLEEP`]) sleeping until a [`Waiting::wake_all`]. `done` must read what it
    /// checks with `Acquire` (or stronger), and turn true only by a write followed by `wake_all`.
    pub fn wait_until(&self, done: impl Fn() -> bool) {
        let mut spins = 0;
        let mut yielding_since = None;
        while !done() {
            if spins < SPINS_BEFORE_YIELD {
                spins += 1;
                std::hint::spin_loop();
                continue;
            }
            let since = *yielding_since.get_or_insert_with(Instant::now);
            if since.elapsed() < WAIT_BEFORE_SLEEP {
                std::thread::yield_now();
                continue;
            }
            self.sleep_until(&done);
            return;
        }
    }

    fn sleep_until(&self, done: &impl Fn() -> bool) {
        self.sleepers.fetch_add(1, Ordering::Relaxed);
        // With the fence in `wake_all`: either the waker sees this sleeper, or the check below
        // sees the waker's write (a store–load pair on each side, ordered by the two fences).
        fence(Ordering::SeqCst);
        let mut guard = self.lock.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        while !done() {
            guard = self.wake.wait(guard).unwrap_or_else(|poisoned| poisoned.into_inner());
        }
        drop(guard);
        self.sleepers.fetch_sub(1, Ordering::Relaxed);
    }

    /// Wakes every sleeping waiter; call it right after the write that makes their `done` true.
    /// Costs a fence and a load when none sleeps.
    pub fn wake_all(&self) {
        fence(Ordering::SeqCst);
        if self.sleepers.load(Ordering::Relaxed) > 0 {
            // Taking the lock orders the notification after any sleeper's last check of `done`
            // (made under the lock), so none misses it.
            drop(self.lock.lock().unwrap_or_else(|poisoned| poisoned.into_inner()));
            self.wake.notify_all();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;
    use std::sync::Arc;

    /// A waiter that outlasts the spinning and the yielding sleeps, and the write that ends its
    /// wait wakes it; many rounds, so a lost wake-up (a waiter asleep for good) would hang here.
    #[test]
    fn a_sleeping_waiter_is_woken_by_the_write_that_ends_its_wait() {
        for round in 0..40 {
            let waiting = Arc::new(Waiting::default());
            let flag = Arc::new(AtomicBool::new(false));
            let waiter = {
                let (waiting, flag) = (Arc::clone(&waiting), Arc::clone(&flag));
                std::thread::spawn(move || waiting.wait_until(|| flag.load(Ordering::Acquire)))
            };
            // Half the rounds end the wait after the waiter has gone to sleep, half around the
            // moment it does.
            let pause = if round % 2 == 0 { 3 * WAIT_BEFORE_SLEEP } else { WAIT_BEFORE_SLEEP };
            std::thread::sleep(pause);
            flag.store(true, Ordering::Release);
            waiting.wake_all();
            waiter.join().expect("the waiter returns");
        }
    }
}
