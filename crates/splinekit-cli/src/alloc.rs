//! The process's allocator: the system allocator for small blocks; large blocks mapped by
//! themselves on 2 MiB boundaries and backed by transparent huge pages.
//!
//! Subdividing a mesh writes hundreds of megabytes of fresh memory (3 Loop levels of a
//! 100k-triangle torus: 154 MB of output alone). With 4 KiB pages every first touch is a page
//! fault, and on this kind of virtual machine faults cost more than the subdivision itself
//! (about 2.3 GB/s against 10–12 GB/s for memory already mapped); 2 MiB pages cost 512 times
//! fewer faults and clear at about 7 GB/s. The kernel maps a huge page only where a whole
//! aligned 2 MiB range lies inside the mapping, which the system allocator's blocks (16 bytes
//! past an arbitrary page) rarely give: so every block of [`LARGE`] bytes or more gets a
//! mapping of its own, rounded up to whole 2 MiB pages and starting on a 2 MiB boundary, with
//! `madvise(MADV_HUGEPAGE)`. Even a 1 MiB block is cheaper to fault as one huge page than as
//! 256 small ones. Where transparent huge pages are off
//! (`/sys/kernel/mm/transparent_hugepage/enabled` = never) the advice does nothing and the
//! mappings behave as the system allocator's own large blocks (which it maps the same way).
//!
//! Inside [`recycling`] (the CLI wraps one subdivision in it), a large block that is freed
//! is kept mapped, and the next large allocation takes the kept mappings over (moved into
//! place with `mremap`, so their pages are not faulted and cleared again) before mapping
//! fresh pages for the rest: one Loop level's parent buffers become its child's. Whatever is
//! still kept when `recycling` returns is unmapped, so nothing carries over from one call to
//! the next. Zeroed allocations never take kept pages (they hold old contents).
//!
//! Small blocks stay with the system allocator, told by [`keep_small_blocks`] to keep freed
//! memory rather than hand it back, so repeated subdivisions do not fault the same small
//! pages in again.
//!
//! This and the core's runtime dispatch (`splinekit/src/wide.rs`) are the workspace's only
//! unsafe code: implementing [`GlobalAlloc`] is unsafe by definition, and `mmap`, `mremap`,
//! `munmap`, `madvise` and `mallopt` are foreign functions.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, PoisonError};

/// Blocks at least this large get a huge-page mapping of their own.
const LARGE: usize = 1 << 20;

/// The huge page size (x86-64, aarch64 with 4 KiB base pages).
const HUGE: usize = 2 << 20;

/// Whether freed large blocks are kept for reuse (see [`recycling`]).
static RECYCLE: AtomicBool = AtomicBool::new(false);

/// The kept mappings, `(start, length)`, lengths whole huge pages.
static KEPT: Mutex<Kept> = Mutex::new(Kept { blocks: [(0, 0); KEPT_MAX], len: 0 });

/// At most this many mappings are kept; more are unmapped when freed.
const KEPT_MAX: usize = 32;

/// A fixed-size list: the allocator must not allocate.
struct Kept {
    blocks: [(usize, usize); KEPT_MAX],
    len: usize,
}

/// Runs `f` with freed large blocks kept and reused by later large allocations, then unmaps
/// the blocks still kept. Blocks allocated inside and alive after are unaffected. The switch
/// is process-wide: not for nested or concurrent calls.
pub fn recycling<R>(f: impl FnOnce() -> R) -> R {
    struct Stop;
    impl Drop for Stop {
        fn drop(&mut self) {
            RECYCLE.store(false, Ordering::SeqCst);
            let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
            for &(start, len) in &kept.blocks[..kept.len] {
                // SAFETY: a kept block is a mapping of ours that no one uses.
                unsafe {
                    libc::munmap(start as *mut libc::c_void, len);
                }
            }
            kept.len = 0;
        }
    }
    RECYCLE.store(true, Ordering::SeqCst);
    let _stop = Stop;
    f()
}

