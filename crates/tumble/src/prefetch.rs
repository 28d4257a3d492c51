//! A hint to the processor to start loading a value's memory into the cache before it is read.
//!
//! The narrow phase and the solver's set-up walk the store of contacts, 896 bytes each, in order,
//! and the set-up writes each one's constraint (1,320 bytes) into its colour's place. The core
//! stalled on the first read of each contact: that stride is not one the hardware prefetchers
//! follow. Asking for the contact (and its constraint's place) a few places ahead lets those
//! loads overlap the work on the current ones: the rain's narrow phase ran about a quarter
//! faster, the large pyramid's set-up a fifth (docs/solver.md, "Prefetching the contacts"). A
//! hint changes no result.
#![allow(unsafe_code)] // `_mm_prefetch`: a hint, which never faults.

/// Cache line size assumed, bytes.
const LINE: usize = 64;

/// Starts loading every cache line of `value` (no effect on other targets).
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    prefetch_at(value as *const T);
}

/// Starts loading every cache line of a `T` at `address` (which need not be valid: nothing is
/// read).
#[inline(always)]
pub(crate) fn prefetch_at<T>(address: *const T) {
    prefetch_span(address.cast(), std::mem::size_of::<T>().div_ceil(LINE));
}

/// Starts loading the first `lines` cache lines of `value`.
#[inline(always)]
pub(crate) fn prefetch_lines<T>(value: &T, lines: usize) {
    prefetch_span((value as *const T).cast(), lines.min(std::mem::size_of::<T>().div_ceil(LINE)));
}

/// Starts loading `lines` cache lines from `start`.
#[inline(always)]
fn prefetch_span(start: *const u8, lines: usize) {
    for line in 0..lines {
        prefetch_line(start.wrapping_add(line * LINE));
    }
}

#[inline(always)]
fn prefetch_line(address: *const u8) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads nothing into the program and cannot fault, whatever the address;
    // the `sse` feature it needs is part of every x86-64 target.
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>(address.cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}
