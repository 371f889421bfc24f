//! The binary's global allocator: the system's, with every large block
//! advised for transparent huge pages on Linux (`madvise(MADV_HUGEPAGE)`,
//! which most distributions leave to the program: `enabled = madvise`).
//!
//! A 1 M-triangle reference allocates some 500 MB in blocks of tens of MB
//! (the BVH builder's arrays, the shading data, the image); touched in 4 KB
//! pages that was about 150 000 page faults, and about a quarter of the
//! process's CPU time went to the kernel (0.32–0.37 s of 1.2 s). With this
//! allocator the same run faults about 36 000 times and spends 0.14–0.21 s
//! there (glibc's own `glibc.malloc.hugetlb=1` tunable, which advises every
//! block, gave the same kind of gain). Embree advises its BVH memory the
//! same way.

use std::alloc::{GlobalAlloc, Layout, System};

/// Blocks of this size or more are advised (smaller ones seldom hold a
/// whole aligned huge page).
const LARGE: usize = 4 << 20;
/// A huge page of x86-64 and most 64-bit Arm kernels.
const HUGE_PAGE: usize = 2 << 20;

/// [`System`], with blocks of `LARGE` bytes (4 MiB) or more advised for huge pages.
pub struct HugePages;

// SAFETY: every call goes to `System` with the caller's arguments; the
// advice only changes how the kernel backs the block's pages, never their
// contents or who owns them.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract, passed on.
        advised(unsafe { System.alloc(layout) }, layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract, passed on.
        advised(unsafe { System.alloc_zeroed(layout) }, layout.size())
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract, passed on.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller's contract, passed on.
        advised(unsafe { System.realloc(ptr, layout, new_size) }, new_size)
    }
}

/// `block` (of `size` bytes, or null) after advising the whole huge pages
/// inside it when it is large.
fn advised(block: *mut u8, size: usize) -> *mut u8 {
    if size >= LARGE && !block.is_null() {
        let start = (block as usize).next_multiple_of(HUGE_PAGE);
        let end = (block as usize + size) / HUGE_PAGE * HUGE_PAGE;
        if end > start {
            advise(start, end - start);
        }
    }
    block
}

#[cfg(target_os = "linux")]
fn advise(start: usize, length: usize) {
    // SAFETY: the range lies inside a block the allocator just handed out
    // and is page-aligned; the advice cannot fail in a way that matters (a
    // kernel without huge pages answers EINVAL and keeps small pages).
    unsafe {
        libc::madvise(start as *mut libc::c_void, length, libc::MADV_HUGEPAGE);
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_start: usize, _length: usize) {}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;

    /// The mapping of /proc/self/smaps that holds `address`: its VmFlags.
    fn flags_at(address: usize) -> String {
        let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap();
        let mut inside = false;
        for line in smaps.lines() {
            let range = line.split_whitespace().next().unwrap_or("");
            if let Some((lo, hi)) = range.split_once('-')
                && let (Ok(lo), Ok(hi)) = (usize::from_str_radix(lo, 16), usize::from_str_radix(hi, 16))
            {
                inside = (lo..hi).contains(&address);
            } else if inside && let Some(flags) = line.strip_prefix("VmFlags:") {
                return flags.to_string();
            }
        }
        panic!("no mapping holds {address:#x}");
    }

    /// A large block is advised ("hg" in its mapping's flags) and keeps its
    /// bytes through a growing and a shrinking realloc.
    #[test]
    fn large_blocks_are_advised_and_keep_their_bytes() {
        let layout = Layout::from_size_align(3 * LARGE, 64).unwrap();
        // SAFETY: a non-zero size; every block is freed with its layout.
        unsafe {
            let block = HugePages.alloc_zeroed(layout);
            assert!(!block.is_null());
            let middle = block as usize + layout.size() / 2;
            assert!(
                flags_at(middle).split_whitespace().any(|f| f == "hg"),
                "not advised"
            );
            for k in 0..layout.size() {
                *block.add(k) = k as u8;
            }
            let grown = HugePages.realloc(block, layout, 5 * LARGE);
            let layout = Layout::from_size_align(5 * LARGE, 64).unwrap();
            assert!((0..3 * LARGE).all(|k| *grown.add(k) == k as u8));
            let shrunk = HugePages.realloc(grown, layout, LARGE / 2);
            assert!((0..LARGE / 2).all(|k| *shrunk.add(k) == k as u8));
            HugePages.dealloc(shrunk, Layout::from_size_align(LARGE / 2, 64).unwrap());
        }
    }
}
