//! How the solver's threads share one colour's constraints so that neither waits long at the
//! barrier that ends the stage: each thread starts on its own contiguous share, taken a chunk at a
//! time from the front, and a thread that has finished its own takes chunks from the back of the
//! others' shares until none is left.
//!
//! Equal counts are not equal work. A still manifold in a group of four costs a fraction of one
//! solved alone (contact_lanes.rs), and whether a group goes together is only known when it is
//! solved; a colour ordered by body (colouring.rs) has the settled base of a pyramid in one half
//! and its moving top in the other. Split by count, the threads of the 5,050-box pyramid waited
//! at the colours' barriers for a fifth of the substeps' time, most of it in waits of 0.1–0.5 ms.
//!
//! Which thread solves which chunk changes no number: a colour's constraints share no moving
//! body. A thread still works its own share first, from the front, so it keeps the bodies it
//! worked on in the last colour (the reason for the order by body); the chunks it takes from
//! another share are that share's last, next to its own bodies.
//!
//! Each share's remaining chunks are one atomic word, `front..back` and the number of the stage
//! it belongs to, which its owner writes as the stage begins and every thread advances by
//! compare-and-swap: the owner its front, the others its back. A thread that reads a share of an
//! earlier stage (its owner has not begun this one) leaves it alone; every share of an earlier
//! stage is used up, as that stage's barrier was passed.

use std::ops::Range;
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};

/// Bits of a chunk index in a share's word (front and back), and of the stage number.
const INDEX_BITS: u32 = 24;
const INDEX_MASK: u64 = (1 << INDEX_BITS) - 1;
const STAGE_MASK: u64 = (1 << (64 - 2 * INDEX_BITS)) - 1;

/// One thread's share of the current stage, on its own cache line (the owner takes from it at
/// every chunk; another thread only once it has finished its own).
#[repr(align(128))]
#[derive(Default)]
struct Share {
    /// `stage << 48 | front << 24 | back`: chunks `front..back` of stage `stage` are left.
    word: AtomicU64,
    /// The number of shared stages this share's thread has begun (written by it alone).
    stages_begun: AtomicU32,
}

/// The shares of the solver's threads, one per thread.
pub(crate) struct StageShares {
    shares: Box<[Share]>,
}

fn pack(stage: u64, chunks: Range<u64>) -> u64 {
    (stage & STAGE_MASK) << (2 * INDEX_BITS) | chunks.start << INDEX_BITS | chunks.end
}

fn unpack(word: u64) -> (u64, Range<u64>) {
    (word >> (2 * INDEX_BITS), (word >> INDEX_BITS) & INDEX_MASK..word & INDEX_MASK)
}

/// Which end of a share a thread takes its next chunk from.
#[derive(Clone, Copy)]
enum End {
    Front,
    Back,
}

impl StageShares {
    pub fn new(threads: usize) -> Self {
        StageShares { shares: (0..threads).map(|_| Share::default()).collect() }
    }

    /// Calls `f` on the chunks of `range` this thread (`index` of the `shares.len()` threads)
    /// takes: `range` cut at the multiples of `chunk`, every piece to exactly one thread, when all
    /// the threads call this for the same stage with the same `range` and `chunk` (and each of
    /// them calls it for every shared stage, in the same order). Returns after this thread's own
    /// share is done and no chunk is left in any other share; chunks another thread took may
    /// still be in its hands, so the stage ends at a barrier.
    pub fn take_chunks(
        &self,
        index: usize,
        range: Range<usize>,
        chunk: usize,
        mut f: impl FnMut(Range<usize>),
    ) {
        let count = self.shares.len();
        if range.is_empty() {
            return;
        }
        let piece = |k: u64| {
            let k = k as usize;
            (k * chunk).max(range.start)..((k + 1) * chunk).min(range.end)
        };
        let chunks = range.start / chunk..range.end.div_ceil(chunk);
        let own =
            chunks.start + chunks.len() * index / count..chunks.start + chunks.len() * (index + 1) / count;
        if chunks.end as u64 > INDEX_MASK {
            // More chunks than a word holds: the static share alone.
            own.map(|k| piece(k as u64)).filter(|p| !p.is_empty()).for_each(f);
            return;
        }
        let share = &self.shares[index];
        let stage = u64::from(share.stages_begun.load(Ordering::Relaxed).wrapping_add(1));
        share.stages_begun.store(stage as u32, Ordering::Relaxed);
        share.word.store(pack(stage, own.start as u64..own.end as u64), Ordering::Release);
        while let Some(k) = Self::take(share, stage, End::Front) {
            f(piece(k));
        }
        for other in (1..count).map(|step| &self.shares[(index + step) % count]) {
            while let Some(k) = Self::take(other, stage, End::Back) {
                f(piece(k));
            }
        }
    }

