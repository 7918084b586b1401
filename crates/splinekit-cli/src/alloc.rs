//! The process's allocator: the system allocator, asking the kernel to back large blocks
//! with transparent huge pages.
//!
//! Subdividing a mesh writes hundreds of megabytes of fresh memory (3 Loop levels of a
//! 100k-triangle torus: 154 MB of output alone). With 4 KiB pages every first touch is a page
//! fault, and on this kind of virtual machine faults cost more than the subdivision itself
//! (about 2.3 GB/s against 10–12 GB/s for memory already mapped). `madvise(MADV_HUGEPAGE)` on
//! blocks of 4 MiB and more lets the kernel map 2 MiB pages instead, 512 times fewer faults.
//! It is advice only: contents, addresses and lifetimes are the system allocator's, and where
//! transparent huge pages are off (`/sys/kernel/mm/transparent_hugepage/enabled` = never) it
//! does nothing.
//!
//! This is the workspace's only unsafe code: implementing [`GlobalAlloc`] is unsafe by
//! definition, and `madvise` is a foreign function.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};

/// Blocks at least this large get the huge-page advice.
const LARGE: usize = 4 << 20;

/// [`System`], plus `madvise(MADV_HUGEPAGE)` on large blocks.
pub struct HugePageAlloc;

/// Advises huge pages for the whole pages inside `[ptr, ptr + len)`.
fn advise(ptr: *mut u8, len: usize) {
    const PAGE: usize = 4096;
    let start = (ptr as usize).next_multiple_of(PAGE);
    let end = (ptr as usize + len) & !(PAGE - 1);
    if end > start {
        // SAFETY: the range lies inside a block the system allocator just handed out, and
        // MADV_HUGEPAGE changes neither its contents nor its mapping; failure is harmless.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
}

// SAFETY: every method forwards to `System` with the same arguments and returns its result;
// `advise` only gives advice about memory the returned block owns.
unsafe impl GlobalAlloc for HugePageAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract for `alloc` is passed on unchanged.
        let ptr = unsafe { System.alloc(layout) };
        if layout.size() >= LARGE && !ptr.is_null() {
            advise(ptr, layout.size());
        }
        ptr
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as `alloc`.
        let ptr = unsafe { System.alloc_zeroed(layout) };
        if layout.size() >= LARGE && !ptr.is_null() {
            advise(ptr, layout.size());
        }
        ptr
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System` through this allocator, with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: as `dealloc`; the caller guarantees `new_size` is valid for `layout`'s align.
        let new = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size >= LARGE && !new.is_null() {
            advise(new, new_size);
        }
        new
    }
}
