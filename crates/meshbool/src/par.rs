//! Helpers for work spread over threads on large arrays: fresh memory filled side by
//! side, parts concatenated side by side, and the offsets and slices of consecutive parts
//! (the count-then-fill pattern of the stages that write their output in parallel).
//!
//! Also the serial mode of small calls ([`serially`]): their parallel steps ([`join`],
//! iterators cut no finer than [`Grain::grained`]) run one after another on the calling
//! thread, which need not be one of rayon's workers; and where a call runs: in a pool of
//! its threads ([`with_threads`]), serially below [`SERIAL_BELOW`] triangles, moved into
//! the current pool once ([`run_for`]). Below the pipeline, which runs its entry points
//! through it; the front door ([`crate::ops`]) re-exports the public part.

use std::cell::Cell;

use rayon::iter::MinLen;
use rayon::prelude::*;

use crate::{Error, Result};

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

/// Runs `f` in a pool of `threads` worker threads (`None` or `Some(0)`: the current
/// pool). A call already on a worker of a pool that size runs directly. Errors when
/// `threads` is over [`RunOptions::MAX_THREADS`](crate::ops::RunOptions::MAX_THREADS) or
/// the threads cannot be started.
pub fn with_threads<R: Send>(threads: Option<usize>, f: impl FnOnce() -> R + Send) -> Result<R> {
    check_threads(threads)?;
    let n = match threads {
        // Inside a small call ([`with_threads_for`]): serial on this thread, as it is.
        _ if is_serial() => return Ok(f()),
        None | Some(0) => return Ok(in_current_pool(f)),
        Some(n) => n,
    };
    if rayon::current_thread_index().is_some() && rayon::current_num_threads() == n {
        return Ok(f());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| Error::InvalidParameter(format!("cannot start {n} threads: {e}")))?;
    Ok(pool.install(|| awake(f)))
}

/// Calls on fewer triangles than this (their meshes together) run serially on the
/// calling thread, whatever their threads: moving a call into a pool and back, and
/// handing its steps to other threads, costs more than those steps save. Measured on 2
/// cores: two cubes of 12 triangles, 71 µs serially against 117 µs on two threads (130
/// µs moved into the pool from outside); 48 + 48 triangles, 83 against 93 (111); 192 +
/// 192, even; 768 + 768, 957 against 555.
pub const SERIAL_BELOW: usize = 256;

/// [`with_threads`] for a call on `triangles` triangles in all: under [`SERIAL_BELOW`],
/// `f` runs serially on the calling thread (after the same check of `threads`).
pub(crate) fn with_threads_for<R: Send>(
    threads: Option<usize>,
    triangles: usize,
    f: impl FnOnce() -> R + Send,
) -> Result<R> {
    if triangles < SERIAL_BELOW {
        check_threads(threads)?;
        return Ok(serially(f));
    }
    with_threads(threads, f)
}

/// Runs `f`, a call on `triangles` triangles in all, as [`with_threads_for`] does with
/// the default threads: serially on this thread under [`SERIAL_BELOW`], else on a worker
/// of the current pool (moved there once from outside). For the pipeline's own entry
/// points ([`crate::boolean::boolean`]), called directly from outside a pool: there every
/// parallel step would otherwise wake the pool from outside.
pub(crate) fn run_for<R: Send>(triangles: usize, f: impl FnOnce() -> R + Send) -> R {
    if triangles < SERIAL_BELOW || is_serial() {
        serially(f)
    } else {
        in_current_pool(f)
    }
}

/// Runs `f` on a worker of the current pool: directly on one, else moved there once
/// from outside, so that its many parallel steps start as local tasks rather than each
/// waking the pool from outside (tens of microseconds each: most of a small boolean),
/// with the pool's other workers kept awake ([`awake`]).
fn in_current_pool<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    if rayon::current_thread_index().is_some() {
        f()
    } else {
        rayon::scope(|_| awake(f))
    }
}

/// The most worker threads a call may ask for
/// ([`RunOptions::MAX_THREADS`](crate::ops::RunOptions::MAX_THREADS)).
pub(crate) const MAX_THREADS: usize = 1024;

/// An error for more threads than [`MAX_THREADS`].
fn check_threads(threads: Option<usize>) -> Result<()> {
    match threads {
        Some(n) if n > MAX_THREADS => Err(Error::InvalidParameter(format!(
            "threads must be at most {MAX_THREADS}, got {n}"
        ))),
        _ => Ok(()),
    }
}

/// How long a worker kept awake by [`awake`] waits without finding work before it
/// goes back to the pool's own idling (and sleep).
const AWAKE_IDLE: std::time::Duration = std::time::Duration::from_micros(500);

/// Runs `f` on the current worker with the pool's other workers kept awake: each takes a
/// task that looks for work (`rayon::yield_now`) until `f` is done, instead of going to
/// sleep in `f`'s serial steps and waking for its next parallel one (a woken thread
/// took about 20 µs on a 2-core virtual machine, a parallel step a few tens). Only for a
/// call that has just moved into its pool ([`with_threads`]): a call made from inside
/// parallel work, where the other workers are busy, leaves them as they are. A task
/// that finds no work for [`AWAKE_IDLE`] ends early, so that one taken late, by a worker
/// waiting inside `f`'s own work, holds that work back no longer than that; one taken
/// by `f`'s own thread ends at once.
fn awake<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    use std::sync::atomic::{AtomicBool, Ordering};
    let n = rayon::current_num_threads();
    let Some(me) = rayon::current_thread_index().filter(|_| n > 1) else {
        return f();
    };
    let done = AtomicBool::new(false);
    rayon::scope(|s| {
        for _ in 1..n {
            s.spawn(|_| {
                if rayon::current_thread_index() == Some(me) {
                    return;
                }
                let mut last = web_time::Instant::now();
                while !done.load(Ordering::Acquire) {
                    if rayon::yield_now() == Some(rayon::Yield::Executed) {
                        last = web_time::Instant::now();
                    } else if last.elapsed() > AWAKE_IDLE {
                        return;
                    } else {
                        std::hint::spin_loop();
                    }
                }
            });
        }
        let r = f();
        done.store(true, Ordering::Release);
        r
    })
}