/// Keeps the system allocator's freed small blocks (below [`LARGE`]) for reuse instead of
/// handing their pages back: blocks from 128 KiB up are then carved from its heap rather
/// than mapped one by one, and freed memory at the top of a heap is no longer returned with
/// `MADV_DONTNEED` past 128 KiB, so a worker thread's heap does not fault its pages in again
/// on every subdivision (about 480 small-page faults, ~2 MB, per run of 3 Loop levels of a
/// 20k-triangle icosphere on one thread without it). Call once, before the first
/// allocation of a thread other than `main`'s. On other C libraries than glibc, nothing.
pub fn keep_small_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` only sets two of glibc's tuning values; no memory is touched.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, LARGE as libc::c_int);
        libc::mallopt(libc::M_TRIM_THRESHOLD, (64 * LARGE) as libc::c_int);
    }
}

/// [`System`], plus 2 MiB-aligned huge-page mappings for large blocks.
pub struct HugePageAlloc;

/// Whether a block of `layout` is one of ours.
fn mapped(layout: Layout) -> bool {
    layout.size() >= LARGE && layout.align() <= HUGE
}

/// The length of the mapping of a block of `size` bytes.
fn mapping_len(size: usize) -> usize {
    size.next_multiple_of(HUGE)
}

/// A mapping of `mapping_len(size)` bytes on a 2 MiB boundary, or null: the kept blocks
/// moved to its start when `reuse` (their old contents stay), fresh zero pages after them.
fn map(size: usize, reuse: bool) -> *mut u8 {
    let len = mapping_len(size);
    let Some(reserve) = len.checked_add(HUGE) else { return core::ptr::null_mut() };
    // SAFETY: a new private anonymous mapping; it aliases nothing.
    let p = unsafe {
        libc::mmap(
            core::ptr::null_mut(),
            reserve,
            libc::PROT_READ | libc::PROT_WRITE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
            -1,
            0,
        )
    };
    if p == libc::MAP_FAILED {
        return core::ptr::null_mut();
    }
    let base = p as usize;
    let start = base.next_multiple_of(HUGE);
    let end = start + len;
    // SAFETY: the head `[base, start)` and tail `[end, base + reserve)` are parts of the
    // mapping just made that the block does not use; unmapping them touches nothing else.
    unsafe {
        if start > base {
            libc::munmap(base as *mut libc::c_void, start - base);
        }
        if base + reserve > end {
            libc::munmap(end as *mut libc::c_void, base + reserve - end);
        }
        // Advice only: failure (e.g. huge pages off) leaves ordinary pages.
        libc::madvise(start as *mut libc::c_void, len, libc::MADV_HUGEPAGE);
    }
    if reuse && RECYCLE.load(Ordering::Relaxed) {
        take_kept(start, len);
    }
    start as *mut u8
}

/// Moves kept blocks, largest first, over the start of the fresh mapping `[start, start +
/// len)` while they fit, so that their pages (already faulted in) serve it; a block that does
/// not move stays kept.
fn take_kept(start: usize, len: usize) {
    let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
    let mut at = start;
    loop {
        let room = start + len - at;
        let Some(k) = (0..kept.len).filter(|&k| kept.blocks[k].1 <= room).max_by_key(|&k| kept.blocks[k].1) else {
            break;
        };
        let (from, n) = kept.blocks[k];
        // SAFETY: `[from, from + n)` is a kept mapping no one uses, and `[at, at + n)` lies
        // inside the fresh mapping, which no one uses yet either: MREMAP_FIXED replaces those
        // fresh pages by the kept ones and unmaps the kept range.
        let moved = unsafe {
            libc::mremap(
                from as *mut libc::c_void,
                n,
                n,
                libc::MREMAP_MAYMOVE | libc::MREMAP_FIXED,
                at as *mut libc::c_void,
            )
        };
        if moved == libc::MAP_FAILED {
            break;
        }
        kept.len -= 1;
        kept.blocks[k] = kept.blocks[kept.len];
        at += n;
    }
}

/// Unmaps a block's mapping, or keeps it while [`recycling`] runs.
fn unmap(ptr: *mut u8, len: usize) {
    if RECYCLE.load(Ordering::Relaxed) {
        let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
        if kept.len < KEPT_MAX {
            let k = kept.len;
            kept.blocks[k] = (ptr as usize, len);
            kept.len += 1;
            return;
        }
    }
    // SAFETY: `[ptr, ptr + len)` is a whole mapping of ours that no one uses any more.
    unsafe {
        libc::munmap(ptr.cast(), len);
    }
}

// SAFETY: small blocks are `System`'s, with the caller's arguments. A large block is a
// private mapping of its own, of at least `layout.size()` bytes aligned to 2 MiB (so to
// `layout.align()`), zeroed by the kernel unless it took over kept blocks (never for
// `alloc_zeroed`), owned by the block until `dealloc` unmaps or keeps exactly that mapping
// (its length follows from the same layout). `realloc` copies between blocks of either kind.
unsafe impl GlobalAlloc for HugePageAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if mapped(layout) {
            map(layout.size(), true)
        } else {
            // SAFETY: the caller's contract for `alloc` is passed on unchanged.
            unsafe { System.alloc(layout) }
        }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if mapped(layout) {
            map(layout.size(), false) // fresh anonymous memory is zero
        } else {
            // SAFETY: as `alloc`.
            unsafe { System.alloc_zeroed(layout) }
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if mapped(layout) {
            // `ptr` is the start of the mapping `map` made for this block, of this length,
            // and the block is no longer used.
            unmap(ptr, mapping_len(layout.size()));
        } else {
            // SAFETY: `ptr` came from `System` through this allocator, with this layout.
            unsafe { System.dealloc(ptr, layout) }
        }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller guarantees `new_size` is valid for `layout`'s alignment.
        let new_layout = unsafe { Layout::from_size_align_unchecked(new_size, layout.align()) };
        match (mapped(layout), mapped(new_layout)) {
            // SAFETY: both blocks are `System`'s: the caller's contract is passed on.
            (false, false) => unsafe { System.realloc(ptr, layout, new_size) },
            (true, true) if mapping_len(new_size) == mapping_len(layout.size()) => ptr,
            _ => {
                // SAFETY: a new block of the new layout; the old one stays valid until the
                // copy of the bytes both hold is done, then is freed with its own layout.
                unsafe {
                    let new = self.alloc(new_layout);
                    if !new.is_null() {
                        core::ptr::copy_nonoverlapping(ptr, new, layout.size().min(new_size));
                        self.dealloc(ptr, layout);
                    }
                    new
                }
            }
        }
    }
}
