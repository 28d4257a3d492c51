//! How the solver's threads share a stage's work, and know when the stage is done, so that no
//! thread waits long for another — not for one with more work, nor for one whose core the machine
//! has taken away for a while.
//!
//! A stage's items (a colour's constraints, the bodies, the blocks, the joints' components) are
//! cut into pieces at the multiples of a chunk. Each thread has a contiguous share of the pieces
//! and works through it from the front; a thread that has finished its own takes pieces from the
//! back of the others' shares until none is left. The stage is done when its last piece is done,
//! whoever did it; the thread that finishes it says so, and the threads go on to the next stage.
//! A thread need not arrive anywhere: one that lost its core before it took a piece holds nothing
//! up, and when it runs again it finds the stages it missed done and catches up.
//!
//! Equal counts are not equal work. A still manifold in a group of four costs a fraction of one
//! solved alone (contact_lanes.rs), and whether a group goes together is only known when it is
//! solved; a colour ordered by body (colouring.rs) has the settled base of a pyramid in one share
//! and its moving top in the other. Split by count and closed by a barrier that every thread had
//! to reach, the threads of the 5,050-box pyramid waited for a fifth of the substeps' time, most
//! of it in waits of 0.1–0.5 ms. And on a virtual machine whose host gave a third of the CPU time
//! to other guests, the rain ran seven times slower on two threads than at ease: at hundreds of
//! barriers a step, whenever either core was taken the other soon waited for it.
//!
//! Which thread does which piece changes no number: the items of a stage are independent (a
//! colour's constraints share no moving body). A thread still works its own share first, from the
//! front, so it keeps the bodies it worked on in the last colour (the reason for the order by
//! body); the pieces it takes from another share are that share's last, next to its own. A share
//! whose thread has not begun it is left alone for a moment first (`PATIENCE`): a stage of one
//! piece — the joint trees, a run of small colours — then stays on the first thread, whose cache
//! holds its data, unless that thread is away; a thread found away once is not waited for again
//! until it begins a stage itself (else each of the step's hundreds of stages would wait).
//!
//! Every word below carries the number of the stage it belongs to. The first thread to begin
//! stage `k` writes its words (the same values whoever writes them: stage `k − 1` is done by
//! then, so no piece of it is left); a thread that reads a word of another stage leaves it alone.
//! The threads number the stages alike, as they all go through the same stages in order.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// How long a thread that has finished its own share leaves another share whose thread has not
/// begun it: longer than the threads take to pass from one stage to the next, or to wake from a
/// short sleep (about 75 µs on a 2-core virtual machine, waiting.rs), far shorter than a core lost
/// to another process or guest (milliseconds).
const PATIENCE: Duration = Duration::from_micros(100);

/// Pieces in a share's word (front and back, 16 bits each): a stage with more has larger pieces.
const MAX_PIECES: usize = u16::MAX as usize;

/// One thread's share of the current stage, on its own cache line (its thread takes from it at
/// every piece, the others only once they have finished their own).
#[repr(align(128))]
#[derive(Default)]
struct Share {
    /// `stage << 32 | front << 16 | back`: pieces `front..back` of stage `stage` are left.
    word: AtomicU64,
    /// The number of stages this share's thread has begun (written by it alone).
    stages_begun: AtomicU32,
    /// Another thread found this share untouched after `PATIENCE` and took it: its thread is
    /// away (its core taken), and its next shares are taken without waiting, until it is back.
    away: AtomicBool,
}

/// The pieces done of the current stage, and the last stage done, on their own cache line.
#[repr(align(128))]
#[derive(Default)]
struct Progress {
    /// `stage << 32 | pieces done`.
    done: AtomicU64,
    /// The number of the last stage done.
    finished: AtomicU32,
}

/// The solver's threads' shares of their stages, one per thread, and the stages' progress.
pub(crate) struct StageShares {
    shares: Box<[Share]>,
    progress: Progress,
}

/// How a thread leaves a stage (`StageShares::take_pieces`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Left {
    /// It did the stage's last piece: the stage is done, and the threads waiting for it are to be
    /// woken.
    Finished,
    /// The stage, numbered so, is done once `is_done` says so: other threads still have pieces.
    Waiting(u32),
    /// The stage was done, or had nothing to do.
    Done,
}