    /// Takes the chunk at `end` of `share` if it belongs to `stage` and has one left.
    fn take(share: &Share, stage: u64, end: End) -> Option<u64> {
        let mut word = share.word.load(Ordering::Acquire);
        loop {
            let (of_stage, left) = unpack(word);
            if of_stage != stage & STAGE_MASK || left.is_empty() {
                return None;
            }
            let (taken, rest) = match end {
                End::Front => (left.start, left.start + 1..left.end),
                End::Back => (left.end - 1, left.start..left.end - 1),
            };
            match share.word.compare_exchange_weak(
                word,
                pack(stage, rest),
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

    /// Every piece of every stage goes to exactly one thread, whatever the timing, and the pieces
    /// are `range` cut at the multiples of the chunk.
    #[test]
    fn every_chunk_goes_to_exactly_one_thread() {
        for threads in 1..=4 {
            let shares = StageShares::new(threads);
            let barrier = Barrier::new(threads);
            let stages = [5..5, 3..1_000, 0..64, 17..18, 1..129, 100..10_000];
            let taken: Vec<Vec<Vec<Range<usize>>>> = std::thread::scope(|scope| {
                let workers: Vec<_> = (0..threads)
                    .map(|index| {
                        let (shares, barrier, stages) = (&shares, &barrier, &stages);
                        scope.spawn(move || {
                            let mut mine = Vec::new();
                            for (s, range) in stages.iter().cycle().take(60).enumerate() {
                                let mut pieces = Vec::new();
                                shares.take_chunks(index, range.clone(), 16, |piece| {
                                    // Uneven work, so that the threads take from each other.
                                    if (piece.start / 16 + s + index) % 3 == 0 {
                                        std::thread::sleep(std::time::Duration::from_micros(20));
                                    }
                                    pieces.push(piece);
                                });
                                mine.push(pieces);
                                barrier.wait();
                            }
                            mine
                        })
                    })
                    .collect();
                workers.into_iter().map(|w| w.join().expect("worker")).collect()
            });
            for (s, range) in stages.iter().cycle().take(60).enumerate() {
                let mut pieces: Vec<Range<usize>> = taken.iter().flat_map(|t| t[s].iter().cloned()).collect();
                pieces.sort_by_key(|p| p.start);
                let mut expected = Vec::new();
                let mut start = range.start;
                while start < range.end {
                    let end = ((start / 16 + 1) * 16).min(range.end);
                    expected.push(start..end);
                    start = end;
                }
                assert_eq!(pieces, expected, "{threads} threads, stage {s}");
            }
        }
    }

    /// A thread held up in its first chunk loses the rest of its share to the other thread, which
    /// takes it from the back after its own share.
    #[test]
    fn a_held_up_share_is_taken_from_its_back() {
        let shares = StageShares::new(2);
        // Thread 1 begins once thread 0 has begun the stage and taken its first chunk; thread 0
        // goes on once thread 1 has finished.
        let (begun, finished) = (Barrier::new(2), Barrier::new(2));
        let taken: Vec<Vec<Range<usize>>> = std::thread::scope(|scope| {
            let workers: Vec<_> = (0..2)
                .map(|index| {
                    let (shares, begun, finished) = (&shares, &begun, &finished);
                    scope.spawn(move || {
                        let mut pieces = Vec::new();
                        if index == 1 {
                            begun.wait();
                        }
                        shares.take_chunks(index, 0..640, 32, |piece| {
                            if index == 0 && pieces.is_empty() {
                                begun.wait();
                                finished.wait();
                            }
                            pieces.push(piece);
                        });
                        if index == 1 {
                            finished.wait();
                        }
                        pieces
                    })
                })
                .collect();
            workers.into_iter().map(|w| w.join().expect("worker")).collect()
        });
        let chunk = |k: usize| 32 * k..32 * (k + 1);
        assert_eq!(taken[0], [chunk(0)]);
        let own = (10..20).map(chunk);
        let from_the_back = (1..10).rev().map(chunk);
        assert_eq!(taken[1], own.chain(from_the_back).collect::<Vec<_>>());
    }
}
