//! A counting global allocator: live bytes, their peak since the last reset, and a hard cap
//! past which an allocation fails (and the process aborts, after saying which case asked).
//!
//! Install it in a binary or test with
//! `#[global_allocator] static ALLOC: splinekit_fuzz::alloc::Counting = splinekit_fuzz::alloc::Counting;`.
//! Without it the harness still runs; it then measures no memory.

// Implementing `GlobalAlloc` is unsafe by definition: this is the workspace's third audited
// exception to `unsafe_code` (with the CLI's allocator and the core's AVX2 dispatch). Every
// call passes its arguments on to `System` unchanged; the counters are plain atomics.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::io::Write;
use std::sync::atomic::{AtomicU8, AtomicUsize, Ordering};

/// The counting allocator (a unit struct wrapping [`System`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static CAP: AtomicUsize = AtomicUsize::new(usize::MAX);
/// What to print when the cap is hit: set by the harness before each case.
static LABEL: [AtomicU8; 200] = [const { AtomicU8::new(0) }; 200];
static LABEL_LEN: AtomicUsize = AtomicUsize::new(0);

/// Counts `size` more live bytes, or refuses them past the cap.
fn grow(size: usize) -> bool {
    let live = LIVE.fetch_add(size, Ordering::Relaxed).saturating_add(size);
    if live > CAP.load(Ordering::Relaxed) {
        LIVE.fetch_sub(size, Ordering::Relaxed);
        over_cap(size);
        return false;
    }
    PEAK.fetch_max(live, Ordering::Relaxed);
    true
}

fn shrink(size: usize) {
    LIVE.fetch_sub(size, Ordering::Relaxed);
}

/// Says which case went past the cap (no allocation: a stack buffer to unbuffered stderr).
fn over_cap(size: usize) {
    let mut buf = [0u8; 200];
    let n = LABEL_LEN.load(Ordering::Relaxed).min(buf.len());
    for (b, a) in buf.iter_mut().zip(&LABEL[..n]) {
        *b = a.load(Ordering::Relaxed);
    }
    let mut err = std::io::stderr();
    let _ = err.write_all(b"\nsplinekit-fuzz: the hard memory cap refused an allocation of ");
    let mut digits = [0u8; 20];
    let mut i = digits.len();
    let mut v = size;
    loop {
        i -= 1;
        digits[i] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    let _ = err.write_all(&digits[i..]);
    let _ = err.write_all(b" bytes in ");
    let _ = err.write_all(&buf[..n]);
    let _ = err.write_all(b"\n");
}

/// `allocate()`'s block of `size` bytes, counted; null past the cap or when it fails.
fn counted(size: usize, allocate: impl FnOnce() -> *mut u8) -> *mut u8 {
    if !grow(size) {
        return std::ptr::null_mut();
    }
    let p = allocate();
    if p.is_null() {
        shrink(size);
    }
    p
}

// SAFETY (all four methods): the layout and pointers are passed to `System` unchanged, and
// the counters never affect what is allocated, only whether an allocation is attempted.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as for `GlobalAlloc::alloc`, the caller's layout is valid.
        counted(layout.size(), || unsafe { System.alloc(layout) })
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as for `GlobalAlloc::alloc_zeroed`.
        counted(layout.size(), || unsafe { System.alloc_zeroed(layout) })
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` was allocated by `System` with `layout` (every path above).
        unsafe { System.dealloc(ptr, layout) };
        shrink(layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old && !grow(new_size - old) {
            return std::ptr::null_mut();
        }
        // SAFETY: as for `GlobalAlloc::realloc`: `ptr` came from `System` with `layout`.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            if new_size > old {
                shrink(new_size - old);
            }
        } else if new_size < old {
            shrink(old - new_size);
        }
        p
    }
}

/// Bytes allocated and not yet freed.
pub fn live() -> usize {
    LIVE.load(Ordering::Relaxed)
}

/// The most live bytes since the last [`reset_peak`].
pub fn peak() -> usize {
    PEAK.load(Ordering::Relaxed)
}

/// Starts a new peak at the current live bytes.
pub fn reset_peak() {
    PEAK.store(live(), Ordering::Relaxed);
}

/// Refuses allocations that would take the live bytes past `bytes` (`usize::MAX`: no cap).
pub fn set_cap(bytes: usize) {
    CAP.store(bytes, Ordering::Relaxed);
}

/// The text printed if the cap is hit (the case and how to replay it); at most 200 bytes.
pub fn set_label(text: &str) {
    let bytes = text.as_bytes();
    let n = bytes.len().min(LABEL.len());
    for (a, &b) in LABEL.iter().zip(&bytes[..n]) {
        a.store(b, Ordering::Relaxed);
    }
    LABEL_LEN.store(n, Ordering::Relaxed);
}

/// Whether [`Counting`] is the global allocator (allocating moves the count).
pub fn is_installed() -> bool {
    let before = live();
    let probe = std::hint::black_box(vec![0u8; 4096]);
    let after = live();
    drop(probe);
    after >= before + 4096
}