fn pack(stage: u32, low: u32) -> u64 {
    u64::from(stage) << 32 | u64::from(low)
}

fn share_word(stage: u32, pieces: Range<usize>) -> u64 {
    pack(stage, (pieces.start as u32) << 16 | pieces.end as u32)
}

fn stage_of(word: u64) -> u32 {
    (word >> 32) as u32
}

fn pieces_of(word: u64) -> Range<u32> {
    (word as u32 >> 16)..(word as u32 & 0xffff)
}

/// Stage `a` comes before stage `b` (the numbers wrap).
fn before(a: u32, b: u32) -> bool {
    (b.wrapping_sub(a) as i32) > 0
}

/// Which end of a share a thread takes its next piece from.
#[derive(Clone, Copy)]
enum End {
    Front,
    Back,
}

impl StageShares {
    pub fn new(threads: usize) -> Self {
        StageShares {
            shares: (0..threads).map(|_| Share::default()).collect(),
            progress: Progress::default(),
        }
    }

    /// Calls `f` on the pieces of `range` (cut at multiples of `chunk`, or of a multiple of it
    /// when there would be too many pieces) that this thread (`index`) takes, and says how it
    /// leaves the stage. Every thread must call it for every stage, in the same order, with the
    /// same `range` and `chunk`; each piece then goes to exactly one thread, and a stage's pieces
    /// are all done before any piece of the next begins.
    pub fn take_pieces(
        &self,
        index: usize,
        range: Range<usize>,
        chunk: usize,
        mut f: impl FnMut(Range<usize>),
    ) -> Left {
        if range.is_empty() {
            return Left::Done; // not a stage: every thread skips it alike
        }
        let mut chunk = chunk.max(1);
        if range.len().div_ceil(chunk) >= MAX_PIECES {
            chunk *= range.len().div_ceil(chunk * (MAX_PIECES - 1)) + 1;
        }
        let first = range.start / chunk;
        let count = range.end.div_ceil(chunk) - first;
        let piece = |k: u32| {
            let k = first + k as usize;
            (k * chunk).max(range.start)..((k + 1) * chunk).min(range.end)
        };
        let threads = self.shares.len();
        // The first threads' shares take the odd pieces: a stage of one piece is the first
        // thread's, as the serial work around the solve is.
        let own = |i: usize| (count * i).div_ceil(threads)..(count * (i + 1)).div_ceil(threads);

        let share = &self.shares[index];
        let stage = share.stages_begun.load(Ordering::Relaxed).wrapping_add(1);
        share.stages_begun.store(stage, Ordering::Relaxed);
        if self.is_done(stage) {
            return Left::Done;
        }
        share.away.store(false, Ordering::Relaxed);
        // Begin the stage's words, unless a thread has begun them (or the stage is done and
        // the words have moved on). The count of pieces done first: a piece is taken only after.
        Self::begin(&self.progress.done, stage, pack(stage, 0));
        for (i, other) in self.shares.iter().enumerate() {
            Self::begin(&other.word, stage, share_word(stage, own(i)));
        }

        let mut done_here = 0;
        let mut run = |k: u32| {
            f(piece(k));
            done_here += 1;
        };
        while let Some(k) = Self::take(share, stage, End::Front) {
            run(k);
        }
        for other in (1..threads).map(|step| (index + step) % threads) {
            let theirs = &self.shares[other];
            let untouched = own(other).start as u32;
            let mut since = None;
            loop {
                let word = theirs.word.load(Ordering::Acquire);
                let left = pieces_of(word);
                if stage_of(word) != stage || left.is_empty() {
                    break;
                }
                // A share whose thread has not begun it yet is left to it for a moment: the
                // data of its pieces is likely in that thread's cache (a stage of one piece, the
                // joint trees, is the same thread's every time).
                if left.start == untouched && !theirs.away.load(Ordering::Relaxed) {
                    if since.get_or_insert_with(Instant::now).elapsed() < PATIENCE {
                        std::hint::spin_loop();
                        continue;
                    }
                    theirs.away.store(true, Ordering::Relaxed);
                }
                match Self::take(theirs, stage, End::Back) {
                    Some(k) => run(k),
                    None => break,
                }
            }
        }
        if done_here == 0 {
            return Left::Waiting(stage);
        }
        // Count this thread's pieces at once: the stage is done when the count reaches them all.
        let before_here = self.progress.done.fetch_add(done_here, Ordering::AcqRel);
        debug_assert_eq!(stage_of(before_here), stage, "a piece counted in another stage");
        if (before_here as u32) as u64 + done_here == count as u64 {
            self.progress.finished.store(stage, Ordering::Release);
            Left::Finished
        } else {
            Left::Waiting(stage)
        }
    }

