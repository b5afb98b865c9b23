//! Helpers for work spread over threads on large arrays: fresh memory filled side by
//! side, parts concatenated side by side, and the offsets and slices of consecutive parts
//! (the count-then-fill pattern of the stages that write their output in parallel).
//!
//! Also the serial mode of small calls ([`serially`]): their parallel steps ([`join`],
//! iterators cut no finer than [`Grain::grained`]) run one after another on the calling
//! thread, which need not be one of rayon's workers.

use std::cell::Cell;

use rayon::iter::MinLen;
use rayon::prelude::*;

thread_local! {
    /// Whether this thread runs its parallel steps serially ([`serially`]).
    static SERIAL: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` with this thread's parallel steps run serially on it: [`join`] calls one
/// closure after the other and iterators made [`Grain::grained`] stay in one piece, so
/// none of them touches a pool. For small inputs, where handing a step to another thread
/// (and, from outside a pool, moving the whole call into it and back) costs more than
/// the step itself.
pub(crate) fn serially<R>(f: impl FnOnce() -> R) -> R {
    /// Puts the flag back as it was, also when `f` panics.
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            SERIAL.with(|s| s.set(self.0));
        }
    }
    let _restore = Restore(SERIAL.with(|s| s.replace(true)));
    f()
}

/// Whether this thread runs its parallel steps serially ([`serially`]).
pub(crate) fn is_serial() -> bool {
    SERIAL.with(Cell::get)
}

/// `rayon::join`, or `a` then `b` on this thread when it runs serially ([`serially`]).
pub(crate) fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
where
    A: FnOnce() -> RA + Send,
    B: FnOnce() -> RB + Send,
    RA: Send,
    RB: Send,
{
    if is_serial() {
        (a(), b())
    } else {
        rayon::join(a, b)
    }
}

/// A parallel iterator kept in one piece (on the calling thread, with no pool touched)
/// when this thread runs serially ([`serially`]); as it was otherwise.
pub(crate) trait Grain: IndexedParallelIterator {
    /// This iterator, cut into no pieces when the thread runs serially.
    fn grained(self) -> MinLen<Self> {
        self.with_min_len(if is_serial() { usize::MAX } else { 1 })
    }
}

impl<I: IndexedParallelIterator> Grain for I {}

/// Each element's sum of the elements before it: where each of consecutive parts of
/// these sizes starts.
pub(crate) fn exclusive_sums(counts: &[usize]) -> Vec<usize> {
    let mut sum = 0;
    counts
        .iter()
        .map(|&c| {
            sum += c;
            sum - c
        })
        .collect()
}

/// `n` copies of `value` in fresh memory, written side by side on large sizes and several
/// threads: there a serial fill (the first touch of fresh pages, or the allocator's
/// zeroing of reused ones) is a serial part of the stage that asks for the memory. On one
/// thread, `vec!` (zeroed pages come from the allocator without a pass of their own).
pub(crate) fn filled<T: Clone + Send + Sync>(value: T, n: usize) -> Vec<T> {
    if n < 1 << 16 || rayon::current_num_threads() == 1 {
        return vec![value; n];
    }
    let mut v = Vec::with_capacity(n);
    v.par_extend(rayon::iter::repeat_n(value, n));
    v
}

/// The vectors one after another, copied side by side into [`filled`] memory (one is
/// taken as it is).
pub(crate) fn concat<T: Copy + Default + Send + Sync>(mut parts: Vec<Vec<T>>) -> Vec<T> {
    if parts.len() == 1 {
        return parts.pop().unwrap_or_default();
    }
    let lengths: Vec<usize> = parts.iter().map(|p| p.len()).collect();
    let mut out = filled(T::default(), lengths.iter().sum());
    split_by(&mut out, &lengths)
        .into_par_iter()
        .zip(parts)
        .for_each(|(to, from)| to.copy_from_slice(&from));
    out
}

/// `v` cut into consecutive slices of the given lengths (which must add up to at most its
/// length).
pub(crate) fn split_by<'v, T>(mut v: &'v mut [T], lengths: &[usize]) -> Vec<&'v mut [T]> {
    lengths
        .iter()
        .map(|&n| {
            let (head, rest) = std::mem::take(&mut v).split_at_mut(n);
            v = rest;
            head
        })
        .collect()
}
