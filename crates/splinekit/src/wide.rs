//! Runtime dispatch to code compiled for the processor's wider instructions.
//!
//! The library is built for baseline x86-64 (SSE2), where `f64` arithmetic is two lanes wide
//! and `count_ones` is a dozen instructions. [`wide`] runs a closure compiled, where it is
//! inlined, for AVX2 (four `f64` lanes) and POPCNT when the processor has them, and as it is
//! otherwise. No FMA: LLVM never fuses a multiply and an add unless told to, and AVX2 alone
//! does the same IEEE operations in the same order, only more at a time, so both paths give
//! the same bits (the tests compare them on every machine that has AVX2, and CI's has).
//!
//! This module and the CLI's allocator are the workspace's only unsafe code: calling a
//! function compiled for features the caller was not compiled for is unsafe by definition;
//! here the features are checked at run time first.
#![allow(unsafe_code)]

/// Runs `f`, compiled for AVX2 and POPCNT when the processor has both (see the module docs).
/// Only the code inlined into `f` is compiled for them: mark the closure `#[inline(always)]`,
/// and the functions it calls that should be too. The check is two loads of a cached word.
#[inline(always)]
pub(crate) fn wide<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2,popcnt")]
        fn avx2<R>(f: impl FnOnce() -> R) -> R {
            f()
        }
        if has_avx2() {
            // SAFETY: the processor has AVX2 and POPCNT, the features `avx2` is compiled for.
            return unsafe { avx2(f) };
        }
    }
    f()
}

/// Whether [`wide`] takes the AVX2 path on this processor.
#[must_use]
pub(crate) fn has_avx2() -> bool {
    #[cfg(test)]
    if BASELINE.load(std::sync::atomic::Ordering::Relaxed) {
        return false;
    }
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Unit tests: [`wide`] takes the baseline path while this is set (process-wide; both paths
/// give the same bits, so other tests running meanwhile are unaffected).
#[cfg(test)]
pub(crate) static BASELINE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