    /// Whether stage `stage` is done.
    pub fn is_done(&self, stage: u32) -> bool {
        !before(self.progress.finished.load(Ordering::Acquire), stage)
    }

    /// Writes `value` (of stage `stage`) into `word` if the word is of an earlier stage.
    fn begin(word: &AtomicU64, stage: u32, value: u64) {
        let mut now = word.load(Ordering::Acquire);
        while before(stage_of(now), stage) {
            match word.compare_exchange_weak(now, value, Ordering::AcqRel, Ordering::Acquire) {
                Ok(_) => return,
                Err(seen) => now = seen,
            }
        }
    }

    /// Takes the piece at `end` of `share` if the share is of `stage` and has one left.
    fn take(share: &Share, stage: u32, end: End) -> Option<u32> {
        let mut word = share.word.load(Ordering::Acquire);
        loop {
            let left = pieces_of(word);
            if stage_of(word) != stage || left.is_empty() {
                return None;
            }
            let (taken, rest) = match end {
                End::Front => (left.start, left.start + 1..left.end),
                End::Back => (left.end - 1, left.start..left.end - 1),
            };
            let rest = rest.start as usize..rest.end as usize;
            match share.word.compare_exchange_weak(
                word,
                share_word(stage, rest),
                Ordering::AcqRel,
                Ordering::Acquire,
            ) {
                Ok(_) => return Some(taken),
                Err(now) => word = now,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Barrier;

    /// `range` cut at the multiples of `chunk`.
    fn pieces(range: Range<usize>, chunk: usize) -> Vec<Range<usize>> {
        let mut expected = Vec::new();
        let mut start = range.start;
        while start < range.end {
            let end = ((start / chunk + 1) * chunk).min(range.end);
            expected.push(start..end);
            start = end;
        }
        expected
    }

    /// Threads that wait for each stage's end as the solver's do (`Left`): every piece of every
    /// stage goes to exactly one thread, whatever the timing, and no piece of a stage is taken
    /// before the stage before it is done.
    #[test]
    fn every_piece_goes_to_exactly_one_thread_and_stages_end_in_order() {
        for threads in 1..=4 {
            let shares = StageShares::new(threads);
            let stages = [3..1_000, 0..64, 17..18, 1..129, 100..10_000];
            let done = AtomicU32::new(0);
            let taken: Vec<Vec<Vec<Range<usize>>>> = std::thread::scope(|scope| {
                let workers: Vec<_> = (0..threads)
                    .map(|index| {
                        let (shares, stages, done) = (&shares, &stages, &done);
                        scope.spawn(move || {
                            let mut mine = Vec::new();
                            for (s, range) in stages.iter().cycle().take(60).enumerate() {
                                let mut pieces = Vec::new();
                                let left = shares.take_pieces(index, range.clone(), 16, |piece| {
                                    // Every piece of the stages before is done.
                                    assert_eq!(done.load(Ordering::Acquire) as usize, s);
                                    // Uneven work, so that the threads take from each other.
                                    if (piece.start / 16 + s + index) % 3 == 0 {
                                        std::thread::sleep(std::time::Duration::from_micros(20));
                                    }
                                    pieces.push(piece);
                                });
                                // The thread that finished the stage says so; the others wait for it
                                // (after `is_done`, which the test's own count may trail).
                                if left == Left::Finished {
                                    done.store(s as u32 + 1, Ordering::Release);
                                }
                                while (done.load(Ordering::Acquire) as usize) < s + 1 {
                                    std::hint::spin_loop();
                                }
                                mine.push(pieces);
                            }
                            mine
                        })
                    })
                    .collect();
                workers.into_iter().map(|w| w.join().expect("worker")).collect()
            });
            for (s, range) in stages.iter().cycle().take(60).enumerate() {
                let mut taken: Vec<Range<usize>> = taken.iter().flat_map(|t| t[s].iter().cloned()).collect();
                taken.sort_by_key(|p| p.start);
                assert_eq!(taken, pieces(range.clone(), 16), "{threads} threads, stage {s}");
            }
        }
    }

    /// A thread held up in its first piece loses the rest of its share to the other thread, which
    /// takes it from the back after its own share; the stage ends with the held-up piece.
    #[test]
    fn a_held_up_share_is_taken_from_its_back() {
        let shares = StageShares::new(2);
        // Thread 1 begins once thread 0 has taken its first piece; thread 0 goes on once thread 1
        // has left the stage.
        let (begun, left) = (Barrier::new(2), Barrier::new(2));
        let taken: Vec<(Vec<Range<usize>>, Left)> = std::thread::scope(|scope| {
            let workers: Vec<_> = (0..2)
                .map(|index| {
                    let (shares, begun, left) = (&shares, &begun, &left);
                    scope.spawn(move || {
                        let mut pieces = Vec::new();
                        if index == 1 {
                            begun.wait();
                        }
                        let leaves = shares.take_pieces(index, 0..640, 32, |piece| {
                            if index == 0 && pieces.is_empty() {
                                begun.wait();
                                left.wait();
                            }
                            pieces.push(piece);
                        });
                        if index == 1 {
                            left.wait();
                        }
                        (pieces, leaves)
                    })
                })
                .collect();
            workers.into_iter().map(|w| w.join().expect("worker")).collect()
        });
        let chunk = |k: usize| 32 * k..32 * (k + 1);
        assert_eq!(taken[0], (vec![chunk(0)], Left::Finished));
        let own = (10..20).map(chunk);
        let from_the_back = (1..10).rev().map(chunk);
        assert_eq!(taken[1], (own.chain(from_the_back).collect::<Vec<_>>(), Left::Waiting(1)));
        assert!(shares.is_done(1));
    }

    /// A thread that has not begun a stage holds nothing up: the other does every piece, and the
    /// late thread finds the stages done when it comes to them.
    #[test]
    fn a_late_thread_finds_its_stages_done() {
        let shares = StageShares::new(2);
        for stage in 0..5 {
            let mut pieces = Vec::new();
            let left = shares.take_pieces(0, stage..1_000, 64, |piece| pieces.push(piece));
            assert_eq!(left, Left::Finished);
            pieces.sort_by_key(|p| p.start);
            assert_eq!(pieces, self::pieces(stage..1_000, 64));
        }
        // Thread 1 was waited for once, then taken from at once.
        assert!(shares.shares[1].away.load(Ordering::Relaxed));
        for stage in 0..5 {
            let left = shares.take_pieces(1, stage..1_000, 64, |_| panic!("a piece of a stage done"));
            assert_eq!(left, Left::Done);
        }
        // Both go on together; thread 1 is back.
        let left = shares.take_pieces(1, 0..10, 64, |_| {});
        assert_eq!(left, Left::Finished);
        assert!(!shares.shares[1].away.load(Ordering::Relaxed));
        assert_eq!(shares.take_pieces(0, 0..10, 64, |_| panic!("taken")), Left::Done);
    }

    /// More pieces than a share's word holds: larger pieces, each still a run of whole chunks.
    #[test]
    fn a_long_range_is_cut_into_larger_pieces() {
        let shares = StageShares::new(1);
        let mut pieces = Vec::new();
        let range = 4..(MAX_PIECES * 32 * 3 + 7);
        assert_eq!(shares.take_pieces(0, range.clone(), 32, |piece| pieces.push(piece)), Left::Finished);
        assert!(pieces.len() < MAX_PIECES);
        assert_eq!(pieces.first().map(|p| p.start), Some(range.start));
        assert!(pieces.windows(2).all(|w| w[0].end == w[1].start && w[1].start % 32 == 0));
        assert_eq!(pieces.last().map(|p| p.end), Some(range.end));
    }
}
